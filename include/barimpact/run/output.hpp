// The run directory: history.csv, fields.csv, case.toml, summary.json (or,
// with `[output] format = "hdf5"`, results.h5 for the two CSV files: see
// results_h5.hpp), written into a hidden staging directory beside the target
// and renamed into place only when written whole, so that no half-written
// result ever carries the target's name. Which targets may be written, and
// how, is the rule of output_directory.hpp: nothing barimpact did not write
// is ever deleted.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "barimpact/case/case.hpp"
#include "barimpact/model/input_error.hpp"
#include "barimpact/run/output_directory.hpp"
#include "barimpact/run/simulate.hpp"

namespace barimpact {

class MadeParents;
namespace detail {
class FieldStream;
}

/// The run's resolved case: case.toml, or case.resolved.toml where
/// case.toml is an input of the command (`run DIR/case.toml --out DIR
/// --force`), which is never written over.
inline constexpr std::string_view case_file_name = "case.toml";
inline constexpr std::string_view resolved_case_name = "case.resolved.toml";

/// The files a run of `c` writes (RunDirectory::commit's), for expect().
[[nodiscard]] std::vector<std::string> run_outputs(const Case& c);

class RunDirectory {
 public:
  /// Checks `target` against the output rule (`force` as --force; `inputs`
  /// what the command read) and creates the staging directory, first
  /// removing what killed processes left beside it (unless the caller
  /// cleans the parent once for many targets: a sweep's runs/). Throws
  /// InputError naming `--out`.
  explicit RunDirectory(std::filesystem::path target, bool force = false, std::string command = "run",
                        bool remove_stale = true, CommandInputs inputs = {});
  /// Removes the staging directory unless `commit` succeeded (never throws).
  ~RunDirectory();
  RunDirectory(const RunDirectory&) = delete;
  RunDirectory& operator=(const RunDirectory&) = delete;

  /// Refuses now, before the work, what `commit` would refuse at the end:
  /// an entry of the target named as a file the command writes that is a
  /// directory, or the reverse (InputError naming --out; nothing written).
  void expect(const std::vector<std::string>& names) const;

  /// Where the run of `c` puts its field snapshots as it takes them
  /// (RunOptions::fields): fields.csv in staging, or results.h5 (written as
  /// the run goes), so that the run never holds them all. Call before the run;
  /// `commit` then writes the rest.
  FieldSink& stream_fields(const Case& c);
  /// Writes the files into staging (history.csv and fields.csv, or
  /// results.h5, as `c.output.format` says; case.toml, summary.json), then
  /// moves them into place.
  void commit(const Case& c, const RunResult& result);
  /// Lets `write` fill the staging directory with files, marks them as
  /// barimpact's, then moves them into place: `target` is created, or
  /// replaced if barimpact wrote it, or else receives the files beside its own
  /// (the resolved case as case.resolved.toml where case.toml is an input;
  /// any other name of an input refused before anything is moved).
  /// What the file system refuses (a full disk) is an OutputError naming
  /// `--out`, the file and the reason; nothing staged is left and the target
  /// is as it was.
  void commit(const std::function<void(const std::filesystem::path& staging)>& write);

  /// The target as given.
  [[nodiscard]] const std::filesystem::path& target() const { return shown_; }

 private:
  void move_into_place();
  void move_beside();
  void spare_inputs();
  /// `e` naming `--out` and the file by its name in the results.
  [[nodiscard]] OutputError refused(const OutputError& e) const;
  /// What the file system or HDF5 refused (`e`, for `reason`), naming `--out`.
  [[nodiscard]] OutputError cannot_write(const std::exception& e, const std::string& reason) const;

  std::filesystem::path shown_, target_, staging_;  // as given; resolved; staging
  CommandInputs inputs_;
  std::unique_ptr<MadeParents> parents_;         // --out's missing parents, made for the staging
  std::unique_ptr<detail::FieldStream> fields_;  // the snapshots streamed, if any
  std::string command_;
  bool beside_ = false;  // --force on someone else's directory
  bool committed_ = false;
};

/// Writes `text` to `path`. Throws OutputError naming `path` and the
/// system's reason; a file it could not write whole is removed.
void write_text(const std::filesystem::path& path, const std::string& text);
/// The same, through a hidden file beside it renamed over `path`: a reader
/// (or an interruption) never sees half of it, and a refusal leaves `path`
/// as it was.
void replace_text(const std::filesystem::path& path, const std::string& text);

/// The file of a run directory that holds its history: history.csv, or
/// results.h5 (output.format = "hdf5").
[[nodiscard]] std::string_view history_file(OutputFormat format);

/// The resolved case of the run in `dir`: case.resolved.toml when its
/// marker lists it, else case.toml.
[[nodiscard]] std::filesystem::path run_case_file(const std::filesystem::path& dir);

/// Reads back what `commit` wrote (the history, from history.csv or
/// results.h5 as its case.toml says, and summary.json; not the fields): the
/// same doubles, as every number is written in its shortest exact form (or
/// as float64). Empty when `dir` holds no readable run, or one whose case.toml
/// is not `case_toml` (when given).
[[nodiscard]] std::optional<RunResult> read_run_directory(const std::filesystem::path& dir,
                                                          const std::string& case_toml = {});

/// summary.json's text.
[[nodiscard]] std::string summary_json(const Case& c, const Summary& s);
/// The short human summary printed on stdout.
[[nodiscard]] std::string summary_text(const Case& c, const Summary& s);

}  // namespace barimpact
