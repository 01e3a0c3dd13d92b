#include "barimpact/case/drive.hpp"

#include "barimpact/case/case.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <string>
#include <utility>

#include "barimpact/model/input_error.hpp"
#include "toml_input.hpp"

namespace barimpact {

namespace detail {
extern const char hammers_toml[];  // data/hammers.toml, compiled in (hammers_data.cpp)
}

const LayerData& DriveData::layer_at(double z) const {
  for (const auto& l : layers)
    if (l.top <= z && z < l.bottom) return l;
  return layers.back();  // the last layer includes its bottom
}

// The layers from the ground down to the toe, as pieces along the pile from
// the toe (x = depth - z): deeper layers first. A layer whose top is the toe's
// depth is a piece of no length, so that the toe's node takes its soil.
DriveSoil soil_at(const DriveData& drive, double depth, double toe_area) {
  DriveSoil s;
  const double p = drive.perimeter;
  for (auto l = drive.layers.rbegin(); l != drive.layers.rend(); ++l) {
    if (l->top > depth) continue;
    const double deepest = std::min(l->bottom, depth);
    ShaftPiece piece;
    piece.from = depth - deepest;
    piece.to = depth - l->top;
    piece.resistance_from = p * l->shaft_at(deepest);
    piece.resistance_to = p * l->shaft_at(l->top);
    piece.soil = l->shaft;
    s.shaft.push_back(piece);
    s.shaft_capacity += piece.ultimate();
    s.long_term_capacity += l->setup * piece.ultimate();
  }
  const LayerData& at = drive.layer_at(depth);
  s.toe = at.toe_soil;
  s.toe_capacity = s.toe.ultimate = toe_area * at.toe;
  s.long_term_capacity += s.toe_capacity;
  return s;
}

void start_ram(Case& c, double stroke) {
  HammerData& h = *c.hammer;
  h.stroke = stroke;
  const double g = drive_gravity(c.load.gravity);
  const bool diesel = h.kind == HammerKind::diesel;
  const double v =
      diesel ? std::sqrt(2.0 * g * std::max(0.0, stroke - h.diesel.compression_length)) : h.impact_velocity(g);
  for (auto& b : c.bodies)
    if (b.name == h.ram) b.velocity = fmt::format("{}", -v);
}

std::vector<double> linear_range(double from, double to, long long count) {
  std::vector<double> v;
  for (long long i = 0; i < count; ++i) {
    const double x = count == 1 ? from
                                : (from * static_cast<double>(count - 1 - i) + to * static_cast<double>(i)) /
                                      static_cast<double>(count - 1);
    v.push_back(std::stod(fmt::format("{:.12g}", x)));
  }
  return v;
}

std::string_view to_string(HammerKind kind) {
  switch (kind) {
    case HammerKind::drop:
      return "drop";
    case HammerKind::hydraulic:
      return "hydraulic";
    case HammerKind::air_steam:
      return "air-steam";
    case HammerKind::diesel:
      return "diesel";
  }
  return "?";
}

namespace {

// One [[hammer]] entry's number (0 when absent and not required).
double entry_number(const toml::table& t, std::string_view key, const std::string& where, bool required) {
  const auto* n = t.get(key);
  if (n == nullptr) {
    if (required) throw InputError(fmt::format("{}: {} is required", where, key));
    return 0.0;
  }
  const auto v = n->value<double>();
  if (!v || !std::isfinite(*v) || *v < 0)
    throw InputError(fmt::format("{}: {} must be a finite number >= 0", where, key));
  return *v;
}

HammerModel read_entry(const toml::table& t, const std::string& where) {
  HammerModel h;
  const auto name = t.get_as<std::string>("name");
  const auto kind = t.get_as<std::string>("kind");
  if (name == nullptr || kind == nullptr) throw InputError(fmt::format("{}: name and kind are required", where));
  h.name = name->get();
  const std::string k = kind->get();
  const std::array<std::pair<const char*, HammerKind>, 4> kinds{{{"drop", HammerKind::drop},
                                                                 {"hydraulic", HammerKind::hydraulic},
                                                                 {"air-steam", HammerKind::air_steam},
                                                                 {"diesel", HammerKind::diesel}}};
  const auto it = std::find_if(kinds.begin(), kinds.end(), [&](const auto& p) { return k == p.first; });
  if (it == kinds.end())
    throw InputError(
        fmt::format("{} ({}): kind must be drop, hydraulic, air-steam or diesel (got \"{}\")", where, h.name, k));
  h.kind = it->second;
  const std::string at = fmt::format("{} ({})", where, h.name);
  h.ram_mass = entry_number(t, "ram_mass", at, true);
  h.stroke = entry_number(t, "stroke", at, false);
  h.energy = entry_number(t, "energy", at, false);
  if ((h.stroke > 0) == (h.energy > 0)) throw InputError(fmt::format("{}: give stroke or energy (one, > 0)", at));
  h.efficiency = entry_number(t, "efficiency", at, true);
  h.cushion_stiffness = entry_number(t, "cushion_stiffness", at, true);
  h.cushion_restitution = entry_number(t, "cushion_restitution", at, true);
  h.helmet_mass = entry_number(t, "helmet_mass", at, true);
  if (const auto* s = t.get_as<std::string>("source")) h.source = s->get();
  if (h.ram_mass <= 0 || h.helmet_mass <= 0 || h.cushion_stiffness <= 0 || h.efficiency <= 0 || h.efficiency > 1 ||
      h.cushion_restitution <= 0 || h.cushion_restitution > 1)
    throw InputError(fmt::format(
        "{}: ram_mass, helmet_mass, cushion_stiffness > 0, efficiency and cushion_restitution in (0, 1]", at));
  if (h.kind == HammerKind::diesel) {
    DieselData& d = h.diesel;
    d.anvil_mass = entry_number(t, "anvil_mass", at, true);
    d.cylinder_area = entry_number(t, "cylinder_area", at, true);
    d.compression_length = entry_number(t, "compression_length", at, true);
    d.chamber_length = entry_number(t, "chamber_length", at, true);
    d.combustion_pressure = entry_number(t, "combustion_pressure", at, true);
    d.max_stroke = entry_number(t, "max_stroke", at, true);
  }
  return h;
}

}  // namespace

std::vector<HammerModel> read_hammer_table(std::string_view text, std::string_view origin) {
  const toml::table root = parse_toml(text, origin);
  const auto* a = root.get_as<toml::array>("hammer");
  if (a == nullptr || !a->is_array_of_tables() || a->empty())
    throw InputError(fmt::format("{}: a hammer table lists [[hammer]] entries", origin));
  std::vector<HammerModel> out;
  for (std::size_t i = 0; i < a->size(); ++i)
    out.push_back(read_entry(*(*a)[i].as_table(), fmt::format("{}: hammer[{}]", origin, i + 1)));
  return out;
}

std::string_view shipped_hammers_toml() {
  return detail::hammers_toml;
}

const std::vector<HammerModel>& shipped_hammers() {
  static const std::vector<HammerModel> table = read_hammer_table(shipped_hammers_toml(), "data/hammers.toml");
  return table;
}

}  // namespace barimpact
