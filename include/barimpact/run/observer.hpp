// Observers see the scheme after every step and record what a user keeps:
// the history rows, field snapshots and contact episodes. They allocate in
// `begin`, never in `observe`, and never do I/O (files are written after the
// run, see output.hpp).
#pragma once

#include <array>
#include <chrono>
#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/run/probe.hpp"
#include "barimpact/schemes/scheme.hpp"

namespace barimpact {

class Observer {
 public:
  virtual ~Observer() = default;
  /// Called once before step 0 with the scheme and the number of steps N:
  /// the place to allocate.
  virtual void begin(const Scheme& /*scheme*/, long long /*steps*/) {}
  /// Called at steps 0, 1, ..., N. Returning false stops the run.
  virtual bool observe(const Scheme& scheme) = 0;
  /// Called once after the last step observed, whatever ended the run.
  virtual void end(const Scheme& /*scheme*/) {}
};

/// One row of history.csv, at t_n.
struct HistoryRow {
  double t, U, V, R, E_kin, E_strain, E_obstacle, W_ext, D_visc, D_contact, D_plastic;

  /// E_total: constant for an exact solution, the budget's test.
  [[nodiscard]] double total() const { return E_kin + E_strain + E_obstacle - W_ext + D_visc + D_contact + D_plastic; }
};

/// The budget: history.csv's first columns, in its order, each a member of HistoryRow.
struct BudgetColumn {
  std::string_view name;
  double HistoryRow::*value;
};
inline constexpr std::array<BudgetColumn, 11> budget_columns{{{"t", &HistoryRow::t},
                                                              {"U", &HistoryRow::U},
                                                              {"V", &HistoryRow::V},
                                                              {"R", &HistoryRow::R},
                                                              {"E_kin", &HistoryRow::E_kin},
                                                              {"E_strain", &HistoryRow::E_strain},
                                                              {"E_obstacle", &HistoryRow::E_obstacle},
                                                              {"W_ext", &HistoryRow::W_ext},
                                                              {"D_visc", &HistoryRow::D_visc},
                                                              {"D_contact", &HistoryRow::D_contact},
                                                              {"D_plastic", &HistoryRow::D_plastic}}};

/// Rows at steps 0, every, 2 every, ... and always at the last step.
class HistoryRecorder final : public Observer {
 public:
  /// `probes`: the columns after the budget (probe.hpp), read at every row.
  explicit HistoryRecorder(int every, const Probes* probes = nullptr) : every_(every), probes_(probes) {}
  void begin(const Scheme& scheme, long long steps) override;
  bool observe(const Scheme& scheme) override;
  void end(const Scheme& scheme) override;
  [[nodiscard]] const std::vector<HistoryRow>& rows() const { return rows_; }
  /// The probes' values, row-major (probes->size() per row).
  [[nodiscard]] const std::vector<double>& extra() const { return extra_; }

 private:
  long long every_;
  const Probes* probes_;
  long long last_ = 0;
  std::vector<HistoryRow> rows_;
  std::vector<double> extra_;
  // The last row's energies while the scheme completes them (begin_energies).
  bool pending_ = false;
  Energies energies_;
  void complete(const Scheme& s);
};

/// Field snapshots, snapshot-major: u[s * x.size() + j] is u at row j, t_s.
/// Rows are the nodes of each bar body in line order (a welded node once per
/// body): row j is node `node[j]` of body `body[j]`.
struct Fields {
  std::vector<double> x;
  std::vector<std::size_t> node;
  std::vector<std::size_t> body;
  std::vector<std::string> body_names;
  std::vector<double> t;
  std::vector<double> u, v, sigma;
  std::vector<double> eps_p;  ///< plastic strain (tension positive), nodal as sigma

