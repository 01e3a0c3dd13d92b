// Signal matching (`barimpact match RECORD.toml`): the soil resistance along
// a tested pile whose computed force at the gauges, under the measured
// velocity imposed there, matches the measured force (Rausche, Moses & Goble
// 1972, "Soil resistance predictions from pile dynamics", the method known
// as CAPWAP). The forward model is the line engine's: the record's pile as
// a line of elements no longer than L/100, Smith's soil on `segments` equal
// lengths of the embedded pile and at the toe, stepped by central
// differences. The fit is Ceres Solver's bounded Levenberg-Marquardt on the
// force difference, from the Case method's estimate and further starts.
#pragma once

#include <atomic>
#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/model/line.hpp"
#include "barimpact/pda/case_method.hpp"

namespace barimpact {

/// Smith's soil of a matched pile: a static resistance per shaft segment
/// (gauges down) and at the toe, one quake and one damping for the shaft
/// and for the toe.
struct MatchSoil {
  std::vector<double> shaft;                          ///< N per segment
  double toe = 0.0;                                   ///< N
  double shaft_quake = 0.00254, toe_quake = 0.00254;  ///< m
  double shaft_damping = 0.0, toe_damping = 0.0;      ///< s/m
  DampingLaw law = DampingLaw::smith;

  [[nodiscard]] double shaft_total() const;
  [[nodiscard]] double capacity() const { return shaft_total() + toe; }
};

/// The forward model of a match, built once: the record's pile driven at
/// the gauges by the measured velocity from `t_start` (at rest) to `t_end`,
/// Smith's soil given per run. Thread-safe: each run steps its own scheme.
class MatchModel {
 public:
  MatchModel(const PileRecord& record, const PileSignals& signals, double t_start, double t_end);

  /// The force at the gauges (compression > 0) at the record's samples
  /// `first` .. `first + out.size() - 1`, for `soil`. False when the run did
  /// not stay finite.
  bool head_force(const MatchSoil& soil, std::size_t first, std::span<double> out) const;

  [[nodiscard]] std::size_t segments() const { return segments_; }
  /// Segment i's depths below the gauges, m.
  [[nodiscard]] double segment_top(std::size_t i) const;
  [[nodiscard]] double segment_bottom(std::size_t i) const;
  [[nodiscard]] const Line& line() const { return line_; }
  /// Sets a copy of line()'s shaft and toe to `soil`.
  void apply(const MatchSoil& soil, Line& line) const;

 private:
  const PileSignals* signals_;
  double t_start_;
  Case case_;  // the scheme's settings
  Line line_;  // the pile, toe at x = 0, the far end driven
  std::size_t segments_ = 0;
  double length_ = 0.0, top_ = 0.0, segment_length_ = 0.0;  // the soil's top below the gauges, a segment's length
  double bare_step_ = 0.0;
  /// Per node, its share of each segment's resistance (the hat function
  /// integrated over the segment over the segment's length): {segment, share}.
  std::vector<std::vector<std::pair<std::size_t, double>>> shares_;
};

/// One starting point of the fit and where it ended.
struct MatchStart {
  MatchSoil start, soil;
  double quality = 0.0;    ///< rms force difference over the largest measured force
  double objective = 0.0;  ///< what the fit minimised: quality^2 with the smoothing penalty (the best start's least)
  std::vector<double> computed;  ///< its force at the window's samples
  int iterations = 0;
  long long evaluations = 0;
  bool converged = false;
  std::string message;  ///< the solver's reason for stopping
};

/// The quasi-static push of the matched pile at the gauges (a simulated
/// static load test): settlement and load, positive down.
struct StaticTest {
  std::vector<double> settlement, load;
  double s_c = 0.0;  ///< where the load reaches the capacity: the largest quake plus the pile's shortening
  /// max(q_toe, q_shaft) + (R_toe L + sum R_i z_i) / (E A) with E A at the
  /// gauges: s_c on a uniform pile (its closed form), not on [[segment]]s.
  double s_c_uniform = 0.0;
};

struct MatchResult {
  CaseMethodResult pda;
  MatchSoil soil;  ///< the best start's
  std::vector<MatchStart> starts;
  std::size_t best = 0;
  double quality = 0.0;
  long long evaluations = 0;
  int iterations = 0;
  double window = 0.0;           ///< s after t2 matched
  double embedded = 0.0;         ///< m
  std::size_t first = 0;         ///< the window's first sample (t_foot)
  std::vector<double> computed;  ///< the best match's force at the window's samples
  std::vector<double> segment_top, segment_bottom;
  StaticTest static_test;
  double seconds = 0.0;  ///< the fit's wall time
  bool interrupted = false;
  /// Whether a start converged (Ceres' tolerances); false: every start ran
  /// out of iterations or failed, and the match may not be a minimum.
  [[nodiscard]] bool converged() const;
  /// The starts' largest capacity less their smallest (N).
  [[nodiscard]] double spread() const;
  /// What to doubt about the match, one line each (summary.json's
  /// `warnings`): match-unfiltered (an uneven record), match-not-converged.
  [[nodiscard]] std::vector<std::string> warnings() const;
};

/// Matches a record (its [match] settings) on `jobs` threads (0: all cores).
/// Throws InputError for a record the analysis refuses. Once `interrupt` is
/// set (from a signal handler) the fit ends at its starts' next iterations
/// and the result is only `interrupted`.
[[nodiscard]] MatchResult match_pile(const PileRecord& record, int jobs = 0,
                                     const std::atomic<bool>* interrupt = nullptr);

/// The simulated static load test of `soil` on the record's pile (the
/// model's segments): 150 equal settlement increments to 1.5 s_C.
[[nodiscard]] StaticTest static_load_test(const MatchModel& model, const MatchSoil& soil);

/// The files a match writes (its figures aside).
[[nodiscard]] const std::vector<std::string>& match_files();
/// match.csv, soil.csv, static.csv and summary.json's texts.
[[nodiscard]] std::string match_csv(const MatchResult& r);
[[nodiscard]] std::string soil_csv(const MatchResult& r);
[[nodiscard]] std::string static_csv(const MatchResult& r);
[[nodiscard]] std::string match_summary_json(const MatchResult& r);

}  // namespace barimpact
