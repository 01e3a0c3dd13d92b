// The time loop, and a convenience that runs a case with the standard
// observers. `simulate` is the only loop in barimpact.
#pragma once

#include <atomic>
#include <chrono>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/run/blow.hpp"
#include "barimpact/run/observer.hpp"
#include "barimpact/run/probe.hpp"
#include "barimpact/schemes/registry.hpp"
#include "barimpact/schemes/scheme.hpp"

namespace barimpact {

enum class RunStatus { complete, non_finite, stopped, interrupted };

struct LoopResult {
  RunStatus status = RunStatus::complete;
  long long steps_done = 0;  ///< the last step observed
  std::string message;       ///< why it did not complete
};

/// What the time loop steps: lanes advanced together, each a Scheme seen by
/// its own observers. One scheme is one lane; the SIMD batch of the paper's
/// scheme (study/paper_batch.hpp) steps several cases at once.
class LaneStepper {
 public:
  virtual ~LaneStepper() = default;
  [[nodiscard]] virtual std::size_t lanes() const = 0;
  [[nodiscard]] virtual Scheme& lane(std::size_t i) = 0;
  virtual void start() = 0;
  virtual void advance() = 0;
};

/// The time loop: starts the lanes, then advances them `steps` times; every
/// lane's observers see its steps 0..steps. A lane stops early, with its
/// observers' data so far, when its state turns non-finite or an observer
/// returns false (its numbers are computed on with the others, and
/// ignored); every lane stops when `interrupt` (set from a signal handler,
/// say) becomes true: the step under way ends first. The loop ends when no
/// lane is left. `observers[i]` are lane i's.
std::vector<LoopResult> simulate(LaneStepper& lanes, long long steps, std::span<const std::vector<Observer*>> observers,
                                 const std::atomic<bool>* interrupt = nullptr);
/// The same for one scheme.
LoopResult simulate(Scheme& scheme, long long steps, std::span<Observer* const> observers,
                    const std::atomic<bool>* interrupt = nullptr);

/// What the elastic-plastic bodies did (material.hpp): the largest plastic
/// strain (signed, by size) at the history's steps, in the element centred
/// at x, and each such body's plastic work at the end.
struct PlasticSummary {
  double largest_strain = 0.0;
  std::string body;
  double x = 0.0, t = 0.0;
  std::vector<std::pair<std::string, double>> work;
};

struct Summary {
  std::string method;  ///< the scheme's name, or "exact"
  bool complete = true;
  RunStatus status = RunStatus::complete;
  std::string message;
  long long steps = 0;  ///< N requested
  long long steps_done = 0;
  double t_end = 0.0;  ///< t of the last step observed
  std::vector<ContactInterval> contacts;
  /// Every link's episodes (observer.hpp), named as the line's links.
  std::vector<std::string> link_names;
  std::vector<std::vector<LinkEpisode>> link_episodes;
  double max_penetration = 0.0;
  double max_reaction = 0.0;              ///< rigid: past each impact step (observer.hpp's ContactInterval)
  double max_impact_impulse = 0.0;        ///< rigid: the largest impact step's impulse (N s); 0 for a penalty
  std::optional<PlasticSummary> plastic;  ///< none: every body elastic
  std::optional<BlowSummary> blow;        ///< none: no Smith soil and no [blow]
  double energy_initial = 0.0;            ///< E_total at t = 0
  double energy_final = 0.0;              ///< E_total at the last history row
  double energy_error_max = 0.0;          ///< max over rows of |E_total - E_total(0)|
  double run_seconds = 0.0;
  /// What the run's own health checks found (health.hpp): one line each.
  std::vector<std::string> warnings;
};

struct RunResult {
  Summary summary;
  std::vector<HistoryRow> history;
  /// The history's columns after the budget (probe.hpp) and their values,
  /// row-major: columns.size() per row.
  std::vector<std::string> columns;
  std::vector<double> extra;
  Fields fields;
};

struct RunOptions {
  /// Called about every `progress_interval` seconds once `progress_delay`
  /// seconds have passed; returning false stops the run. Empty: no reports.
  ProgressMonitor::Report progress;
  double progress_interval = 0.5;
  double progress_delay = 0.0;
  /// When it becomes true the run ends after the step under way, its rows
  /// so far kept, with RunStatus::interrupted. Null: never.
  const std::atomic<bool>* interrupt = nullptr;
  /// Called once the run's set-up is done (its scheme and observers made),
  /// just before its time loop: from then on `interrupt` is polled every
  /// step. The command ends set-up at once on a signal until then (set-up
  /// does not poll). Empty: nothing.
  std::function<void()> loop_begins;
  /// Field snapshots go there as they are taken (RunDirectory::stream_fields)
  /// instead of into RunResult::fields, which then has the rows only. Null:
  /// all held in the result.
  FieldSink* fields = nullptr;
};

/// Whether a run of `c` is several blows at one soil, the last its result:
/// a diesel hammer's stroke iteration, [drive] blows > 1's residual stresses.
/// run() runs them; run_scheme() runs one.
[[nodiscard]] bool repeats_blows(const Case& c);

/// Runs `c` with its scheme and the history, field and contact observers:
/// fits it to the scheme first (fit_scheme). Throws InputError when the case
/// does not fit its scheme, or needs more memory than is available
/// (check_resources, check.hpp).
[[nodiscard]] RunResult run(const Case& c, const RunOptions& options = {});
/// The same for a case already fitted (the caller keeps fitted.c, the case
/// the results are of); its line, if fitting kept one, is the run's.
[[nodiscard]] RunResult run(FittedCase fitted, const RunOptions& options = {});

/// The standard observers of one run of `c` (the history with its probes,
/// field snapshots, contact and link episodes, plastic strains, the blow)
/// and the RunResult they add up to. The loop is the caller's: `run`'s
/// simulate, or a batch's over its lanes. They read the scheme's own line,
/// or build one for a scheme that holds none; `c` and `scheme` must
/// outlive the recorder.
class RunRecorder {
 public:
  /// `fields`: where the snapshots go as they are taken (null: held).
  RunRecorder(const Case& c, const Scheme& scheme, FieldSink* fields = nullptr);
  RunRecorder(const RunRecorder&) = delete;  // the observers point into it
  RunRecorder& operator=(const RunRecorder&) = delete;

