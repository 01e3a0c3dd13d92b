// Where barimpact may put its results (`--out`), and the marker that says a
// directory is barimpact's. The rule: barimpact never deletes what it did
// not write.
//   - a new path, or an empty directory: written;
//   - a directory barimpact wrote (the marker lists every entry in it: a
//     run's history.csv and fields.csv or results.h5, case.toml,
//     summary.json, figures/, a study's runs/ and tables; and it holds
//     nothing else): replaced, or resumed by sweep and converge;
//   - any other non-empty directory, and the working directory: refused,
//     unless --force, which writes barimpact's files beside the others and
//     replaces only files of the same names;
//   - "/", the home directory and any parent of the working directory:
//     refused, --force or not;
//   - what the command reads (CommandInputs) is never written over, --force
//     or not: --out may not be an input file, nor a directory the command
//     reads or a parent of one, and a directory barimpact would replace or
//     resume in may not hold an input file; beside the user's files an
//     input takes no name of barimpact's (a run's resolved case then goes
//     to case.resolved.toml, output.hpp).
// This header owns the rule and the marker; output.hpp writes the files.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace barimpact {

/// The marker file barimpact writes into every output directory.
inline constexpr std::string_view output_marker = ".barimpact";
/// The file that marks a staging directory as barimpact's while it fills.
inline constexpr std::string_view staging_flag = ".barimpact-staging";

/// What writing into a checked `--out` does.
enum class OutputMode {
  create,   ///< the path does not exist, or is an empty directory
  replace,  ///< a directory barimpact wrote: replaced (run, exact) or resumed
  beside,   ///< --force on someone else's directory: only barimpact's own names are written
};

/// What a command reads, which its results never overwrite.
struct CommandInputs {
  std::vector<std::filesystem::path> files;        ///< a case, sweep or setup file, signals
  std::vector<std::filesystem::path> directories;  ///< runs read back (hopkinson, plot)

  /// True when `path` is one of `files` (compared resolved).
  [[nodiscard]] bool reads_file(const std::filesystem::path& path) const;
  /// The first of `files` that is `entry` of `dir` or lies inside it, or empty.
  [[nodiscard]] std::filesystem::path file_under(const std::filesystem::path& dir, const std::string& entry) const;
};

/// Checks `target` against the rule above. Throws InputError naming
/// `option` (e.g. "--out") and the rule it breaks.
[[nodiscard]] OutputMode check_output_directory(const std::filesystem::path& target, bool force,
                                                std::string_view option = "--out", const CommandInputs& inputs = {});

/// Throws InputError naming `option` when one of `names`, written into
/// `dir`, would replace an input of the command, or a directory holding one.
void refuse_names_over_inputs(const std::filesystem::path& dir, const std::vector<std::string>& names,
                              const CommandInputs& inputs, std::string_view option = "--out");

/// True for the entries barimpact writes as directories (a study's runs/,
/// figures/); every other entry it writes is a file.
[[nodiscard]] inline bool written_as_directory(std::string_view name) {
  return name == "runs" || name == "figures";
}

/// Throws InputError naming `option` when one of `names` is in `dir` as
/// another kind of entry than barimpact writes (a directory summary.json/,
/// a file runs): checked before anything is written, --force or not.
void refuse_entries_of_another_kind(const std::filesystem::path& dir, const std::vector<std::string>& names,
                                    std::string_view option = "--out");

/// True when `dir` holds barimpact's marker and nothing the marker does not
/// list, and each listed directory is barimpact's in turn (a directory with
/// no marker, such as a study's runs/, holds only directories that are).
[[nodiscard]] bool written_by_barimpact(const std::filesystem::path& dir);

/// The entries the marker of `dir` lists (none without a marker barimpact wrote).
[[nodiscard]] std::vector<std::string> marked_entries(const std::filesystem::path& dir);

/// The command that wrote `dir` by its marker ("run", "converge", ...), or empty.
[[nodiscard]] std::string output_command(const std::filesystem::path& dir);

/// Writes (replaces) the marker of `dir`, listing `entries` and what the
/// marker already listed; `command` is the command that wrote them.
void write_output_marker(const std::filesystem::path& dir, std::string_view command,
                         const std::vector<std::string>& entries);

/// Removes the files among `names` that the marker of `dir` lists as
/// barimpact's (regular files only; anything else is left) and drops them
/// from the marker.
void remove_listed_files(const std::filesystem::path& dir, std::string_view command,
                         const std::vector<std::string>& names);

/// The names of the entries of `dir` (not recursive), sorted; empty if it does not exist.
[[nodiscard]] std::vector<std::string> directory_entries(const std::filesystem::path& dir);

/// Removes the staging directories (`.<name>.partial-<pid>`, flagged by
/// staging_flag), old results directories (`.<name>.old-<pid>`, barimpact's
/// whole) and staged copies of a listed file (`.sweep.csv.partial-<pid>`)
/// that a killed barimpact process left in `parent` for `name` (for any
/// name when `name` is empty); those of live processes, and anything
/// barimpact did not make, stay.
void remove_stale_staging(const std::filesystem::path& parent, const std::string& name);

/// The directories above a checked `--out` that did not exist: made by the
/// constructor, removed again (innermost first, while empty) by the
/// destructor unless `keep()` was called once the results are in place.
class MadeParents {
 public:
  explicit MadeParents(const std::filesystem::path& target);
  ~MadeParents();
  MadeParents(const MadeParents&) = delete;
  MadeParents& operator=(const MadeParents&) = delete;
  void keep() { made_.clear(); }

 private:
  void remove_made();
  std::vector<std::filesystem::path> made_;  // outermost first
};

/// For a command that fills its directory bit by bit and resumes (sweep,
/// converge): checks `target` (check_output_directory, that none of
/// `entries`, the names it will write, is or holds one of `inputs`, and
/// refuse_entries_of_another_kind), creates
/// it if need be and marks it as the command's, listing `entries`. Throws
/// InputError naming `option`.
void prepare_output_directory(const std::filesystem::path& target, std::string_view command,
                              const std::vector<std::string>& entries, bool force, std::string_view option = "--out",
                              const CommandInputs& inputs = {});

}  // namespace barimpact
