// Parameter sweeps: a base case, axes over any case key (lists or ranges,
// linear or logarithmic), optional zips of axes; every case runs once and
// keeps its run directory (runs/<id>/, the files of `barimpact run`), and
// one row of sweep.csv. Rerunning skips cases whose directory holds their
// run (directories appear only when written whole: see output.hpp), so an
// interrupted sweep, rerun, ends as an uninterrupted one.
//
// The sweep file:
//   case = "paper-example1.toml"          # relative to the sweep file
//   [set]                                 # optional base overrides: any --set key
//   time.end = 2.0                        # (body.<name>.key = ... and the like too)
//   [[axis]]
//   key = "obstacle.stiffness"
//   values = [100.0, 1000.0]              # a list, or
//   [[axis]]
//   key = "time.step"
//   from = 0.01                           # a range: from, to, count,
//   to = 0.001                            # scale = "linear" | "log"
//   count = 4
//   scale = "log"
//   zip = [["obstacle.stiffness", "bar.elements"]]   # axes that move together
#pragma once

#include <atomic>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/run/output_directory.hpp"

namespace barimpact {

struct SweepAxis {
  std::string key;
  std::vector<std::string> values;  ///< TOML values as text (strings quoted)
};

struct SweepPoint {
  std::string id;                                           ///< zero-padded index, stable for a given sweep file
  std::vector<std::pair<std::string, std::string>> values;  ///< key, TOML value text
};

class SweepPlan {
 public:
  /// Reads and checks a sweep file; every point's case is validated too.
  /// Throws InputError naming the file, line and key.
  static SweepPlan from_file(const std::filesystem::path& path);
  /// Same from TOML text: `origin` names it in error messages and `case`
  /// is resolved relative to `dir` (the sweep file's directory).
  static SweepPlan from_string(std::string_view toml, std::string_view origin, const std::filesystem::path& dir);
  /// Overrides every point's case takes before its own values (a study's
  /// --set, already checked against the case); they replace [set]'s.
  void set_base(std::vector<Case::Override> sets) { base_sets_ = std::move(sets); }

  [[nodiscard]] const std::vector<SweepPoint>& points() const { return points_; }
  [[nodiscard]] const std::vector<std::string>& keys() const { return keys_; }
  /// The case of one point (throws InputError if that combination is invalid).
  [[nodiscard]] Case case_at(const SweepPoint& p) const;
  /// What the sweep reads: its file (from_file) and its case file.
  [[nodiscard]] CommandInputs inputs() const;

 private:
  std::filesystem::path sweep_file_, case_file_;
  std::vector<Case::Override> base_sets_;
  std::vector<std::string> keys_;
  std::vector<SweepPoint> points_;
};

/// One row of sweep.csv.
struct SweepRow {
  std::string id;
  std::vector<std::string> values;  ///< in SweepPlan::keys() order, as plain text
  std::string status;               ///< complete, non-finite, refused, interrupted (not run or cut short)
  std::string message;
  std::vector<std::string> warnings;  ///< the run's health checks (health.hpp)
  long long steps_done = 0;
  /// lift_off and rebound_velocity: the end and the rebound of one episode,
  /// the last, when it ended before the run's end (observer.hpp's
  /// departure); both NaN when the body is still in contact at the end.
  double t_end = 0, first_contact = 0, lift_off = 0, rebound_velocity = 0, max_penetration = 0, max_reaction = 0,
         energy_error_relative = 0, run_seconds = 0;
  int contacts = 0;
  /// A pile-driving blow's (summary.json's blow), after the contract's
  /// columns: set, blow counts, driving stresses and ENTHRU; NaN without a blow.
  bool blow = false;
  double set = 0, blows_per_250mm = 0, blows_per_m = 0, max_compression = 0, max_tension = 0, enthru = 0;
  bool resumed = false;  ///< read back from a complete run directory
  bool batched = false;  ///< ran in a SIMD batch with other cases
};

struct SweepOptions {
  int jobs = 0;       ///< threads (0: all cores)
  bool batch = true;  ///< run compatible paper-scheme cases 4 to a SIMD register
  /// When it becomes true, cases under way end after their step and are not
  /// kept, cases not begun are not run: their rows say "interrupted", and a
  /// rerun resumes them. Null: never.
  const std::atomic<bool>* interrupt = nullptr;
};

/// Makes `dir` ready for a sweep (or another study of sweep points, as
/// bearing): checks `options` (--jobs), applies the output rule (new, empty
/// or the command's own; `force` as --force; never over `inputs`) and marks
/// `dir` as `command`'s, listing `entries`; creates dir/runs/ and removes
/// what a killed sweep left there. Throws InputError.
void prepare_sweep(const std::filesystem::path& dir, const SweepOptions& options, bool force,
                   const CommandInputs& inputs, std::string_view command = "sweep",
                   const std::vector<std::string>& entries = {"runs", "sweep.csv"});

/// A sweep's rows before it runs: one per point, those whose run directory
/// holds their run read back (read_row), and the points still to run.
struct SweepStart {
  std::vector<SweepRow> rows;
  std::vector<std::size_t> todo;
};
[[nodiscard]] SweepStart resume_sweep(const SweepPlan& plan, const std::filesystem::path& dir);

/// How a sweep ended.
struct SweepOutcome {
  std::vector<SweepRow> rows;  ///< every point's, in order (sweep.csv's)
  std::size_t resumed = 0;     ///< read back, not run
  std::size_t run = 0;         ///< run this time (interrupted ones included)
  std::size_t batched = 0;     ///< of those, run in SIMD batches
};

/// Puts the rows run (run_sweep's, from any rank, in any order) in their
/// places among `start`'s and writes dir/sweep.csv.
[[nodiscard]] SweepOutcome finish_sweep(const SweepPlan& plan, const std::filesystem::path& dir, SweepStart start,
                                        const std::vector<SweepRow>& done);

/// All of `barimpact sweep` on one machine: prepare_sweep, resume_sweep,
/// run_sweep on the points left, finish_sweep.
[[nodiscard]] SweepOutcome write_sweep(const SweepPlan& plan, const std::filesystem::path& dir,
                                       const SweepOptions& options, bool force);

/// Runs (or resumes) the points `todo` (indices into plan.points()) into
/// `dir`/runs/<id>/ and returns their rows. `dir` must exist, with no stale
/// staging left in runs/ by a killed sweep (remove_stale_staging). A case
/// that fails is a row; a run's results the file system refuses (a full
/// disk) end the sweep instead: no further case begins, and the
/// OutputError is thrown once those under way are done.
[[nodiscard]] std::vector<SweepRow> run_sweep(const SweepPlan& plan, const std::filesystem::path& dir,
                                              const std::vector<std::size_t>& todo, const SweepOptions& options);

/// The row of a point whose run directory holds its run, written whole for
/// this very case (its case.toml is the point's), if it does.
[[nodiscard]] bool read_row(const SweepPlan& plan, const std::filesystem::path& dir, std::size_t point, SweepRow& row);

[[nodiscard]] std::string sweep_csv(const SweepPlan& plan, const std::vector<SweepRow>& rows);
/// A row as one line of JSON and back (for MPI ranks).
[[nodiscard]] std::string row_to_json(const SweepRow& row);
[[nodiscard]] SweepRow row_from_json(const std::string& text);

}  // namespace barimpact