  [[nodiscard]] std::size_t count() const { return t.size(); }
  [[nodiscard]] std::size_t nodes() const { return x.size(); }
};

/// Where field snapshots go as they are taken (the run directory's files,
/// output.hpp), so that a run holds one at a time, not all of them.
class FieldSink {
 public:
  virtual ~FieldSink() = default;
  /// One snapshot: `snapshot` holds its rows and one t with its values.
  /// False when it could not be kept (the sink holds the error): the run stops.
  virtual bool write(const Fields& snapshot) = 0;
};

/// u, v and the stress sigma = (E A u_x + eta A v_x) / A at every row, at the
/// steps nearest the requested times (each step once). Nodal sigma: the mean
/// of the body's two elements beside the node, its end element at its ends.
class FieldRecorder final : public Observer {
 public:
  /// Snapshots of `line` (which must outlive the recorder) at the steps
  /// nearest `times`: held until take(), or handed to `sink` one by one
  /// (then take() has the rows and no snapshot).
  FieldRecorder(const Case& c, const Line& line, std::vector<double> times, FieldSink* sink = nullptr);
  void begin(const Scheme& scheme, long long steps) override;
  bool observe(const Scheme& scheme) override;
  /// How many snapshots were recorded so far.
  [[nodiscard]] std::size_t taken() const { return taken_; }
  /// The recorded snapshots (moved out: call once, after the run).
  [[nodiscard]] Fields take();

 private:
  double dt_;
  const Line* line_;  // the run's, which outlives its recorders
  std::vector<double> times_;
  std::vector<long long> steps_;  // sorted, unique
  std::size_t taken_ = 0;
  FieldSink* sink_;
  Fields fields_;  // every snapshot, or with a sink the one under way
};

/// A contact episode: U + g < 0 from `start` to `end` (crossing times
/// interpolated linearly between steps; a start up to a step ahead of the
/// step that saw the contact, an end never before the start).
struct ContactInterval {
  double start = 0.0;
  double end = 0.0;
  bool closed = false;            ///< false: still in contact at the last step
  double exit_velocity = 0.0;     ///< V, the end's velocity, at the first step after separation
  double rebound_velocity = 0.0;  ///< the bar's mean velocity (momentum / mass) then
  /// The largest reaction, past the episode's first step against a rigid
  /// obstacle: that step's reaction is the impact's impulse over one step
  /// (the velocity stopped at once), not a force, and is reported apart.
  double max_reaction = 0.0;
  double impact_impulse = 0.0;  ///< rigid: the first step's reaction times its step (N s); 0 for a penalty
};

/// The episode the body left the obstacle from: the last one, when it ended
/// before the run's end; null when there is none or the body is still in
/// contact at the end. A study's lift-off and rebound both read it, so that
/// they never mix episodes (chatter's first brief touch with the last).
[[nodiscard]] const ContactInterval* departure(const std::vector<ContactInterval>& episodes);

/// Watches the near end at every step: its link's contact episodes (the
/// crossings of its opening U + g = 0 interpolated between steps, where the
/// links' monitor below counts whole steps of force), the largest
/// penetration and reaction, a rigid end's impact impulses.
class ContactMonitor final : public Observer {
 public:
  /// The line's near link, if any (none: no episodes); `dt` the run's step,
  /// which turns a rigid impact step's reaction into its impulse.
  explicit ContactMonitor(const Line& line, double dt = 0.0);
  void begin(const Scheme& scheme, long long steps) override;
  /// Allocates only when an episode begins beyond the 65536 reserved.
  bool observe(const Scheme& scheme) override;
  [[nodiscard]] const std::vector<ContactInterval>& intervals() const { return intervals_; }
  [[nodiscard]] double max_penetration() const { return max_penetration_; }
  /// The largest reaction of every episode (rigid: past its first step).
  [[nodiscard]] double max_reaction() const { return max_reaction_; }
  /// The largest impact impulse of a rigid obstacle's episodes (0 for a penalty).
  [[nodiscard]] double max_impact_impulse() const { return max_impulse_; }

