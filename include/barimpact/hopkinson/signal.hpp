// A gauge's signal: axial strain against time, tension positive, read from a
// measured CSV file (strain or bridge volts, one or several columns or files
// averaged) or from a gauge column of a barimpact run's history.csv.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "barimpact/hopkinson/setup.hpp"

namespace barimpact {

struct GaugeSignal {
  std::vector<double> t;       ///< strictly increasing
  std::vector<double> strain;  ///< tension positive, polarity and bridge applied
  std::string label;           ///< "[incident] incident.csv", for messages
  bool simulated = false;      ///< from a barimpact run (no dispersion to correct)
};

/// How a measured CSV file is laid out (a Hopkinson channel's, a pile
/// record's): the delimiter, the lines skipped, the header, the time column.
struct CsvLayout {
  std::string section;            ///< "incident", "record": messages name it
  std::string time_column = "t";  ///< empty with sample_interval
  bool header = true;
  double sample_interval = 0.0;  ///< > 0: t_k = k dt, no time column
  char delimiter = ',';
  int skip_rows = 0;
};

/// Named columns of a CSV file, as numbers, with the file's line of each sample.
struct CsvColumns {
  std::vector<double> t;                  ///< strictly increasing
  std::vector<std::vector<double>> data;  ///< one per name, in order
  std::vector<long> lines;
};

/// Reads the columns `names` of `file`; `keys[i]` is the setup key that
/// named `names[i]` (for messages). Throws InputError naming the file (and
/// line), the column and the rule: a missing file or column, a cell that is
/// not a finite number, a time column that is not increasing, no samples.
[[nodiscard]] CsvColumns read_csv_columns(const CsvLayout& layout, const std::filesystem::path& file,
                                          const std::vector<std::string>& names, const std::vector<std::string>& keys);

/// Reads the channel's signal. Throws InputError naming the section, the file
/// (and line) or column and the rule: a missing file or column, a cell that
/// is not a number, a time column that is not increasing, channels that are
/// not on one clock, clipping (3 or more consecutive samples at or beyond
/// `full_scale`, in the channel's own unit).
[[nodiscard]] GaugeSignal read_gauge_signal(const ChannelSetup& channel);

}  // namespace barimpact
