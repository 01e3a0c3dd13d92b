// A gauge's signal: axial strain against time, tension positive, read from a
// measured CSV file (strain or bridge volts, one or several columns or files
// averaged) or from a gauge column of a barimpact run's history.csv.
#pragma once

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

/// Reads the channel's signal. Throws InputError naming the section, the file
/// (and line) or column and the rule: a missing file or column, a cell that
/// is not a number, a time column that is not increasing, channels that are
/// not on one clock, clipping (3 or more consecutive samples at or beyond
/// `full_scale`, in the channel's own unit).
[[nodiscard]] GaugeSignal read_gauge_signal(const ChannelSetup& channel);

}  // namespace barimpact
