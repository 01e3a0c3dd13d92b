// Bad input, the one exception every layer throws for it; and what the
// file system refused while results were written, which ends a command the
// same way (one line, exit 2).
#pragma once

#include <filesystem>
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

/// What the file system refused while barimpact wrote its results (a full
/// disk, a quota, a read-only mount, a file it cannot create): the file and
/// the system's reason ("No space left on device"). An InputError, so that
/// every command ends on it with one line and exit 2; by then whatever was
/// half-written has been removed.
class OutputError : public InputError {
 public:
  /// "cannot write PATH: REASON".
  OutputError(const std::filesystem::path& path, const std::string& reason);
  /// The caller's own message `what` for the same file and reason.
  OutputError(const std::string& what, const std::filesystem::path& path, const std::string& reason);

  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  [[nodiscard]] const std::string& reason() const { return reason_; }

 private:
  std::filesystem::path path_;
  std::string reason_;
};

/// A module of the install that a feature needs (signal matching's fitting
/// module) is not where the library looks: one line naming it and why, exit
/// 2 as a file the system refuses; Python raises it as an ImportError too.
class MissingModule : public InputError {
 public:
  using InputError::InputError;
};

/// A case that needs more memory than is available, refused before it is
/// built (run/check.hpp): bad input, which Python also raises as a
/// MemoryError (barimpact.OutOfMemoryError).
class MemoryRefusal : public InputError {
 public:
  using InputError::InputError;
};

}  // namespace barimpact
