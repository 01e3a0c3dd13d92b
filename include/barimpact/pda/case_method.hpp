// The analysis of a measured blow as a pile-driving analyser makes it on site
// (`barimpact pda`): the waves down and up at the gauges, the maxima of
// force, velocity, energy and displacement, the stresses along the pile, the
// Case method's static resistance (Rausche, Goble & Likins 1985; ASTM D4945)
// and Rausche and Goble's integrity factor BTA (1979).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "barimpact/pda/record.hpp"

namespace barimpact {

/// The wave down Wd = (F + Z v) / 2 and the wave up Wu = (F - Z v) / 2 at
/// the gauges, N, at the record's samples.
struct PileWaves {
  std::vector<double> t;
  std::vector<double> velocity_z;  ///< Z v, N
  std::vector<double> down, up;

  /// Wd or Wu at time `at` by linear interpolation between samples (the
  /// first or last value outside the record).
  [[nodiscard]] double down_at(double at) const;
  [[nodiscard]] double up_at(double at) const;
};

/// Splits the record's force and velocity into the waves, with Z at the gauges.
[[nodiscard]] PileWaves pile_waves(const PileRecord& record, const PileSignals& signals);

/// The Case method's static resistance at time t: (1 - J_c) Wd(t) + (1 + J_c) Wu(t + 2L/c).
[[nodiscard]] double case_resistance(const PileWaves& w, double t, double travel_time, double damping);

/// summary.json's quantities (SI: s, N, m/s, J, m, Pa).
struct CaseMethodResult {
  PileRecord record;
  PileSignals signals;
  PileWaves waves;
  double t_foot = 0.0, t1 = 0.0, t2 = 0.0;
  double fmx = 0.0;  ///< the largest force
  double vmx = 0.0;  ///< the largest velocity
  double emx = 0.0;  ///< the largest of the energy's integral of F v dt
  double dmx = 0.0;  ///< the largest displacement
  double csx = 0.0;  ///< fmx / A at the gauges
  double tsx = 0.0;  ///< the largest tension stress along the pile within [t1, t2] (a magnitude, 0 if none)
  double tsx_time = 0.0, tsx_depth = 0.0;  ///< where tsx is: t at the gauges, depth below them
  double rmx = 0.0, rmx_time = 0.0;        ///< the largest Case resistance over [t1, min(t1 + 30 ms, t_end - 2L/c)]
  double rsp = 0.0;                        ///< the Case resistance at t1
  double bta = 1.0;                        ///< beta, 1 for an intact pile
  std::optional<double> bta_depth;         ///< below the gauges, where the wave up is least
  double ratio_at_impact = 0.0;            ///< F / (Z v) at t1
};

/// Analyses a record's signals.
[[nodiscard]] CaseMethodResult analyse_pda(const PileRecord& record, PileSignals signals);
/// Reads the record's signals and analyses them.
[[nodiscard]] CaseMethodResult analyse_pda(const PileRecord& record);

/// pda.csv's columns, in order: the contract's six (t, force, velocity_z,
/// wave_down, wave_up, displacement), then velocity and energy.
[[nodiscard]] const std::vector<std::string>& pda_columns();
/// The files the analysis writes (its figures aside).
[[nodiscard]] const std::vector<std::string>& pda_files();
/// pda.csv's text, one row a sample.
[[nodiscard]] std::string pda_csv(const CaseMethodResult& r);
/// summary.json's text.
[[nodiscard]] std::string pda_summary_json(const CaseMethodResult& r);

}  // namespace barimpact