  [[nodiscard]] const std::vector<Observer*>& observers() const { return observers_; }
  /// The run's result once its loop ended as `loop` (of `steps` requested,
  /// begun at `started`); `finite_rows`: a history row that is not finite
  /// ends a complete run there as non-finite.
  [[nodiscard]] RunResult finish(LoopResult loop, long long steps, std::chrono::steady_clock::time_point started,
                                 bool finite_rows = true);

 private:
  /// Where and when the plastic strain peaked, and each body's plastic work.
  [[nodiscard]] PlasticSummary plastic_summary() const;

  const Case& case_;
  std::optional<Line> own_;  // built only for a scheme that holds no line (the fused one-bar paper scheme)
  const Line& line_;
  Probes probes_;
  HistoryRecorder history_;
  FieldRecorder fields_;
  ContactMonitor contact_;
  LinkMonitor links_;
  PlasticMonitor plastic_;
  std::optional<BlowMonitor> blow_;
  std::vector<Observer*> observers_;
};

/// Runs `scheme` (made for `c`) for `steps` steps with the standard
/// observers: what `run` does once it has made the scheme (exact/tabulate
/// hands it a tabulated solution); `finite_rows` as RunRecorder::finish.
[[nodiscard]] RunResult run_scheme(const Case& c, Scheme& scheme, long long steps, const RunOptions& options,
                                   bool finite_rows = true);

[[nodiscard]] std::string_view to_string(RunStatus status);

}  // namespace barimpact
