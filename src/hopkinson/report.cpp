// hopkinson.csv and summary.json of an analysis.
#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "../study/csv_cells.hpp"
#include "barimpact/hopkinson/analysis.hpp"

namespace barimpact {

namespace {

using nlohmann::ordered_json;

// A number, or null where there is none.
ordered_json number(double v) {
  return std::isfinite(v) ? ordered_json(v) : ordered_json(nullptr);
}
ordered_json number(const std::optional<double>& v) {
  return v ? number(*v) : ordered_json(nullptr);
}

ordered_json window(const PulseWindow& w) {
  return ordered_json::array({number(w.start), number(w.end)});
}

ordered_json peak(const HopkinsonPeak& p) {
  return {{"value", number(p.value)}, {"t", number(p.t)}};
}

ordered_json alignment(const HopkinsonAlignment& a) {
  ordered_json j;
  j["method"] = a.method;
  j["baseline"] = {{"incident", a.baseline_incident}, {"transmitted", a.baseline_transmitted}};
  j["noise_rms"] = {{"incident", a.noise_incident}, {"transmitted", a.noise_transmitted}};
  j["incident_peak"] = a.incident_peak;
  j["trigger_level"] = a.trigger_level;
  j["iterations"] = a.iterations;
  j["foot"] = a.foot;
  j["wave_speed"] = {{"incident", a.wave_speed_incident}, {"transmitted", a.wave_speed_transmitted}};
  j["shift"] = {
      {"front_face", a.to_front_face}, {"reflected", a.reflected_shift}, {"transmitted", a.transmitted_shift}};
  j["windows"] = {
      {"incident", window(a.incident)}, {"reflected", window(a.reflected)}, {"transmitted", window(a.transmitted)}};
  j["dispersion"] = {{"applied", a.dispersion_terms > 0}, {"terms", a.dispersion_terms}, {"note", a.dispersion_note}};
  return j;
}

ordered_json fit(const HopkinsonFit& f) {
  ordered_json j;
  j["modulus"] = f.modulus > 0 ? ordered_json(f.modulus) : ordered_json(nullptr);
  // yield_stress and hardening_modulus only for a yielding specimen, as the contract has them.
  if (f.yield_stress) j["yield_stress"] = *f.yield_stress;
  if (f.hardening_modulus) j["hardening_modulus"] = *f.hardening_modulus;
  if (f.yield_strain) j["yield_strain"] = *f.yield_strain;
  j["strain_intercept"] = f.modulus > 0 ? ordered_json(f.strain_intercept) : ordered_json(nullptr);
  j["elastic_range"] = {f.elastic_range.first, f.elastic_range.second};
  j["elastic_points"] = f.elastic_points;
  if (f.yield_stress) {
    j["plastic_range"] = {f.plastic_range.first, f.plastic_range.second};
    j["plastic_points"] = f.plastic_points;
  }
  j["offset"] = 0.002;
  j["curve"] = "3-wave";
  if (!f.message.empty()) j["message"] = f.message;
  return j;
}

}  // namespace

std::string hopkinson_csv(const HopkinsonResult& r) {
  std::string out;
  for (std::size_t c = 0; c < r.columns.size(); ++c) out += (c ? "," : "") + r.columns[c].name;
  out += '\n';
  const std::size_t rows = r.columns.empty() ? 0 : r.columns.front().values.size();
  for (std::size_t i = 0; i < rows; ++i) {
    for (std::size_t c = 0; c < r.columns.size(); ++c) {
      if (c) out += ',';
      out += detail::csv_number(r.columns[c].values[i]);
    }
    out += '\n';
  }
  return out;
}

std::string hopkinson_summary_json(const HopkinsonResult& r) {
  const auto& s = r.setup;
  ordered_json j;
  j["setup"] = s.origin.string();
  j["rows"] = r.columns.empty() ? 0 : r.columns.front().values.size();
  j["alignment"] = alignment(r.alignment);
  j["peak_stress"] = number(r.peak_stress_3w.value);
  j["peak_strain_rate"] = number(r.peak_strain_rate_3w.value);
  j["peaks"] = {{"stress_1w", peak(r.peak_stress_1w)},
                {"stress_2w", peak(r.peak_stress_2w)},
                {"stress_3w", peak(r.peak_stress_3w)},
                {"strain_rate_1w", peak(r.peak_strain_rate_1w)},
                {"strain_rate_3w", peak(r.peak_strain_rate_3w)}};
  j["equilibrium_from"] = number(r.equilibrium_from);
  j["equilibrium_first"] = number(r.equilibrium_first);
  j["equilibrium_tolerance"] = 0.05;
  if (r.fit.done) j["fit"] = fit(r.fit);
  auto bar = [](const HopkinsonBar& b) {
    return ordered_json{{"modulus", b.modulus}, {"density", b.density}, {"area", b.area}, {"wave_speed", b.wave_speed}};
  };
  j["bars"] = {{"incident", bar(s.incident_bar)}, {"transmitter", bar(s.transmitter_bar)}};
  j["specimen"] = {{"length", s.specimen.length}, {"area", s.specimen.area}};
  j["gauge_to_specimen"] = {{"incident", s.incident.gauge_to_specimen},
                            {"transmitted", s.transmitted.gauge_to_specimen}};
  j["warnings"] = r.warnings;
  return j.dump(2) + "\n";
}

}  // namespace barimpact
