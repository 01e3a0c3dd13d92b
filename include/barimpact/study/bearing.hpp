// The bearing graph of pile driving: the blow count a hammer reaches
// against a range of static soil capacities (Smith 1960's use of the wave
// equation; every wave-equation program draws it). Toe and shaft capacities
// are scaled together, keeping the case's toe share unless one is given;
// each capacity runs as a point of a sweep (sweep.hpp: runs/<id>/, all
// cores, resumable, a failed run a row), and bearing.csv lists per capacity
// the blow's results (summary.json's `blow`).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/study/sweep.hpp"

namespace barimpact {

struct BearingOptions {
  double from = 0.0, to = 0.0;       ///< the capacities R_toe + R_shaft, N
  int count = 0;                     ///< spaced linearly, from and to included
  std::optional<double> toe_share;   ///< R_toe / capacity in [0, 1] (none: the case's); BearingPlan checks it
  std::vector<Case::Override> sets;  ///< --set overrides of the case, for every capacity (time.end, the mesh, ...)
};

/// Reads --capacity FROM:TO:COUNT into `o` (count >= 2, or 1 with FROM = TO).
void parse_capacity(const std::string& text, BearingOptions& o);

class BearingPlan {
 public:
  /// The sweep over capacities of the case file. Throws InputError when the
  /// case has no Smith soil to scale or the options break a rule.
  BearingPlan(const std::filesystem::path& case_file, const BearingOptions& options);
  [[nodiscard]] const SweepPlan& sweep() const { return sweep_; }
  [[nodiscard]] double capacity(std::size_t point) const { return capacity_[point]; }
  [[nodiscard]] double toe_share() const { return share_; }

 private:
  SweepPlan sweep_;
  std::vector<double> capacity_;
  double share_ = 0.0;
};

/// One row of bearing.csv: the capacity and its blow (NaN where the run
/// gave none; its status says why).
struct BearingRow {
  double capacity = 0.0, toe = 0.0, shaft = 0.0;
  double set = 0.0, blows_per_250mm = 0.0, blows_per_m = 0.0, max_compression = 0.0, max_tension = 0.0, enthru = 0.0,
         transfer_ratio = 0.0;
  bool finished = false;
  SweepRow run;
};

/// Runs (or resumes) every capacity into `dir`/runs/ and reads each blow back.
[[nodiscard]] std::vector<BearingRow> run_bearing(const BearingPlan& plan, const std::filesystem::path& dir,
                                                  const SweepOptions& options);

/// All of `barimpact bearing` but its figure: checks `options` (--jobs),
/// prepares `dir` (the output rule: new, empty or a bearing's; `force` as
/// --force), runs or resumes, and writes bearing.csv. Returns the rows.
[[nodiscard]] std::vector<BearingRow> write_bearing(const BearingPlan& plan, const std::filesystem::path& dir,
                                                    const SweepOptions& options, bool force);

/// bearing.csv: capacity,set,blows_per_250mm,blows_per_m,max_compression,
/// max_tension,enthru,finished, then toe,shaft,transfer_ratio,id,status,
/// message,warnings (infinite blow counts "inf", a missing value "nan").
[[nodiscard]] std::string bearing_csv(const std::vector<BearingRow>& rows);

}  // namespace barimpact
