#include "drive_input.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

namespace barimpact::detail {

namespace {

// The edit distance of two names, case folded: how near an unknown hammer is.
std::size_t distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      const bool same =
          std::tolower(static_cast<unsigned char>(a[i - 1])) == std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// The table [hammer] reads: the shipped one, or `table` (relative to the case file).
std::vector<HammerModel> hammer_table(const Reader& r) {
  const std::string file = r.word("hammer", "table", "");
  if (file.empty()) return shipped_hammers();
  std::filesystem::path path(file);
  std::error_code ec;
  if (path.is_relative() && std::filesystem::is_regular_file(r.origin(), ec))
    path = std::filesystem::path(r.origin()).parent_path() / path;
  try {
    return read_hammer_table(read_input_file(path, "hammer table"), path.string());
  } catch (const InputError& e) {
    r.fail("hammer", "table", fmt::format("cannot be used: {}", e.what()));
  }
}

const HammerModel& find_model(const Reader& r, const std::vector<HammerModel>& table, const std::string& name) {
  for (const auto& h : table)
    if (h.name == name) return h;
  std::vector<std::pair<std::size_t, std::string>> near;
  for (const auto& h : table) near.emplace_back(distance(name, h.name), fmt::format("\"{}\"", h.name));
  std::sort(near.begin(), near.end());
  std::vector<std::string> names;
  for (std::size_t i = 0; i < near.size() && i < 4; ++i) names.push_back(near[i].second);
  r.fail("hammer", "model",
         fmt::format("= \"{}\" is no hammer of the table (nearest: {}; `barimpact hammers` lists them)", name,
                     fmt::join(names, ", ")));
}

HammerKind read_kind(const Reader& r, const std::string& kind) {
  for (const auto k : {HammerKind::drop, HammerKind::hydraulic, HammerKind::air_steam, HammerKind::diesel})
    if (kind == to_string(k)) return k;
  r.fail("hammer", "kind", fmt::format("must be drop, hydraulic, air-steam or diesel (got \"{}\")", kind));
}

double default_efficiency(HammerKind kind) {
  return kind == HammerKind::hydraulic ? 0.95 : kind == HammerKind::diesel ? 0.8 : 0.67;
}

double body_mass(const BodyData& b) {
  return b.kind == BodyKind::mass ? b.mass : b.density * b.area * b.length;
}

std::optional<HammerData::Cushion> read_pile_cushion(const Reader& r) {
  const auto* n = r.node("hammer", "pile_cushion");
  if (n == nullptr) return std::nullopt;
  const auto* t = n->as_table();
  HammerData::Cushion k;
  const auto stiffness = t ? t->get("stiffness") : nullptr;
  const auto restitution = t ? t->get("restitution") : nullptr;
  if (t == nullptr || stiffness == nullptr || t->size() != (restitution ? 2U : 1U))
    r.fail("hammer", "pile_cushion", "must be a table { stiffness = N/m, restitution = e }");
  k.stiffness = stiffness->value<double>().value_or(-1.0);
  k.restitution = restitution ? restitution->value<double>().value_or(-1.0) : 0.8;
  if (!(k.stiffness > 0 && std::isfinite(k.stiffness) && k.restitution > 0 && k.restitution <= 1))
    r.fail("hammer", "pile_cushion", "needs stiffness > 0 (N/m) and restitution in (0, 1]");
  return k;
}

// drive.depths: "FROM:TO:COUNT" (linear) or a list, ascending, each in (0, length].
std::vector<double> read_depths(const Reader& r, double length) {
  const auto* n = r.node("drive", "depths");
  if (n == nullptr) r.fail("drive", "depths", "is required: \"FROM:TO:COUNT\" or a list of penetrations (m)");
  std::vector<double> d;
  if (const auto* text = n->as_string()) {
    const std::string t = text->get();
    double from = 0, to = 0;
    long long count = 0;
    int used = 0;
    if (std::sscanf(t.c_str(), "%lf:%lf:%lld%n", &from, &to, &count, &used) != 3 ||
        used != static_cast<int>(t.size()) || count < 1 || count > 100'000 || (count == 1 && from != to))
      r.fail("drive", "depths",
             fmt::format("= \"{}\": expected \"FROM:TO:COUNT\" (m, COUNT in [1, 100000]; 1 needs FROM = TO)", t));
    d = linear_range(from, to, count);
  } else {
    d = r.numbers("drive", "depths");
  }
  if (d.empty()) r.fail("drive", "depths", "lists no penetration");
  for (std::size_t i = 0; i < d.size(); ++i) {
    if (!(d[i] > 0 && d[i] <= length))
      r.fail("drive", "depths", fmt::format("must lie in (0, {}], the pile's length (got {})", length, d[i]));
    if (i > 0 && !(d[i] > d[i - 1])) r.fail("drive", "depths", "must ascend (from the ground down)");
  }
  return d;
}

SoilSpring read_layer_soil(const Reader& r, const std::string& s, const char* quake, const char* damping,
                           SoilSpring soil, DampingLaw law) {
  soil.quake = r.quantity(s, quake, soil.quake, Dimension::length);
  soil.damping = r.quantity(s, damping, soil.damping, Dimension::damping);
  soil.damping_law = law;
  if (!(soil.quake > 0)) r.fail(s, quake, fmt::format("must be > 0 (got {})", soil.quake));
  if (soil.quake > 0.1) r.fail(s, quake, fmt::format("= {}: mm? quakes are a few mm, in m (0.00254)", soil.quake));
  if (!(soil.damping >= 0)) r.fail(s, damping, fmt::format("must be >= 0 (got {})", soil.damping));
  if (soil.damping > 5.0)
    r.fail(s, damping, fmt::format("= {}: s/ft? Smith dampings are 0.1 to 1 s/m (0.16 sand, 0.65 clay)", soil.damping));
  return soil;
}

LayerData read_layer(Reader& r, const toml::table& t, std::size_t i, double top) {
  const std::string s = fmt::format("layer[{}]", i + 1);
  r.view(s, &t);
  LayerData l;
  for (const char* key : {"top", "bottom", "shaft", "toe"})
    if (r.node(s, key) == nullptr) r.fail(s, key, "is required");
  l.top = r.quantity(s, "top", 0.0, Dimension::length);
  l.bottom = r.quantity(s, "bottom", 0.0, Dimension::length);
  if (l.top != top)
    r.fail(s, "top",
           i == 0 ? fmt::format("must be 0: the layers start at the ground (got {})", l.top)
                  : fmt::format("must be {}, the bottom of the layer above (got {}: {})", top, l.top,
                                l.top > top ? "a gap" : "an overlap"));
  if (!(l.bottom > l.top)) r.fail(s, "bottom", fmt::format("must be below top = {} (got {})", l.top, l.bottom));
  const auto shaft = r.numbers(s, "shaft");
  if (shaft.empty() || shaft.size() > 2) r.fail(s, "shaft", "must be a number or [at the top, at the bottom] (Pa)");
  l.shaft_top = shaft.front();
  l.shaft_bottom = shaft.back();
  l.toe = r.quantity(s, "toe", 0.0, Dimension::stress);
  if (!(l.shaft_top >= 0 && l.shaft_bottom >= 0)) r.fail(s, "shaft", "must be >= 0 (Pa)");
  if (!(l.toe >= 0)) r.fail(s, "toe", fmt::format("must be >= 0 (Pa; got {})", l.toe));
  // Unit resistances in kPa (or kN) are the likely slip: no soil resists so little
  // (the softest clays: a few kPa along the shaft, some 50 kPa at the toe).
  for (const double v : {l.shaft_top, l.shaft_bottom})
    if (v > 0 && v < 500.0) r.fail(s, "shaft", fmt::format("= {}: kPa? unit resistances are in Pa (25e3)", v));
  if (l.toe > 0 && l.toe < 10e3) r.fail(s, "toe", fmt::format("= {}: kPa? unit resistances are in Pa (6e6)", l.toe));
  const std::string law = r.word(s, "damping_law", "smith");
  if (law != "smith" && law != "viscous")
    r.fail(s, "damping_law", fmt::format("must be smith or viscous (got \"{}\")", law));
  const DampingLaw dl = law == "smith" ? DampingLaw::smith : DampingLaw::viscous;
  l.shaft = read_layer_soil(r, s, "shaft_quake", "shaft_damping", l.shaft, dl);
  l.toe_soil = read_layer_soil(r, s, "toe_quake", "toe_damping", l.toe_soil, dl);
  l.setup = r.number(s, "setup", 1.0);
  if (!(l.setup > 0)) r.fail(s, "setup", fmt::format("must be > 0 (got {})", l.setup));
  return l;
}

// The pile [drive] drives: drive.pile, [blow] pile, else the bar nearest x = 0; it must be the first body.
std::size_t drive_pile(const Reader& r, const Case& c, const BodyIndex& index, std::string& name) {
  name = r.word("drive", "pile", c.blow.pile.empty() ? c.bodies.front().name : c.blow.pile);
  const std::size_t i = index(name);
  if (i == c.bodies.size()) r.fail("drive", "pile", fmt::format("names no body of the line (got \"{}\")", name));
  if (i != 0 || c.bodies[i].kind != BodyKind::bar)
    r.fail("drive", "pile", fmt::format("must be the bar at the near end, x = 0 (its toe; got \"{}\")", name));
  return i;
}

// Gives the pile the profile's soil at the analysed depth: its shaft as pieces, its toe as [near_end].
void apply_profile(Case& c, std::size_t pile) {
  const DriveData& d = *c.drive;
  BodyData& b = c.bodies[pile];
  const double depth = d.analysed_depth();
  const DriveSoil soil = soil_at(d, depth, d.toe_area.value_or(b.area));
  ShaftData shaft;
  shaft.profile = soil.shaft;
  shaft.soil.ultimate = soil.shaft_capacity;
  shaft.embedded = depth;
  b.shaft = shaft;
  c.near_end = LawData{};
  c.near_end.law = JointLaw::smith;
  c.near_end.soil = soil.toe;
}

// A diesel hammer by hand: its masses and cylinder ([hammer] keys).
void read_diesel(const Reader& r, HammerData& h) {
  DieselData& d = h.diesel;
  for (auto [key, field] :
       {std::pair{"ram_mass", &h.ram_mass}, std::pair{"anvil_mass", &d.anvil_mass},
        std::pair{"cylinder_area", &d.cylinder_area}, std::pair{"compression_length", &d.compression_length},
        std::pair{"chamber_length", &d.chamber_length}, std::pair{"combustion_pressure", &d.combustion_pressure},
        std::pair{"max_stroke", &d.max_stroke}}) {
    if (r.node("hammer", key) == nullptr) r.fail("hammer", key, "is required by a diesel hammer");
    *field = r.number("hammer", key, 0.0);
    if (!(*field > 0)) r.fail("hammer", key, fmt::format("must be > 0 (got {})", *field));
  }
  d.impact_stiffness = r.number("hammer", "impact_stiffness", d.impact_stiffness);
  d.impact_restitution = r.number("hammer", "impact_restitution", d.impact_restitution);
  if (!(d.impact_stiffness > 0)) r.fail("hammer", "impact_stiffness", "must be > 0 (N/m)");
  if (!(d.impact_restitution > 0 && d.impact_restitution <= 1))
    r.fail("hammer", "impact_restitution", "must be in (0, 1]");
  if (!(d.max_stroke > d.compression_length))
    r.fail("hammer", "max_stroke",
           fmt::format("= {} must exceed compression_length = {} (the ram falls from above the ports)", d.max_stroke,
                       d.compression_length));
}

// The gas between anvil and ram, the ram at the exhaust ports.
JointData gas_joint(const DieselData& d) {
  JointData j{"gas", "anvil", "ram", {}, "hammer.gas"};
  j.law.law = JointLaw::diesel;
  j.law.gas.area = d.cylinder_area;
  j.law.gas.compression_length = d.compression_length;
  j.law.gas.chamber_length = d.chamber_length;
  j.law.gas.combustion_pressure = d.combustion_pressure;
  j.law.stiffness = d.impact_stiffness;
  j.law.restitution = d.impact_restitution;
  j.law.gap = d.compression_length;
  return j;
}

// A model's pile cushion (or the helmet resting on the head, as stiff as
// its top element), and its capblock below the ram or the anvil.
void add_model_joints(const Reader& r, Case& c, HammerData& h) {
  const HammerModel& m = *h.entry;
  h.pile_cushion = read_pile_cushion(r);
  const BodyData& head =
      *std::find_if(c.bodies.rbegin(), c.bodies.rend(), [](const BodyData& b) { return b.kind == BodyKind::bar; });
  JointData cushion{"pile-cushion", head.name, "helmet", {}, {}};
  cushion.law.law = h.pile_cushion ? JointLaw::cushion : JointLaw::elastic;
  cushion.law.stiffness =
      h.pile_cushion ? h.pile_cushion->stiffness : head.modulus * head.area * head.elements / head.length;
  cushion.law.restitution = h.pile_cushion ? h.pile_cushion->restitution : 1.0;
  JointData capblock{"capblock", "helmet", h.kind == HammerKind::diesel ? "anvil" : "ram", {}, {}};
  capblock.law.law = JointLaw::cushion;
  capblock.law.stiffness = m.cushion_stiffness;
  capblock.law.restitution = m.cushion_restitution;
  c.joints.push_back(cushion);
  c.joints.push_back(capblock);
}

// The stroke: given, from the rated energy (m g stroke), or the table's; a
// diesel hammer's first blow falls from its max_stroke.
void read_stroke(const Reader& r, const Case& c, const BodyIndex& index, HammerData& h) {
  const double g = drive_gravity(c.load.gravity);
  const double mass = body_mass(c.bodies[index(h.ram)]);
  const bool stroke = r.node("hammer", "stroke") != nullptr, energy = r.node("hammer", "energy") != nullptr;
  const bool diesel = h.kind == HammerKind::diesel;
  if (stroke && energy) r.fail("hammer", "energy", "cannot be given with stroke (energy = m g stroke)");
  if (!h.entry && !diesel && !stroke && !energy)
    r.fail("hammer", "stroke", "is required (m), or energy (J, rated: m g stroke)");
  h.stroke = stroke                ? r.quantity("hammer", "stroke", 0.0, Dimension::length)
             : energy              ? r.number("hammer", "energy", 0.0) / (mass * g)
             : diesel              ? h.diesel.max_stroke
             : h.entry->stroke > 0 ? h.entry->stroke
                                   : h.entry->energy / (mass * g);
  if (!(h.stroke > 0)) r.fail("hammer", energy ? "energy" : "stroke", fmt::format("must be > 0 (got {})", h.stroke));
  const double rated = diesel    ? h.diesel.max_stroke
                       : h.entry ? (h.entry->stroke > 0 ? h.entry->stroke : h.entry->energy / (mass * g))
                                 : 10.0;  // m: no hammer falls further
  if (h.stroke > rated * (1 + 1e-9))
    r.fail("hammer", energy ? "energy" : "stroke",
           fmt::format("gives a stroke of {} m, above the hammer's {} of {} m{}", h.stroke,
                       h.entry || diesel ? "rated stroke" : "plausible", rated, h.stroke > 100 ? " (mm?)" : ""));
  if (diesel && !(h.stroke > h.diesel.compression_length))
    r.fail("hammer", energy ? "energy" : "stroke",
           fmt::format("gives a stroke of {} m, not above the ports (compression_length = {} m)", h.stroke,
                       h.diesel.compression_length));
  h.efficiency = r.number("hammer", "efficiency", h.entry ? h.entry->efficiency : default_efficiency(h.kind));
  if (!(h.efficiency > 0 && h.efficiency <= 1))
    r.fail("hammer", "efficiency", fmt::format("must be in (0, 1] (got {})", h.efficiency));
}

}  // namespace

void add_hammer_bodies(Reader& r, Case& c, BodyIndex& index) {
  if (r.table("hammer") == nullptr) return;
  HammerData h;
  h.model = r.word("hammer", "model", "");
  if (!h.model.empty()) {
    for (const char* key : {"kind", "ram", "ram_mass", "anvil_mass"})
      if (r.node("hammer", key) != nullptr) r.fail("hammer", key, "comes from the table with model (remove it)");
    h.entry = find_model(r, hammer_table(r), h.model);
    h.kind = h.entry->kind;
    h.diesel = h.entry->diesel;
  } else {
    h.kind = read_kind(r, r.word("hammer", "kind", "drop"));
    if (h.kind == HammerKind::diesel) read_diesel(r, h);
  }
  const bool diesel = h.kind == HammerKind::diesel;
  std::vector<std::pair<std::string, double>> added;  // the hammer's bodies, bottom up
  if (h.entry) added.emplace_back("helmet", h.entry->helmet_mass);
  if (diesel) added.emplace_back("anvil", h.diesel.anvil_mass);
  if (h.entry || diesel) added.emplace_back("ram", h.entry ? h.entry->ram_mass : h.ram_mass);
  for (const auto& [name, mass] : added)
    if (index(name) != c.bodies.size())
      r.fail("hammer", h.entry ? "model" : "kind",
             fmt::format("adds the body \"{}\", which the case already defines (the hammer brings its own)", name));
  if (h.entry && c.bodies.back().kind != BodyKind::bar)
    r.fail("hammer", "model",
           fmt::format("needs the line to end at the pile head (a bar; \"{}\" is a mass)", c.bodies.back().name));
  for (const auto& [name, mass] : added) {
    BodyData b;
    b.name = name;
    b.kind = BodyKind::mass;
    b.mass = mass;
    c.bodies.push_back(b);
    index.add(name);
  }
  if (!added.empty()) h.ram = "ram";
  c.hammer = h;
}

void read_hammer(Reader& r, Case& c, BodyIndex& index) {
  if (!c.hammer) return;
  HammerData& h = *c.hammer;
  if (h.entry) add_model_joints(r, c, h);
  if (h.ram.empty()) {
    if (r.node("hammer", "pile_cushion") != nullptr)
      r.fail("hammer", "pile_cushion", "goes with model; by hand, the case's joints are the cushions");
    h.ram = r.word("hammer", "ram", c.bodies.back().name);
    if (index(h.ram) == c.bodies.size())
      r.fail("hammer", "ram", fmt::format("names no body of the line (got \"{}\")", h.ram));
  }
  if (h.kind == HammerKind::diesel) {
    if (r.node("load", "gravity") == nullptr) c.load.gravity = 9.81;  // the ram rises and falls under it
    c.joints.push_back(gas_joint(h.diesel));
  }
  read_stroke(r, c, index, h);
  if (r.table("body." + h.ram) != nullptr && r.node("body." + h.ram, "velocity") != nullptr)
    r.fail("body." + h.ram, "velocity", "is set by [hammer] (the ram's speed at impact): remove it");
  start_ram(c, h.stroke);
}

}  // namespace barimpact::detail

namespace barimpact::detail {

void read_drive(Reader& r, Case& c, const BodyIndex& index) {
  const auto* layers = r.root().get_as<toml::array>("layer");
  if (r.table("drive") == nullptr) {
    if (layers != nullptr) throw InputError(fmt::format("{}: [[layer]] needs a [drive] section", r.where("layer", "")));
    return;
  }
  if (layers == nullptr || layers->empty())
    throw InputError(fmt::format("{}: [drive] needs the soil as [[layer]] tables", r.where("drive", "")));
  DriveData d;
  const std::size_t pile = drive_pile(r, c, index, d.pile);
  if (c.bodies.size() == 1)
    throw InputError(
        fmt::format("{}: [drive] needs a hammer: a [hammer] section, or the ram (and helmet) as bodies "
                    "above the pile",
                    r.where("drive", "")));
  const BodyData& b = c.bodies[pile];
  d.perimeter = r.number("drive", "perimeter", 0.0);
  if (r.node("drive", "perimeter") == nullptr) r.fail("drive", "perimeter", "is required: the shaft's perimeter, m");
  if (!(d.perimeter > 0)) r.fail("drive", "perimeter", fmt::format("must be > 0 (m; got {})", d.perimeter));
  if (d.perimeter > 50.0)
    r.fail("drive", "perimeter", fmt::format("= {}: mm? a pile's perimeter in m is at most a few metres", d.perimeter));
  if (r.node("drive", "toe_area") != nullptr) {
    d.toe_area = r.number("drive", "toe_area", 0.0);
    if (!(*d.toe_area > 0)) r.fail("drive", "toe_area", fmt::format("must be > 0 (m2; got {})", *d.toe_area));
    if (*d.toe_area > 20.0)
      r.fail("drive", "toe_area", fmt::format("= {}: mm2? a pile's toe area in m2 is at most a few", *d.toe_area));
  }
  d.depths = read_depths(r, b.length);
  d.refusal = r.number("drive", "refusal", d.refusal);
  d.blow_rate = r.number("drive", "blow_rate", d.blow_rate);
  const long long blows = r.integer("drive", "blows", d.blows);
  if (!(d.refusal > 0)) r.fail("drive", "refusal", fmt::format("must be > 0 (blows per 250 mm; got {})", d.refusal));
  if (!(d.blow_rate > 0)) r.fail("drive", "blow_rate", fmt::format("must be > 0 (per minute; got {})", d.blow_rate));
  if (blows < 1 || blows > 1000) r.fail("drive", "blows", fmt::format("must be in [1, 1000] (got {})", blows));
  if (blows > 1 && c.hammer && c.hammer->kind == HammerKind::diesel)
    r.fail("drive", "blows",
           fmt::format("= {}: a diesel hammer repeats its blows to find its stroke; with residual stresses too "
                       "(blows > 1) it is not in this version",
                       blows));
  d.blows = static_cast<int>(blows);
  if (r.node("drive", "depth") != nullptr) {
    d.depth = r.number("drive", "depth", 0.0);
    if (!(*d.depth > 0 && *d.depth <= b.length))
      r.fail("drive", "depth", fmt::format("must lie in (0, {}], the pile's length (got {})", b.length, *d.depth));
  }
  double top = 0.0;
  for (std::size_t i = 0; i < layers->size(); ++i) {
    const auto* t = (*layers)[i].as_table();
    if (t == nullptr)
      throw InputError(fmt::format("{}: layer must be an array of tables [[layer]]", r.where("layer", "")));
    d.layers.push_back(read_layer(r, *t, i, top));
    top = d.layers.back().bottom;
  }
  const double deepest = std::max(d.depths.back(), d.depth.value_or(0.0));
  if (top < deepest)
    r.fail(fmt::format("layer[{}]", layers->size()), "bottom",
           fmt::format("= {} must reach the deepest penetration analysed, {} m", top, deepest));
  c.drive = d;
  apply_profile(c, pile);
}

}  // namespace barimpact::detail
