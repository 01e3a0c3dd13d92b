// The run directory: history.csv, fields.csv, case.toml, summary.json,
// written into a hidden staging directory beside the target and renamed into
// place only when complete, so that no half-written result ever carries the
// target's name.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include "barimpact/case.hpp"
#include "barimpact/simulate.hpp"

namespace barimpact {

class RunDirectory {
 public:
  /// Checks that `target` can be written and creates the staging directory.
  /// Throws InputError naming `--out` when it cannot.
  explicit RunDirectory(std::filesystem::path target);
  /// Removes the staging directory unless `commit` succeeded.
  ~RunDirectory();
  RunDirectory(const RunDirectory&) = delete;
  RunDirectory& operator=(const RunDirectory&) = delete;

  /// Writes the four files into staging, then replaces `target` with it.
  void commit(const Case& c, const RunResult& result);
  /// Lets `write` fill the staging directory, then replaces `target` with it.
  void commit(const std::function<void(const std::filesystem::path& staging)>& write);

  [[nodiscard]] const std::filesystem::path& target() const { return target_; }

 private:
  std::filesystem::path target_, staging_;
  bool committed_ = false;
};

/// Writes `text` to `path` (throws std::system_error).
void write_text(const std::filesystem::path& path, const std::string& text);

/// summary.json's text.
[[nodiscard]] std::string summary_json(const Case& c, const Summary& s);
/// The short human summary printed on stdout.
[[nodiscard]] std::string summary_text(const Case& c, const Summary& s);

}  // namespace barimpact
