// Drivability: the pile driven from the ground to its final depth. Every
// penetration of [drive] depths is a blow (a point of a sweep over
// drive.depth: runs/<id>/, all cores, resumable, a failed run a row) whose
// pile meets the soil profile's shaft and toe at that depth; drive.csv lists
// per depth the soil's capacities and the blow's results, and the blows
// and time it takes to get there.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/study/sweep.hpp"

namespace barimpact {

class DrivePlan {
 public:
  /// The sweep over the depths of the case file's [drive]. Throws
  /// InputError when the case has no [drive] or an override breaks a rule.
  DrivePlan(const std::filesystem::path& case_file, const std::vector<Case::Override>& sets);
  [[nodiscard]] const SweepPlan& sweep() const { return sweep_; }
  /// The case as read (at its deepest depth): its drive, hammer and pile.
  [[nodiscard]] const Case& base() const { return base_; }
  [[nodiscard]] const DriveData& drive() const { return *base_.drive; }
  [[nodiscard]] const DriveSoil& soil(std::size_t point) const { return soil_[point]; }
  /// The hammer's stroke (m), NaN without a [hammer].
  [[nodiscard]] double stroke() const;

 private:
  SweepPlan sweep_;
  Case base_;
  std::vector<DriveSoil> soil_;
};

/// One row of drive.csv: a depth, its soil and its blow (NaN where the run
/// gave none; its status says why).
struct DriveRow {
  double depth = 0.0, shaft = 0.0, toe = 0.0, capacity = 0.0, long_term_capacity = 0.0;
  double set = 0.0, blows_per_250mm = 0.0, blows_per_m = 0.0, max_compression = 0.0, max_tension = 0.0, enthru = 0.0;
  double stroke = 0.0, cumulative_blows = 0.0;
  bool finished = false;
  double first_set = 0.0;
  int blows_run = 0;
  double transfer_ratio = 0.0;
  SweepRow run;
};

/// What drive's summary.json says of the whole drive.
struct DriveTotals {
  double total_blows = 0.0;   ///< up to the first refused depth (or the deepest)
  double driving_time = 0.0;  ///< minutes, at [drive] blow_rate
  std::optional<double> refusal_depth;
  double max_compression = 0.0, max_compression_depth = 0.0;
  double max_tension = 0.0, max_tension_depth = 0.0;
};

/// Runs (or resumes) every depth into `dir`/runs/ and reads each blow back.
[[nodiscard]] std::vector<DriveRow> run_drive(const DrivePlan& plan, const std::filesystem::path& dir,
                                              const SweepOptions& options);

/// All of `barimpact drive` but its figure: checks `options`, prepares `dir`
/// (the output rule; `force` as --force), runs or resumes, and writes
/// drive.csv and summary.json. Returns the rows.
[[nodiscard]] std::vector<DriveRow> write_drive(const DrivePlan& plan, const std::filesystem::path& dir,
                                                const SweepOptions& options, bool force);

[[nodiscard]] DriveTotals drive_totals(const DrivePlan& plan, const std::vector<DriveRow>& rows);

/// drive.csv: depth,shaft,toe,capacity,long_term_capacity,set,
/// blows_per_250mm,blows_per_m,max_compression,max_tension,enthru,stroke,
/// cumulative_blows,finished, then first_set,blows_run,transfer_ratio,id,
/// status,message,warnings (infinite counts "inf", a missing value "nan").
[[nodiscard]] std::string drive_csv(const std::vector<DriveRow>& rows);

/// The inspector's chart: at one soil (the case's, or its [drive] profile
/// at one depth), the blow against the hammer's stroke. Each stroke is a
/// point of a sweep over hammer.stroke.
class InspectorPlan {
 public:
  /// `strokes` "FROM:TO:COUNT" (m); `depth` required for a case with
  /// [drive], refused for one without. Throws InputError naming the option or key.
  InspectorPlan(const std::filesystem::path& case_file, const std::string& strokes, std::optional<double> depth,
                std::vector<Case::Override> sets);
  [[nodiscard]] const SweepPlan& sweep() const { return sweep_; }
  [[nodiscard]] double stroke(std::size_t point) const { return strokes_[point]; }
  [[nodiscard]] double ram_weight() const { return ram_weight_; }  ///< m g, N

 private:
  SweepPlan sweep_;
  std::vector<double> strokes_;
  double ram_weight_ = 0.0;
};

struct InspectorRow {
  double stroke = 0.0, energy = 0.0;
  double set = 0.0, blows_per_250mm = 0.0, blows_per_m = 0.0, max_compression = 0.0, max_tension = 0.0, enthru = 0.0,
         transfer_ratio = 0.0;
  bool finished = false;
  SweepRow run;
};

/// All of `barimpact inspector` but its figure: prepares `dir`, runs or
/// resumes every stroke and writes inspector.csv
/// (stroke,energy,set,blows_per_250mm,blows_per_m,max_compression,
/// max_tension,enthru, then finished,transfer_ratio,id,status,message,warnings).
[[nodiscard]] std::vector<InspectorRow> write_inspector(const InspectorPlan& plan, const std::filesystem::path& dir,
                                                        const SweepOptions& options, bool force);

[[nodiscard]] std::string inspector_csv(const std::vector<InspectorRow>& rows);

}  // namespace barimpact
