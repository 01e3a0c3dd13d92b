// The setup of a split Hopkinson pressure bar analysis (`barimpact hopkinson
// SETUP.toml`): the bars, the specimen, and where each gauge's signal comes
// from (a measured file, or a gauge of a barimpact run), read from TOML and
// validated.
//
// This header owns the setup-file contract: sections [bar], [specimen],
// [incident], [transmitted], [window], [fit], their keys, defaults and rules.
// Reading the signals themselves is signal.hpp's; the analysis analysis.hpp's.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "barimpact/run/output_directory.hpp"

namespace barimpact {

/// One bar (incident or transmitter): material and size. `wave_speed` c0
/// defaults to sqrt(E / rho); a calibrated one sets travel times and strain rates.
struct HopkinsonBar {
  double modulus = 0.0;     ///< E
  double density = 0.0;     ///< rho
  double area = 0.0;        ///< A_b
  double diameter = 0.0;    ///< for the dispersion correction (from the area when not given)
  double wave_speed = 0.0;  ///< c0
  double poisson = -1.0;    ///< nu (< 0: not given)
  bool dispersion = false;  ///< correct measured pulses for Pochhammer-Chree dispersion
};

struct HopkinsonSpecimen {
  double length = 0.0;  ///< L_s, initial
  double area = 0.0;    ///< A_s, initial
  std::string body;     ///< the specimen's body in a barimpact run
};

/// The bridge of a gauge recorded in volts: n in eps = n V / (gain excitation gauge_factor).
enum class Bridge { quarter = 4, half = 2, full = 1 };

/// One gauge's channel ([incident] or [transmitted]).
struct ChannelSetup {
  std::string section;                                ///< "incident" or "transmitted"
  std::vector<std::filesystem::path> files;           ///< one, or several on one clock (averaged)
  std::string time_column = "t";                      ///< empty with sample_interval
  std::vector<std::string> strain_columns{"strain"};  ///< averaged sample by sample
  bool volts = false;                                 ///< the columns hold volts, converted by the bridge
  double gauge_factor = 0.0;
  double excitation = 0.0;
  Bridge bridge = Bridge::quarter;
  double gain = 1.0;
  double polarity = 1.0;  ///< +1, or -1 for a bridge recording compression positive
  bool header = true;
  double sample_interval = 0.0;  ///< > 0: t_k = k dt, no time column
  char delimiter = ',';
  int skip_rows = 0;
  std::optional<double> full_scale;  ///< the channel's range, in its own unit (clipping)
  double gauge_to_specimen = -1.0;   ///< from a run's case when not given
  std::optional<double> start, end;  ///< the pulse's window at the gauge, instead of the trigger
  std::filesystem::path run;         ///< a barimpact run directory, instead of files
  std::string gauge;                 ///< the run's gauge
};

struct HopkinsonSetup {
  std::filesystem::path origin;                ///< the setup file, for messages
  std::filesystem::path file;                  ///< the setup file read (from_file), empty for text
  HopkinsonBar incident_bar, transmitter_bar;  ///< one [bar]; a run may give two
  HopkinsonSpecimen specimen;
  ChannelSetup incident, transmitted;
  double trigger = 0.1;  ///< [window] trigger: the fraction of the incident peak that finds the pulse
  std::optional<std::pair<double, double>> fit_elastic;  ///< [fit] elastic: a stress range
  std::optional<std::pair<double, double>> fit_plastic;  ///< [fit] plastic: a strain range
  /// In SI (m, s, Pa, kg/m^3): the numbers are checked against what a
  /// laboratory's bars, specimens and records can be (false for a run whose
  /// case says `[units] system = "none"`).
  bool si = true;

  /// Reads and validates a setup file; relative paths in it are relative to
  /// its directory (or, when nothing is there but something is in the
  /// working directory, to that). A section that names a `run` takes the gauge's distance,
  /// and [bar] and [specimen] (keys the setup gives win), from the run's
  /// case.toml. Throws InputError naming the key and the rule.
  static HopkinsonSetup from_file(const std::filesystem::path& path);
  /// The same from TOML text; relative paths are relative to `base`.
  static HopkinsonSetup from_string(const std::string& toml, const std::filesystem::path& base,
                                    const std::string& origin = "setup");
};

/// What the analysis reads: the setup file, the signal files and the runs'
/// directories, which its results never overwrite.
[[nodiscard]] CommandInputs hopkinson_inputs(const HopkinsonSetup& setup);

}  // namespace barimpact
