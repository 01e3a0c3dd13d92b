// RECORD.toml's contract, and the record's signals at the gauges.
#include "barimpact/pda/record.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "../hopkinson/setup_reader.hpp"
#include "barimpact/case/case.hpp"
#include "barimpact/model/input_error.hpp"

namespace barimpact {

namespace {

const std::vector<std::string_view> pile_keys{"length", "area", "modulus", "density", "wave_speed"};
const std::vector<std::string_view> record_keys{"file",     "time",         "force",     "strain",
                                                "velocity", "acceleration", "delimiter", "skip_rows"};

const std::vector<std::string_view> match_keys{"segments",    "embedded",    "window",    "damping_law",
                                               "unknowns",    "shaft_quake", "toe_quake", "shaft_damping",
                                               "toe_damping", "starts",      "low_pass",  "smoothing"};

// [[segment]] tables become sections "segment[1]", "segment[2]", ... of the
// root (moved, so that messages keep their lines); returns how many.
std::size_t number_segments(toml::table& root, const std::string& origin) {
  auto* node = root.get("segment");
  if (node == nullptr) return 0;
  auto* tables = node->as_array();
  if (tables == nullptr || tables->empty() || !tables->is_array_of_tables()) {
    const auto line = node->source().begin.line;
    throw InputError(fmt::format("{}{}: segment must be [[segment]] tables (length, area, modulus, density), not {}",
                                 origin, line ? fmt::format(":{}", line) : "", toml_type_name(*node)));
  }
  std::vector<toml::table> moved;
  for (auto& t : *tables) moved.push_back(std::move(*t.as_table()));
  root.erase("segment");
  for (std::size_t i = 0; i < moved.size(); ++i) root.insert(fmt::format("segment[{}]", i + 1), std::move(moved[i]));
  return moved.size();
}

// The contract's sections; `names` holds the segments' section names.
std::vector<SectionKeys> record_contract(const std::vector<std::string>& names) {
  std::vector<SectionKeys> c{
      {"pile", pile_keys}, {"record", record_keys}, {"case_method", {"damping"}}, {"match", match_keys}};
  for (const auto& name : names) c.push_back({name, pile_keys});
  return c;
}

// One uniform stretch: length, area, modulus and density (or wave_speed), all > 0.
PileSegment read_segment(const SetupReader& r, const std::string& s) {
  PileSegment g;
  auto required = [&](std::string_view key, std::string_view what) {
    const auto v = r.positive(s, key);
    if (!v) r.fail(s, key, fmt::format("is missing: {}", what));
    return *v;
  };
  g.length = required("length", "the length below the gauges, m");
  g.area = required("area", "the cross-section's area, m^2");
  g.modulus = required("modulus", "Young's modulus, Pa");
  if (const auto c = r.positive(s, "wave_speed")) {
    g.wave_speed = *c;
    g.density = g.modulus / (*c * *c);  // Z = E A / c as given
  } else {
    g.density = required("density", "kg/m^3 (or give wave_speed)");
    g.wave_speed = std::sqrt(g.modulus / g.density);
  }
  return g;
}

// [pile] uniform, or [[segment]] from the gauges down (adding up to [pile] length when given).
std::vector<PileSegment> read_pile(const SetupReader& r, std::size_t segments) {
  if (segments == 0) {
    if (!r.has_section("pile"))
      r.fail_section("pile", "is missing: the pile below the gauges (length, area, modulus, density), or [[segment]]");
    return {read_segment(r, "pile")};
  }
  for (std::string_view key : {"area", "modulus", "density", "wave_speed"})
    if (r.has("pile", key)) r.fail("pile", key, "and [[segment]] both given: the segments give the pile's properties");
  std::vector<PileSegment> out;
  double total = 0.0;
  for (std::size_t i = 0; i < segments; ++i) {
    out.push_back(read_segment(r, fmt::format("segment[{}]", i + 1)));
    total += out.back().length;
  }
  if (const auto length = r.positive("pile", "length"); length && std::abs(*length - total) > 1e-9 * *length)
    r.fail("pile", "length", fmt::format("= {} m, but the segments' lengths add up to {} m", *length, total));
  return out;
}

// force or strain, velocity or acceleration: one of each.
void read_channels(const SetupReader& r, PileRecord& rec) {
  auto one_of = [&](std::string_view a, std::string_view b, bool& second) {
    const auto x = r.words("record", a);
    const auto y = r.words("record", b);
    if (!x.empty() && !y.empty()) r.fail("record", b, fmt::format("and {} both given: give one", a));
    if (x.empty() && y.empty()) r.fail("record", a, fmt::format("is missing: give {} or {} (columns)", a, b));
    second = !y.empty();
    return second ? y : x;
  };
  rec.force_columns = one_of("force", "strain", rec.strain);
  rec.velocity_columns = one_of("velocity", "acceleration", rec.acceleration);
}

void read_record_section(const SetupReader& r, PileRecord& rec, const std::filesystem::path& base) {
  if (!r.has_section("record")) r.fail_section("record", "is missing: the CSV file and its columns");
  const auto file = r.word("record", "file");
  if (!file || file->empty()) r.fail("record", "file", "is missing: the record's CSV file");
  const std::filesystem::path p(*file);
  rec.csv = p.is_absolute() ? p : base / p;
  rec.layout.section = "record";
  if (const auto time = r.word("record", "time")) {
    if (time->empty()) r.fail("record", "time", "must name a column");
    rec.layout.time_column = *time;
  }
  read_delimiter_and_skip_rows(r, "record", rec.layout.delimiter, rec.layout.skip_rows);
  read_channels(r, rec);
}

// A whole number in [lo, hi].
int read_count(const SetupReader& r, std::string_view key, int lo, int hi, int fallback) {
  const auto v = r.number("match", key);
  if (!v) return fallback;
  if (!(*v >= lo && *v <= hi && std::floor(*v) == *v))
    r.fail("match", key, fmt::format("must be a whole number in [{}, {}] (got {})", lo, hi, *v));
  return static_cast<int>(*v);
}

// A value inside the fit's bounds.
std::optional<double> read_bounded(const SetupReader& r, std::string_view key, double lo, double hi,
                                   std::string_view what) {
  const auto v = r.number("match", key);
  if (v && !(*v >= lo && *v <= hi))
    r.fail("match", key, fmt::format("must be in [{}, {}] {} (got {})", lo, hi, what, *v));
  return v;
}

void read_match(const SetupReader& r, PileRecord& rec) {
  MatchSettings& m = rec.match;
  m.segments = read_count(r, "segments", 1, 50, m.segments);
  m.starts = read_count(r, "starts", 1, 32, m.starts);
  if ((m.embedded = r.number("match", "embedded")) && !(*m.embedded > 0.0 && *m.embedded <= rec.length() * (1 + 1e-12)))
    r.fail("match", "embedded",
           fmt::format("must be in (0, {}] m, the pile's length below the gauges (got {})", rec.length(), *m.embedded));
  if ((m.window = r.number("match", "window")) && !(*m.window > 0.0))
    r.fail("match", "window", fmt::format("must be > 0 s after t2 (got {})", *m.window));
  if (const auto law = r.word("match", "damping_law")) {
    if (*law == "smith")
      m.damping_law = DampingLaw::smith;
    else if (*law == "viscous")
      m.damping_law = DampingLaw::viscous;
    else
      r.fail("match", "damping_law", fmt::format("must be \"smith\" or \"viscous\" (got \"{}\")", *law));
  }
  if (r.has("match", "unknowns")) {
    m.unknowns = r.words("match", "unknowns");
    if (m.unknowns.empty()) r.fail("match", "unknowns", "must name at least one unknown");
    const auto& all = MatchSettings::all_unknowns();
    for (std::size_t i = 0; i < m.unknowns.size(); ++i) {
      const auto& u = m.unknowns[i];
      if (std::find(all.begin(), all.end(), u) == all.end())
        r.fail("match", "unknowns",
               fmt::format("names \"{}\": the unknowns are shaft, toe, shaft_quake, toe_quake, shaft_damping, "
                           "toe_damping",
                           u));
      if (std::find(m.unknowns.begin(), m.unknowns.begin() + static_cast<std::ptrdiff_t>(i), u) !=
          m.unknowns.begin() + static_cast<std::ptrdiff_t>(i))
        r.fail("match", "unknowns", fmt::format("names \"{}\" twice", u));
    }
  }
  const char* quake = "m (the fit's bounds on a quake: 0.5 to 15 mm)";
  const char* damping = "s/m (the fit's bounds on a damping)";
  if (const auto q = read_bounded(r, "shaft_quake", 0.0005, 0.015, quake)) m.shaft_quake = *q;
  if (const auto q = read_bounded(r, "toe_quake", 0.0005, 0.015, quake)) m.toe_quake = *q;
  if (const auto f = r.number("match", "low_pass")) {
    if (!(*f >= 0.0)) r.fail("match", "low_pass", fmt::format("must be >= 0 Hz (0: no filter; got {})", *f));
    m.low_pass = *f;
  }
  if (const auto w = r.number("match", "smoothing")) {
    if (!(*w >= 0.0)) r.fail("match", "smoothing", fmt::format("must be >= 0 (0: no penalty; got {})", *w));
    m.smoothing = *w;
  }
  m.shaft_damping = read_bounded(r, "shaft_damping", 0.0, 2.5, damping);
  m.toe_damping = read_bounded(r, "toe_damping", 0.0, 2.5, damping);
}

}  // namespace

const std::vector<std::string>& MatchSettings::all_unknowns() {
  static const std::vector<std::string> u{"shaft", "toe", "shaft_quake", "toe_quake", "shaft_damping", "toe_damping"};
  return u;
}

bool MatchSettings::fits(std::string_view unknown) const {
  return std::find(unknowns.begin(), unknowns.end(), unknown) != unknowns.end();
}

double PileRecord::length() const {
  double l = 0.0;
  for (const auto& s : segments) l += s.length;
  return l;
}

double PileRecord::travel_time() const {
  return two_way_time(length());
}

double PileRecord::impedance() const {
  return segments.front().impedance();
}

double PileRecord::area() const {
  return segments.front().area;
}

double PileRecord::two_way_time(double x) const {
  double tau = 0.0, top = 0.0;
  for (const auto& s : segments) {
    tau += 2.0 * std::clamp(x - top, 0.0, s.length) / s.wave_speed;
    top += s.length;
  }
  return tau;
}

double PileRecord::depth_at(double two_way) const {
  double x = 0.0, left = std::max(two_way, 0.0);
  for (const auto& s : segments) {
    const double through = 2.0 * s.length / s.wave_speed;
    if (left <= through) return x + 0.5 * left * s.wave_speed;
    left -= through;
    x += s.length;
  }
  return x;
}

const PileSegment& PileRecord::segment_at(double x) const {
  double bottom = 0.0;
  for (const auto& s : segments) {
    bottom += s.length;
    if (x <= bottom) return s;
  }
  return segments.back();
}

PileRecord PileRecord::from_string(const std::string& toml, const std::filesystem::path& base,
                                   const std::string& origin) {
  toml::table root = parse_toml(toml, origin);
  const std::size_t segments = number_segments(root, origin);
  std::vector<std::string> names;  // outlives the reader, which holds views of them
  for (std::size_t i = 0; i < segments; ++i) names.push_back(fmt::format("segment[{}]", i + 1));
  const SetupReader r(std::move(root), origin, record_contract(names));
  r.check_layout();
  PileRecord rec;
  rec.origin = origin;
  rec.segments = read_pile(r, segments);
  read_record_section(r, rec, base);
  if (const auto j = r.number("case_method", "damping")) {
    if (!(*j >= 0.0 && *j <= 1.0))
      r.fail("case_method", "damping", fmt::format("must be in [0, 1]: the Case damping J_c (got {})", *j));
    rec.damping = *j;
  }
  read_match(r, rec);
  return rec;
}

PileRecord PileRecord::from_file(const std::filesystem::path& path) {
  const std::string text = read_input_file(path, "record file");
  PileRecord rec = from_string(text, path.parent_path(), path.string());
  rec.file = path;
  return rec;
}

CommandInputs pda_inputs(const PileRecord& record) {
  CommandInputs in;
  if (!record.file.empty()) in.files.push_back(record.file);
  in.files.push_back(record.csv);
  return in;
}

}  // namespace barimpact
