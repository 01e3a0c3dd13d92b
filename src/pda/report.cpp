// pda.csv and summary.json of a record's analysis.
#include <nlohmann/json.hpp>
#include <utility>

#include "../study/csv_cells.hpp"
#include "barimpact/pda/case_method.hpp"

namespace barimpact {

const std::vector<std::string>& pda_columns() {
  static const std::vector<std::string> c{"t",       "force",        "velocity_z", "wave_down",
                                          "wave_up", "displacement", "velocity",   "energy"};
  return c;
}

const std::vector<std::string>& pda_files() {
  static const std::vector<std::string> f{"pda.csv", "summary.json"};
  return f;
}

std::string pda_csv(const CaseMethodResult& r) {
  const auto& s = r.signals;
  const auto& w = r.waves;
  std::string out;
  for (const auto& name : pda_columns()) {
    if (!out.empty()) out += ',';
    out += name;
  }
  out += '\n';
  for (std::size_t k = 0; k < s.t.size(); ++k) {
    out += detail::csv_number(s.t[k]);
    for (double v : {s.force[k], w.velocity_z[k], w.down[k], w.up[k], s.displacement[k], s.velocity[k], s.energy[k]}) {
      out += ',';
      out += detail::csv_number(v);
    }
    out += '\n';
  }
  return out;
}

std::string pda_summary_json(const CaseMethodResult& r) {
  using nlohmann::ordered_json;
  const auto& rec = r.record;
  ordered_json j;
  // The contract's keys first, then what the quantities were computed from.
  const std::pair<const char*, double> numbers[] = {
      {"t1", r.t1},   {"t2", r.t2},   {"fmx", r.fmx}, {"vmx", r.vmx},           {"emx", r.emx}, {"dmx", r.dmx},
      {"csx", r.csx}, {"tsx", r.tsx}, {"rmx", r.rmx}, {"rmx_time", r.rmx_time}, {"rsp", r.rsp}, {"bta", r.bta}};
  for (const auto& [key, value] : numbers) j[key] = value;
  j["bta_depth"] = r.bta_depth ? ordered_json(*r.bta_depth) : ordered_json(nullptr);
  const std::pair<const char*, double> inputs[] = {{"t_foot", r.t_foot},
                                                   {"damping", rec.damping},
                                                   {"impedance", rec.impedance()},
                                                   {"area", rec.area()},
                                                   {"length", rec.length()},
                                                   {"travel_time", rec.travel_time()},
                                                   {"ratio_at_impact", r.ratio_at_impact},
                                                   {"tsx_time", r.tsx_time},
                                                   {"tsx_depth", r.tsx_depth}};
  for (const auto& [key, value] : inputs) j[key] = value;
  j["samples"] = r.signals.t.size();
  j["baseline_samples"] = r.signals.baseline;
  j["units"] = {{"system", "SI"}, {"force", "N"}, {"length", "m"}, {"time", "s"}, {"stress", "Pa"}, {"energy", "J"}};
  j["record"] = rec.origin.string();
  j["file"] = rec.csv.string();
  return j.dump(2) + "\n";
}

}  // namespace barimpact
