// Signal matching's simulated static load test and its files: match.csv,
// soil.csv, static.csv and summary.json.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "barimpact/study/match.hpp"
#include "csv_cells.hpp"

namespace barimpact {

namespace {

// A Smith spring loaded monotonically to w >= 0: elastic to its quake, then R_u.
double spring(double ultimate, double quake, double w) {
  return std::min(ultimate, ultimate * w / quake);
}

// The pile pushed slowly at the head: from the toe's settlement w0 up, each
// element shortens by the force it carries (the resistances below) over
// its stiffness E A / h. Returns the head's settlement and its load.
std::pair<double, double> push(const Line& line, double w0) {
  const auto& s = line.shaft;
  const auto& toe = line.links.front().law.soil;
  double w = w0, carried = spring(toe.ultimate, toe.quake, w0);
  for (std::size_t j = 0;; ++j) {
    if (s.ultimate[j] > 0.0) carried += spring(s.ultimate[j], s.quake[j], w);
    if (j + 1 == line.nodes()) return {w, carried};
    w += carried / line.bonds[j].stiffness;
  }
}

}  // namespace

StaticTest static_load_test(const MatchModel& model, const MatchSoil& soil) {
  Line line = model.line();
  model.apply(soil, line);
  StaticTest t;
  // s_C: the largest quake plus the shortening with every spring at R_u, the
  // sum over elements of the resistance below over E A / h (the integral of
  // N / E A along the pile: R_toe L + sum R_i z_i over E A on a uniform pile).
  double carried = soil.toe, shortening = 0.0;
  for (std::size_t j = 0; j + 1 < line.nodes(); ++j) {
    carried += line.shaft.ultimate[j];
    shortening += carried / line.bonds[j].stiffness;
  }
  t.s_c = std::max(soil.toe_quake, soil.shaft_quake) + shortening;
  // The closed form with E A at the gauges (the far end's element):
  // s_c itself on a uniform pile, not on [[segment]]s of other sections.
  double moment = soil.toe * model.segment_bottom(model.segments() - 1);
  for (std::size_t i = 0; i < soil.shaft.size(); ++i)
    moment += soil.shaft[i] * 0.5 * (model.segment_top(i) + model.segment_bottom(i));
  t.s_c_uniform = std::max(soil.toe_quake, soil.shaft_quake) + moment / line.bonds.back().axial;
  constexpr int increments = 150;
  for (int i = 0; i <= increments; ++i) {
    const double s = 1.5 * t.s_c * i / increments;
    // The toe's settlement for head settlement s, by bisection (s grows with it).
    double lo = 0.0, hi = s;
    for (int k = 0; k < 200 && hi - lo > 1e-15 * s; ++k) {
      const double mid = 0.5 * (lo + hi);
      (push(line, mid).first < s ? lo : hi) = mid;
    }
    t.settlement.push_back(s);
    t.load.push_back(push(line, 0.5 * (lo + hi)).second);
  }
  return t;
}

const std::vector<std::string>& match_files() {
  static const std::vector<std::string> f{"match.csv", "soil.csv", "static.csv", "summary.json"};
  return f;
}

std::string match_csv(const MatchResult& r) {
  const auto& sig = r.pda.signals;
  const double z = r.pda.record.impedance();
  std::string out = "t,force_measured,force_computed,velocity_z,wave_up_measured,wave_up_computed\n";
  for (std::size_t k = 0; k < r.computed.size(); ++k) {
    const std::size_t i = r.first + k;
    const double zv = z * sig.velocity[i];
    out += detail::csv_number(sig.t[i]);
    for (double v : {sig.force[i], r.computed[k], zv, 0.5 * (sig.force[i] - zv), 0.5 * (r.computed[k] - zv)}) {
      out += ',';
      out += detail::csv_number(v);
    }
    out += '\n';
  }
  return out;
}

// A depth to the nanometre, so that 19.2 m less 18 m reads 1.2.
static std::string depth_cell(double x) {
  return detail::csv_number(std::round(x * 1e9) / 1e9);
}

std::string soil_csv(const MatchResult& r) {
  const auto& s = r.soil;
  std::string out = "segment,top,bottom,resistance,quake,damping\n";
  for (std::size_t i = 0; i < s.shaft.size(); ++i)
    out += fmt::format("{},{},{},{},{},{}\n", i + 1, depth_cell(r.segment_top[i]), depth_cell(r.segment_bottom[i]),
                       detail::csv_number(s.shaft[i]), detail::csv_number(s.shaft_quake),
                       detail::csv_number(s.shaft_damping));
  const double l = r.pda.record.length();
  out += fmt::format("toe,{},{},{},{},{}\n", depth_cell(l), depth_cell(l), detail::csv_number(s.toe),
                     detail::csv_number(s.toe_quake), detail::csv_number(s.toe_damping));
  return out;
}

std::string static_csv(const MatchResult& r) {
  std::string out = "settlement,load\n";
  for (std::size_t i = 0; i < r.static_test.settlement.size(); ++i)
    out += detail::csv_number(r.static_test.settlement[i]) + ',' + detail::csv_number(r.static_test.load[i]) + '\n';
  return out;
}

namespace {

nlohmann::ordered_json start_json(const MatchStart& st) {
  return {{"capacity", st.soil.capacity()}, {"shaft", st.soil.shaft_total()}, {"toe", st.soil.toe},
          {"match_quality", st.quality},    {"objective", st.objective},      {"start_capacity", st.start.capacity()},
          {"iterations", st.iterations},    {"evaluations", st.evaluations},  {"converged", st.converged},
          {"message", st.message}};
}

// The matched soil and the settings it was matched with.
void add_soil(nlohmann::ordered_json& j, const MatchResult& r) {
  const auto& s = r.soil;
  j["shaft_quake"] = s.shaft_quake;
  j["toe_quake"] = s.toe_quake;
  j["shaft_damping"] = s.shaft_damping;
  j["toe_damping"] = s.toe_damping;
  j["damping_law"] = s.law == DampingLaw::smith ? "smith" : "viscous";
  j["segments"] = s.shaft.size();
  j["embedded"] = r.embedded;
  j["smoothing"] = r.pda.record.match.smoothing;
}

// What of the record was matched: the window, the filter, the Case method's references.
void add_record(nlohmann::ordered_json& j, const MatchResult& r) {
  j["window"] = r.window;
  j["low_pass"] = r.pda.signals.filtered ? nlohmann::ordered_json(r.pda.signals.cutoff) : nullptr;
  if (!r.pda.signals.filter_note.empty()) j["low_pass_note"] = r.pda.signals.filter_note;
  j["window_start"] = r.pda.t_foot;
  j["window_end"] = r.pda.t2 + r.window;
  j["samples_matched"] = r.computed.size();
  j["s_c"] = r.static_test.s_c;
  j["s_c_uniform"] = r.static_test.s_c_uniform;
  j["case_method_rmx"] = r.pda.rmx;
  j["t1"] = r.pda.t1;
  j["t2"] = r.pda.t2;
  j["impedance"] = r.pda.record.impedance();
  j["length"] = r.pda.record.length();
}

}  // namespace

std::string match_summary_json(const MatchResult& r) {
  nlohmann::ordered_json j;
  const auto& s = r.soil;
  // The contract's keys first.
  j["capacity"] = s.capacity();
  j["shaft"] = s.shaft_total();
  j["toe"] = s.toe;
  j["match_quality"] = r.quality;
  j["evaluations"] = r.evaluations;
  j["iterations"] = r.iterations;
  j["starts"] = r.starts.size();
  j["spread"] = r.spread();
  j["spread_relative"] = s.capacity() > 0.0 ? r.spread() / s.capacity() : 0.0;
  j["best_start"] = r.best + 1;
  j["converged"] = r.converged();
  add_soil(j, r);
  add_record(j, r);
  j["seconds"] = r.seconds;
  j["start_results"] = nlohmann::ordered_json::array();
  for (const auto& st : r.starts) j["start_results"].push_back(start_json(st));
  j["warnings"] = r.warnings();
  j["units"] = {{"system", "SI"}, {"force", "N"}, {"length", "m"}, {"time", "s"}, {"damping", "s/m"}};
  j["record"] = r.pda.record.origin.string();
  j["file"] = r.pda.record.csv.string();
  return j.dump(2) + "\n";
}

}  // namespace barimpact
