// Observers see the scheme after every step and record what a user keeps:
// the history rows, field snapshots and contact episodes. They allocate in
// `begin`, never in `observe`, and never do I/O (files are written after the
// run, see output.hpp).
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <span>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/model/obstacle.hpp"
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
};

/// One row of history.csv, at t_n.
struct HistoryRow {
  double t, U, V, R, E_kin, E_strain, E_obstacle, W_ext, D_visc;
};

/// Rows at steps 0, every, 2 every, ... and always at the last step.
class HistoryRecorder final : public Observer {
 public:
  explicit HistoryRecorder(int every) : every_(every) {}
  void begin(const Scheme& scheme, long long steps) override;
  bool observe(const Scheme& scheme) override;
  [[nodiscard]] const std::vector<HistoryRow>& rows() const { return rows_; }

 private:
  long long every_;
  long long last_ = 0;
  std::vector<HistoryRow> rows_;
};

/// Field snapshots, snapshot-major: u[s * x.size() + j] is u(x_j, t_s).
struct Fields {
  std::vector<double> x;
  std::vector<double> t;
  std::vector<double> u, v, sigma;

  [[nodiscard]] std::size_t count() const { return t.size(); }
  [[nodiscard]] std::size_t nodes() const { return x.size(); }
};

/// u, v and sigma = a u_x + b v_x at every node, at the steps nearest the
/// requested times (each step once). Nodal sigma: the mean of the two
/// adjacent elements' constant values, the end element's at x = 0 and L.
class FieldRecorder final : public Observer {
 public:
  FieldRecorder(const Case& c, std::vector<double> times);
  void begin(const Scheme& scheme, long long steps) override;
  bool observe(const Scheme& scheme) override;
  /// How many snapshots were recorded so far.
  [[nodiscard]] std::size_t taken() const { return taken_; }
  /// The recorded snapshots (moved out: call once, after the run).
  [[nodiscard]] Fields take();

 private:
  double dt_, h_, a_, b_;
  std::vector<double> times_;
  std::vector<long long> steps_;  // sorted, unique
  std::size_t taken_ = 0;
  Fields fields_;
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
  double max_reaction = 0.0;
};

/// Watches every step: contact episodes, largest penetration and reaction.
class ContactMonitor final : public Observer {
 public:
  explicit ContactMonitor(const ObstacleData& obstacle) : law_(obstacle) {}
  void begin(const Scheme& scheme, long long steps) override;
  /// Allocates only when an episode begins beyond the 65536 reserved.
  bool observe(const Scheme& scheme) override;
  [[nodiscard]] const std::vector<ContactInterval>& intervals() const { return intervals_; }
  [[nodiscard]] double max_penetration() const { return max_penetration_; }
  [[nodiscard]] double max_reaction() const { return max_reaction_; }

 private:
  ObstacleLaw law_;
  std::vector<ContactInterval> intervals_;
  bool in_contact_ = false;
  bool have_previous_ = false;
  double previous_t_ = 0.0, previous_d_ = 0.0;
  double max_penetration_ = 0.0, max_reaction_ = 0.0;
  std::vector<double> velocity_;
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