 private:
  [[nodiscard]] double mean_velocity(const Scheme& s) const;
  const Line* line_;                      // the run's, which outlives its recorders
  bool present_ = false, rigid_ = false;  // a near link, and whether it is rigid
  double gap_ = 0.0;
  std::vector<ContactInterval> intervals_;
  bool in_contact_ = false;
  bool have_previous_ = false;
  double previous_t_ = 0.0, previous_d_ = 0.0;
  double max_penetration_ = 0.0, max_reaction_ = 0.0, max_impulse_ = 0.0;
  double dt_ = 0.0;
};

/// A link's contact episode (line.hpp): force > 0 (above 1e-9 of the
/// largest link force so far) from
/// `start` to `end` (at steps), the largest force, and the two faces'
/// velocities at the first step after they part (NaN for the ground).
struct LinkEpisode {
  double start = 0.0;
  double end = 0.0;
  bool closed = false;
  double max_force = 0.0;
  double velocity_lower = 0.0;
  double velocity_upper = 0.0;
};

/// Contact episodes of every link of the line.
class LinkMonitor final : public Observer {
 public:
  explicit LinkMonitor(const Line& line);
  void begin(const Scheme& scheme, long long steps) override;
  /// Allocates only when an episode begins beyond the 4096 reserved per link.
  bool observe(const Scheme& scheme) override;
  [[nodiscard]] const std::vector<std::string>& names() const { return names_; }
  [[nodiscard]] const std::vector<std::vector<LinkEpisode>>& episodes() const { return episodes_; }

 private:
  std::vector<std::string> names_;
  std::vector<std::size_t> a_, b_;
  std::vector<std::vector<LinkEpisode>> episodes_;
  std::vector<char> in_contact_;
  double largest_ = 0.0;
};

/// The largest plastic strain (by size, signed) of the elastic-plastic
/// elements, where and when, sampled at the history's steps (every
/// `every`-th and the last), and each body's plastic work at the last one.
class PlasticMonitor final : public Observer {
 public:
  PlasticMonitor(const Line& line, long long every);
  void begin(const Scheme& scheme, long long steps) override;
  bool observe(const Scheme& scheme) override;
  [[nodiscard]] bool any() const { return !bonds_.empty(); }
  [[nodiscard]] double largest() const { return largest_; }
  [[nodiscard]] std::size_t bond() const { return bond_; }
  [[nodiscard]] double time() const { return time_; }
  /// Per body of the line (0 for elastic bodies and masses).
  [[nodiscard]] const std::vector<double>& work() const { return work_; }

 private:
  std::vector<std::size_t> bonds_;  // the elastic-plastic elements
  long long every_ = 1, last_ = 0;
  double largest_ = 0.0, time_ = 0.0;
  std::size_t bond_ = 0;
  std::vector<double> work_;
};

/// Where a run stands, for progress reports.
struct Progress {
  long long step = 0;
  long long steps = 0;
  double t = 0.0;
  double t_end = 0.0;
  double elapsed_seconds = 0.0;
};

/// Calls `report` about every `interval` seconds of wall time once `delay`
/// seconds have passed. The clock is read every `stride` steps, the stride
/// doubling while reads come faster than interval/16, so that the cost per
/// step stays negligible at any mesh size. `report` returning false stops
/// the run.
class ProgressMonitor final : public Observer {
 public:
  using Report = std::function<bool(const Progress&)>;
  ProgressMonitor(Report report, double t_end, double interval_seconds = 0.5, double delay_seconds = 0.0);
  void begin(const Scheme& scheme, long long steps) override;
  bool observe(const Scheme& scheme) override;

 private:
  using Clock = std::chrono::steady_clock;
  Report report_;
  double t_end_, interval_, delay_;
  long long steps_ = 0, stride_ = 1, countdown_ = 1;
  Clock::time_point started_, last_read_, last_report_;
};

}  // namespace barimpact
