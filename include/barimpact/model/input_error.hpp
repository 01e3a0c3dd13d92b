// Bad input, the one exception every layer throws for it.
#pragma once

#include <stdexcept>
#include <string>

namespace barimpact {

/// Bad input: a case file, a `--set` override or an option that breaks a rule.
/// `what()` is one line naming the key (with file and line when known) and the
/// rule it breaks; the command line prints it and exits with status 2.
class InputError : public std::runtime_error {
 public:
  /// Control characters in `what` (quoted input: a key, a value, toml++'s
  /// excerpt) are escaped, so that the message stays one line.
  explicit InputError(const std::string& what);
};

}  // namespace barimpact
