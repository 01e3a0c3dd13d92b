// The split Hopkinson bar analysis: from the incident and transmitted gauge
// signals to the specimen's stress, strain and strain rate by the 1-, 2- and
// 3-wave formulas (Kolsky 1949; Gray, ASM Handbook 8, 2000; Chen & Song,
// Split Hopkinson (Kolsky) Bar, 2011, ch. 2).
//
// One-dimensional waves in elastic bars: a strain eps travelling in a bar of
// modulus E, area A_b and wave speed c0 carries the force -E A_b eps
// (compression positive) and the particle velocity -/+ c0 eps. With the
// gauge strains eps_i, eps_r, eps_t (tension positive) moved to the
// specimen's faces by travel times, the faces carry
//   force_front = -E A_b (eps_i + eps_r),   force_back = -E A_b eps_t,
// and approach each other at c0 (eps_r - eps_i + eps_t), so that
//   stress_1w = force_back / A_s,  stress_2w = force_front / A_s,
//   stress_3w = (force_front + force_back) / (2 A_s),
//   strain_rate_1w = 2 c0 eps_r / L_s   (equilibrium: eps_t = eps_i + eps_r),
//   strain_rate_3w = c0 (eps_r + eps_t - eps_i) / L_s,
// strains their integrals from t = 0, every output compression positive, and
//   equilibrium = 2 (force_front - force_back) / (force_front + force_back).
//
// Alignment: each signal loses its mean over the record before the incident
// pulse's foot; the foot is the last sample before the trigger crossing
// (trigger x the incident peak) at or below 2% of the peak, found again on
// the new baseline until it stays (on a moving average when the record is
// noisy, so that noise passes for neither the pulse nor its foot). t = 0 when the foot reaches the front
// face. The reflected and transmitted pulses are placed by the travel times
// 2 d_i / c0 and (d_i + d_t) / c0 alone, and read between samples by linear
// interpolation.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "barimpact/hopkinson/setup.hpp"
#include "barimpact/hopkinson/signal.hpp"

namespace barimpact {

/// One column of hopkinson.csv: one value per row (nan where missing).
struct HopkinsonColumn {
  std::string name;
  std::vector<double> values;
};

/// How a pulse was placed, in the gauge's own clock.
struct PulseWindow {
  double start = 0.0;
  double end = 0.0;
};

struct HopkinsonAlignment {
  std::string method;              ///< "trigger" or "windows"
  double baseline_incident = 0.0;  ///< the means subtracted
  double baseline_transmitted = 0.0;
  double noise_incident = 0.0;  ///< the rms about them
  double noise_transmitted = 0.0;
  double incident_peak = 0.0;      ///< the incident pulse's largest compression (a strain > 0)
  double trigger_level = 0.0;      ///< trigger x incident_peak
  int iterations = 0;              ///< baseline-foot rounds until the foot stayed
  double foot = 0.0;               ///< the incident foot's time at its gauge (t = 0 at the face)
  double to_front_face = 0.0;      ///< d_i / c0_i
  double reflected_shift = 0.0;    ///< 2 d_i / c0_i: reflected sample = incident sample + this
  double transmitted_shift = 0.0;  ///< d_i / c0_i + d_t / c0_t (or a given [transmitted] start - foot)
  PulseWindow incident, reflected, transmitted;
  double wave_speed_incident = 0.0, wave_speed_transmitted = 0.0;
  int dispersion_terms = 0;  ///< Fourier terms corrected (0: none)
  std::string dispersion_note;
};

/// A peak of a column: its value and time (nan when the column has none).
struct HopkinsonPeak {
  double value = 0.0;
  double t = 0.0;
};

struct HopkinsonFit {
  bool done = false;
  std::string message;            ///< why a part is missing, if one is
  double modulus = 0.0;           ///< least-squares slope over the elastic stress range
  double strain_intercept = 0.0;  ///< where that line crosses sigma = 0
  int elastic_points = 0;
  std::optional<double> yield_stress;  ///< 0.2% offset
  std::optional<double> yield_strain;
  std::optional<double> hardening_modulus;  ///< the slope past yield
  std::pair<double, double> elastic_range{0, 0}, plastic_range{0, 0};
  int plastic_points = 0;
};

struct HopkinsonResult {
  HopkinsonSetup setup;                  ///< as read, with the runs' values filled in
  std::vector<HopkinsonColumn> columns;  ///< hopkinson.csv's, in order; the contract's 11 first
  HopkinsonAlignment alignment;
  HopkinsonPeak peak_stress_1w, peak_stress_2w, peak_stress_3w, peak_strain_rate_1w, peak_strain_rate_3w;
  std::optional<double> equilibrium_from;   ///< from then to the 3-wave peak stress, |equilibrium| < 0.05
  std::optional<double> equilibrium_first;  ///< the first time |equilibrium| < 0.05
  HopkinsonFit fit;
  std::vector<std::string> warnings;

  /// A column by name; throws std::out_of_range for a name it does not have.
  [[nodiscard]] const std::vector<double>& column(const std::string& name) const;
  [[nodiscard]] std::vector<double>& column(const std::string& name);
};

/// The contract's columns of hopkinson.csv, in order.
[[nodiscard]] const std::vector<std::string>& hopkinson_columns();

/// Analyses the two signals. Throws InputError (one line naming the section,
/// the file and the rule) for a signal that cannot be analysed: a missing
/// pulse, baseline noise above half the trigger level, an incident window
/// longer than 2 gauge_to_specimen / c0, a record too short.
[[nodiscard]] HopkinsonResult analyse_hopkinson(const HopkinsonSetup& setup, GaugeSignal incident,
                                                GaugeSignal transmitted);

/// Reads the setup's two signals (the incident's errors first) and analyses them.
[[nodiscard]] HopkinsonResult analyse_hopkinson(const HopkinsonSetup& setup);

/// Reads the setup file and its signals and analyses them.
[[nodiscard]] HopkinsonResult analyse_hopkinson(const std::filesystem::path& setup_file);

/// hopkinson.csv's text (numbers in their shortest exact form, `nan` where missing).
[[nodiscard]] std::string hopkinson_csv(const HopkinsonResult& r);
/// summary.json's text.
[[nodiscard]] std::string hopkinson_summary_json(const HopkinsonResult& r);

}  // namespace barimpact
