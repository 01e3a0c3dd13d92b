// A blow's results as a study reads them back from a run directory's
// summary.json (bearing.csv's and drive.csv's rows). Internal to src/study/.
#pragma once

#include <filesystem>
#include <limits>

namespace barimpact::detail {

struct BlowRead {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double set = nan, blows_per_250mm = nan, blows_per_m = nan, max_compression = nan, max_tension = nan, enthru = nan,
         transfer_ratio = nan;
  bool finished = false;
  double stroke = nan, first_set = nan;  ///< a diesel hammer's stroke iteration (NaN: one blow)
  int blows_run = 1;
};

/// The blow `run_dir`/summary.json holds: NaN throughout when there is none
/// (or the file is not a summary barimpact wrote whole); a set of 0 (the
/// hammer did not move the pile) gives infinite blow counts.
[[nodiscard]] BlowRead read_blow(const std::filesystem::path& run_dir);

/// A study's row (bearing.csv's, drive.csv's) takes the blow's columns.
template <class Row>
void take_blow(Row& row, const BlowRead& b) {
  row.set = b.set;
  row.blows_per_250mm = b.blows_per_250mm;
  row.blows_per_m = b.blows_per_m;
  row.max_compression = b.max_compression;
  row.max_tension = b.max_tension;
  row.enthru = b.enthru;
  row.transfer_ratio = b.transfer_ratio;
  row.finished = b.finished;
}

}  // namespace barimpact::detail
