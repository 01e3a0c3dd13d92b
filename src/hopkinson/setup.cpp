#include "barimpact/hopkinson/setup.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "../case/toml_input.hpp"
#include "barimpact/case/case.hpp"
#include "barimpact/model/input_error.hpp"
#include "barimpact/run/output.hpp"
#include "plausible.hpp"
#include "setup_reader.hpp"

namespace barimpact {

namespace {

const std::vector<std::string_view> channel_keys{
    "signal",          "time",      "strain",    "volts",      "gauge_factor",
    "excitation",      "bridge",    "gain",      "polarity",   "header",
    "sample_interval", "delimiter", "skip_rows", "full_scale", "gauge_to_specimen",
    "start",           "end",       "run",       "gauge"};

// The setup-file contract: sections and keys.
const std::vector<SectionKeys>& contract() {
  static const std::vector<SectionKeys> c{
      {"bar", {"modulus", "density", "diameter", "area", "wave_speed", "poisson", "dispersion"}},
      {"specimen", {"length", "diameter", "area", "body"}},
      {"incident", channel_keys},
      {"transmitted", channel_keys},
      {"window", {"trigger"}},
      {"fit", {"elastic", "plastic"}}};
  return c;
}

double circle_area(double diameter) {
  return std::numbers::pi * diameter * diameter / 4.0;
}

// A bar's or the specimen's cross-section: `diameter` or `area`, not both.
std::optional<double> read_area(const SetupReader& r, std::string_view section) {
  const auto d = r.positive(section, "diameter", Dimension::length);
  const auto a = r.positive(section, "area", Dimension::area);
  if (d && a) r.fail(section, "area", "and diameter both given: give one");
  if (d) return circle_area(*d);
  return a;
}

// The part of a channel that a barimpact run gives: its bar and its gauge's
// distance to the specimen, from the run's case.toml.
struct RunGauge {
  HopkinsonBar bar;
  double gauge_to_specimen = 0.0;
  double specimen_length = 0.0, specimen_area = 0.0;
  bool si = true;  ///< the run's case holds SI numbers ([units] system = "SI" or "US")
};

// Sets the channel's file: the run's history.csv, or its results.h5.
RunGauge read_run_gauge(const SetupReader& r, ChannelSetup& ch, const std::string& specimen_body) {
  const std::string s = ch.section;
  const auto case_file = run_case_file(ch.run);
  if (!std::filesystem::is_regular_file(case_file) ||
      (!std::filesystem::is_regular_file(ch.run / history_file(OutputFormat::csv)) &&
       !std::filesystem::is_regular_file(ch.run / history_file(OutputFormat::hdf5))))
    r.fail(s, "run",
           fmt::format("= \"{}\" holds no case.toml and history.csv or results.h5 (give a directory written by "
                       "barimpact run)",
                       ch.run.string()));
  if (specimen_body.empty()) r.fail("specimen", "body", "must name the specimen's body of the run (given a run)");
  Case c;
  try {
    c = Case::from_file(case_file);
  } catch (const InputError& e) {
    r.fail(s, "run", fmt::format("= \"{}\": its case.toml does not read ({})", ch.run.string(), e.what()));
  }
  ch.files = {ch.run / history_file(c.output.format)};
  if (!std::filesystem::is_regular_file(ch.files.front()))
    r.fail(s, "run",
           fmt::format("= \"{}\" holds no {} (its case.toml says output.format = \"{}\")", ch.run.string(),
                       history_file(c.output.format), to_string(c.output.format)));
  const auto body_index = [&](const std::string& name) {
    for (std::size_t i = 0; i < c.bodies.size(); ++i)
      if (c.bodies[i].name == name) return static_cast<long>(i);
    return -1L;
  };
  const long sp = body_index(specimen_body);
  if (sp < 0)
    r.fail("specimen", "body", fmt::format("= \"{}\" is not a body of the run {}", specimen_body, ch.run.string()));
  const auto g = std::find_if(c.gauges.begin(), c.gauges.end(), [&](const GaugeData& x) { return x.name == ch.gauge; });
  if (g == c.gauges.end()) {
    std::vector<std::string> names;
    for (const auto& x : c.gauges) names.push_back(x.name);
    r.fail(s, "gauge",
           fmt::format("= \"{}\" is not a gauge of the run {} (its gauges: {})", ch.gauge, ch.run.string(),
                       names.empty() ? std::string("none") : fmt::format("{}", fmt::join(names, ", "))));
  }
  const long gb = body_index(g->body);
  if (gb != sp - 1 && gb != sp + 1)
    r.fail(s, "gauge",
           fmt::format("= \"{}\" is on body \"{}\", which does not touch the specimen \"{}\" (a bar beside it)",
                       ch.gauge, g->body, specimen_body));
  const auto& b = c.bodies[static_cast<std::size_t>(gb)];
  const auto& spec = c.bodies[static_cast<std::size_t>(sp)];
  RunGauge out;
  out.bar.modulus = b.modulus;
  out.bar.density = b.density;
  out.bar.area = b.area;
  out.bar.diameter = std::sqrt(4.0 * b.area / std::numbers::pi);
  // A body's `at` runs from its near end (x = 0's side): the upper
  // neighbour faces the specimen with its near end, the lower with its far end.
  out.gauge_to_specimen = gb == sp + 1 ? g->at : b.length - g->at;
  out.specimen_length = spec.length;
  out.specimen_area = spec.area;
  out.si = c.units != "none";  // "US" cases hold SI numbers too
  return out;
}

// A relative path from the setup file's directory; if nothing is there and
// something is in the working directory, that (a run's `out/...` named from
// where the commands are typed).
std::filesystem::path relative_to(const std::filesystem::path& base, const std::string& name) {
  const std::filesystem::path p(name);
  if (p.is_absolute() || std::filesystem::exists(base / p) || !std::filesystem::exists(p)) return base / p;
  return p;
}

// time/sample_interval, strain/volts and the bridge's constants.
void read_columns(const SetupReader& r, std::string_view s, ChannelSetup& ch) {
  const auto time = r.word(s, "time");
  if (const auto dt = r.positive(s, "sample_interval")) {
    if (time) r.fail(s, "sample_interval", "and time both given: sample_interval is for a file without a time column");
    ch.sample_interval = *dt;
    ch.time_column.clear();
  } else if (time) {
    if (time->empty()) r.fail(s, "time", "must name a column");
    ch.time_column = *time;
  }
  const auto strain = r.words(s, "strain");
  const auto volts = r.words(s, "volts");
  if (!strain.empty() && !volts.empty()) r.fail(s, "volts", "and strain both given: a channel is in one unit");
  if (!volts.empty()) {
    ch.volts = true;
    ch.strain_columns = volts;
    const auto gf = r.positive(s, "gauge_factor");
    const auto ex = r.positive(s, "excitation");
    const auto bridge = r.word(s, "bridge");
    if (!gf) r.fail(s, "gauge_factor", "is missing: volts need the gauge factor, excitation and bridge");
    if (!ex) r.fail(s, "excitation", "is missing: volts need the gauge factor, excitation and bridge");
    if (!bridge) r.fail(s, "bridge", "is missing: \"quarter\", \"half\" or \"full\"");
    if (*bridge == "quarter")
      ch.bridge = Bridge::quarter;
    else if (*bridge == "half")
      ch.bridge = Bridge::half;
    else if (*bridge == "full")
      ch.bridge = Bridge::full;
    else
      r.fail(s, "bridge", fmt::format("must be \"quarter\", \"half\" or \"full\" (got \"{}\")", *bridge));
    ch.gauge_factor = *gf;
    ch.excitation = *ex;
    if (const auto g = r.positive(s, "gain")) ch.gain = *g;
  } else {
    for (std::string_view key : {"gauge_factor", "excitation", "bridge", "gain"})
      if (r.has(s, key)) r.fail(s, key, "applies to a signal in volts (volts = \"COLUMN\")");
    if (!strain.empty()) ch.strain_columns = strain;
  }
  if (ch.files.size() > 1 && ch.strain_columns.size() != 1 && ch.strain_columns.size() != ch.files.size())
    r.fail(s, ch.volts ? "volts" : "strain",
           fmt::format("must name one column (in each file) or one per file ({} files, {} names)", ch.files.size(),
                       ch.strain_columns.size()));
}

// polarity, header, delimiter, skip_rows, full_scale.
void read_file_layout(const SetupReader& r, std::string_view s, ChannelSetup& ch) {
  if (const auto p = r.number(s, "polarity")) {
    if (*p != 1.0 && *p != -1.0) r.fail(s, "polarity", fmt::format("must be 1 or -1 (got {})", *p));
    ch.polarity = *p;
  }
  if (const auto h = r.boolean(s, "header")) ch.header = *h;
  if (!ch.header && !r.has(s, "strain") && !r.has(s, "volts"))
    r.fail(s, "strain", "is missing: a file without a header names its columns \"1\", \"2\", ...");
  if (!ch.header && !ch.time_column.empty() && !r.has(s, "time"))
    r.fail(s, "time",
           "is missing: a file without a header names its columns \"1\", \"2\", ... (or give "
           "sample_interval)");
  read_delimiter_and_skip_rows(r, s, ch.delimiter, ch.skip_rows);
  ch.full_scale = r.positive(s, "full_scale");
}

ChannelSetup read_channel(const SetupReader& r, std::string_view s, const std::filesystem::path& base) {
  ChannelSetup ch;
  ch.section = std::string(s);
  if (!r.has_section(s))
    r.fail_section(s, "is missing: it names the gauge's signal (signal = \"FILE\", or run and gauge)");
  const auto files = r.words(s, "signal");
  const auto run = r.word(s, "run");
  if (run && !files.empty()) r.fail(s, "run", "and signal both given: a channel reads a file or a run");
  if (run) {
    for (std::string_view key : {"time", "strain", "volts", "header", "sample_interval", "delimiter", "skip_rows",
                                 "gauge_factor", "excitation", "bridge", "gain", "polarity", "full_scale"})
      if (r.has(s, key)) r.fail(s, key, "does not apply to a run's gauge (its history is read as written)");
    ch.run = relative_to(base, *run);
    const auto gauge = r.word(s, "gauge");
    if (!gauge || gauge->empty()) r.fail(s, "gauge", "must name the run's gauge (given run)");
    ch.gauge = *gauge;
    ch.time_column = std::string("t");  // std::string(...): GCC 12's -Wrestrict on a literal's assignment
    ch.strain_columns = {fmt::format("gauge.{}.strain", ch.gauge)};  // files: read_run_gauge, from its case
  } else {
    if (files.empty()) r.fail(s, "signal", "is missing: a CSV file (or a list of them), or run and gauge");
    if (r.has(s, "gauge")) r.fail(s, "gauge", "needs run (a barimpact run's gauge)");
    for (const auto& f : files) ch.files.push_back(relative_to(base, f));
    read_columns(r, s, ch);
    read_file_layout(r, s, ch);
  }
  if (const auto d = r.positive(s, "gauge_to_specimen", Dimension::length))
    ch.gauge_to_specimen = *d;
  else if (!run)
    r.fail(s, "gauge_to_specimen", "is missing: the distance from the gauge to the specimen's face");
  ch.start = r.number(s, "start");
  ch.end = r.number(s, "end");
  if (ch.start.has_value() != ch.end.has_value())
    r.fail(s, ch.start ? "end" : "start", "must be given with the other: start and end make the pulse's window");
  if (ch.start && !(*ch.start < *ch.end))
    r.fail(s, "end", fmt::format("must be after start (got start = {}, end = {})", *ch.start, *ch.end));
  return ch;
}

HopkinsonBar read_bar(const SetupReader& r, const std::optional<RunGauge>& from_run) {
  HopkinsonBar b;
  if (from_run) b = from_run->bar;
  if (const auto v = r.positive("bar", "modulus", Dimension::stress)) b.modulus = *v;
  if (const auto v = r.positive("bar", "density", Dimension::density)) b.density = *v;
  const auto d = r.positive("bar", "diameter", Dimension::length);
  if (const auto a = read_area(r, "bar")) {
    b.area = *a;
    b.diameter = d ? *d : std::sqrt(4.0 * *a / std::numbers::pi);
  }
  const std::string_view given = from_run ? " (and no run gives it)" : "";
  if (!(b.modulus > 0)) r.fail("bar", "modulus", fmt::format("is missing: the bars' Young's modulus E{}", given));
  if (!(b.density > 0)) r.fail("bar", "density", fmt::format("is missing: the bars' density{}", given));
  if (!(b.area > 0)) r.fail("bar", "diameter", fmt::format("is missing: the bars' diameter (or area){}", given));
  b.wave_speed = std::sqrt(b.modulus / b.density);
  if (const auto c = r.positive("bar", "wave_speed", Dimension::velocity)) b.wave_speed = *c;
  if (const auto nu = r.number("bar", "poisson")) {
    if (!(*nu > 0 && *nu < 0.5)) r.fail("bar", "poisson", fmt::format("must be in (0, 0.5) (got {})", *nu));
    b.poisson = *nu;
  }
  if (const auto disp = r.boolean("bar", "dispersion")) b.dispersion = *disp;
  if (b.dispersion && b.poisson < 0) r.fail("bar", "dispersion", "needs the bars' poisson (Pochhammer-Chree)");
  return b;
}

// The bounds of plausible_setup, in SI, wide on purpose:
//   - bar modulus 1e8 to 1.5e12 Pa: polymer bars (0.2 to 5 GPa) to tungsten
//     carbide (about 700 GPa; diamond's is 1.2 TPa);
//   - bar density 500 to 25000 kg/m^3: polymers (about 900) to tungsten (19300);
//   - wave speed 300 to 20000 m/s: low-density polyethylene (about 500),
//     polymers 1400 to 2300, steel 5000, aluminium 5100, beryllium 12900;
//   - bar diameter 1 mm to 1 m: miniature bars (3 mm) to the largest (0.3 m);
//   - gauge_to_specimen up to 100 m: bars are a few metres long;
//   - the specimen no wider than the bars (10% of area for rounding): wider,
//     it overhangs the faces, which load only their own area;
//   - the specimen's length 0.02 to 10 diameters: thin discs of soft
//     materials to long rods (usual: 0.5 to 2); longer, it cannot reach
//     equilibrium within a pulse.
namespace hp = hopkinson_plausible;
constexpr hp::Bounds bar_modulus{1e8, 1.5e12, 200e9}, bar_density{500.0, 25000.0, 7850.0},
    bar_wave_speed{300.0, 20000.0, 5000.0}, bar_diameter{1e-3, 1.0, 0.02}, gauge_distance{0.0, 100.0, 1.0},
    specimen_aspect{0.02, 10.0, 0.5};
constexpr double specimen_overhang = 1.1;

// section.key = v, refused outside the bounds with the unit it was probably meant in.
void plausible(const SetupReader& r, std::string_view section, std::string_view key, double v, const hp::Bounds& b,
               std::string_view unit, std::initializer_list<hp::Unit> units) {
  if (!b.holds(v))
    r.fail(section, key, fmt::format("= {}: {}outside [{:g}, {:g}] {}", v, hp::meant(v, b, units), b.lo, b.hi, unit));
}

// A bar's or the specimen's size key, "diameter" or "area", with its value:
// checked as a diameter, so that an area in mm^2 is found as a diameter in mm.
std::string_view size_key(const SetupReader& r, std::string_view section) {
  return r.has(section, "area") ? "area" : "diameter";
}

void plausible_bar(const SetupReader& r, const HopkinsonBar& b) {
  plausible(r, "bar", "modulus", b.modulus, bar_modulus, "Pa (steel 200e9)", {{1e9, "GPa"}, {1e6, "MPa"}});
  plausible(r, "bar", "density", b.density, bar_density, "kg/m^3 (steel 7850)", {{1e3, "g/cm^3"}});
  const auto size = size_key(r, "bar");
  if (!bar_diameter.holds(b.diameter))
    r.fail("bar", size,
           fmt::format("= {}: {}a diameter of {:g} m, outside [{:g}, {:g}] m", size == "area" ? b.area : b.diameter,
                       hp::meant(b.diameter, bar_diameter, {{1e-3, size == "area" ? "mm^2" : "mm"}}), b.diameter,
                       bar_diameter.lo, bar_diameter.hi));
  if (r.has("bar", "wave_speed"))
    plausible(r, "bar", "wave_speed", b.wave_speed, bar_wave_speed, "m/s (steel 5000)", {{1e3, "km/s"}});
  else if (!bar_wave_speed.holds(b.wave_speed))
    r.fail("bar", "modulus",
           fmt::format("= {} and bar.density = {} give c0 = sqrt(modulus / density) = {:.4g} m/s, outside [{:g}, "
                       "{:g}] m/s: check their units (Pa, kg/m^3)",
                       b.modulus, b.density, b.wave_speed, bar_wave_speed.lo, bar_wave_speed.hi));
}

void plausible_setup(const SetupReader& r, const HopkinsonSetup& s) {
  plausible_bar(r, s.incident_bar);
  plausible_bar(r, s.transmitter_bar);
  for (const ChannelSetup* ch : {&s.incident, &s.transmitted}) {
    plausible(r, ch->section, "gauge_to_specimen", ch->gauge_to_specimen, gauge_distance, "m", {{1e-3, "mm"}});
    if (ch->sample_interval > 0)
      plausible(r, ch->section, "sample_interval", ch->sample_interval, hp::sample_interval, "s", hp::time_units);
  }
  const auto& sp = s.specimen;
  const double bar_area = std::min(s.incident_bar.area, s.transmitter_bar.area);
  const double diameter = std::sqrt(4.0 * sp.area / std::numbers::pi);
  const double widest = std::sqrt(4.0 * specimen_overhang * bar_area / std::numbers::pi);
  const auto size = size_key(r, "specimen");
  if (diameter > widest)
    r.fail("specimen", size,
           fmt::format("= {}: {}the specimen (area {:.4g} m^2) is wider than the bars (area {:.4g} m^2), whose "
                       "faces load only their own area",
                       size == "area" ? sp.area : diameter,
                       hp::meant(diameter, {0.0, widest, 0.5 * widest}, {{1e-3, size == "area" ? "mm^2" : "mm"}}),
                       sp.area, bar_area));
  const double aspect = sp.length / diameter;
  if (!specimen_aspect.holds(aspect))
    r.fail("specimen", "length",
           fmt::format("= {}: {}{:.3g} diameters long (diameter {:.4g} m), outside [{:g}, {:g}]: a Hopkinson "
                       "specimen is a disc or a short cylinder",
                       sp.length, hp::meant(aspect, specimen_aspect, {{1e-3, "mm"}}), aspect, diameter,
                       specimen_aspect.lo, specimen_aspect.hi));
}

}  // namespace

HopkinsonSetup HopkinsonSetup::from_string(const std::string& toml, const std::filesystem::path& base,
                                           const std::string& origin) {
  const SetupReader r(parse_toml(toml, origin), origin, contract());
  r.check_layout();
  HopkinsonSetup s;
  s.origin = origin;
  if (const auto body = r.word("specimen", "body")) s.specimen.body = *body;
  s.incident = read_channel(r, "incident", base);
  s.transmitted = read_channel(r, "transmitted", base);
  std::optional<RunGauge> run_i, run_t;
  if (!s.incident.run.empty()) run_i = read_run_gauge(r, s.incident, s.specimen.body);
  if (!s.transmitted.run.empty()) run_t = read_run_gauge(r, s.transmitted, s.specimen.body);
  if (!run_i && !run_t && r.has("specimen", "body"))
    r.fail("specimen", "body", "names a run's body: give run and gauge in [incident] and [transmitted]");
  s.incident_bar = read_bar(r, run_i ? run_i : run_t);
  s.transmitter_bar = read_bar(r, run_t ? run_t : run_i);
  for (auto [ch, run] : {std::pair{&s.incident, &run_i}, std::pair{&s.transmitted, &run_t}})
    if (*run && ch->gauge_to_specimen < 0) ch->gauge_to_specimen = (*run)->gauge_to_specimen;
  const auto& any_run = run_i ? run_i : run_t;
  if (any_run) {
    s.specimen.length = any_run->specimen_length;
    s.specimen.area = any_run->specimen_area;
  }
  if (const auto l = r.positive("specimen", "length", Dimension::length)) s.specimen.length = *l;
  if (const auto a = read_area(r, "specimen")) s.specimen.area = *a;
  if (!(s.specimen.length > 0)) r.fail("specimen", "length", "is missing: the specimen's initial length");
  if (!(s.specimen.area > 0)) r.fail("specimen", "diameter", "is missing: the specimen's initial diameter (or area)");
  if (const auto t = r.number("window", "trigger")) {
    if (!(*t > 0.02 && *t < 1))
      r.fail("window", "trigger",
             fmt::format("must be in (0.02, 1): a fraction of the incident peak above the foot's 2% (got {})", *t));
    s.trigger = *t;
  }
  s.fit_elastic = r.range("fit", "elastic");
  s.fit_plastic = r.range("fit", "plastic");
  if (s.fit_plastic && !s.fit_elastic)
    r.fail("fit", "plastic", "needs fit.elastic: the yield, where the plastic range starts, comes from the modulus");
  s.si = !(run_i && !run_i->si) && !(run_t && !run_t->si);
  if (s.si) plausible_setup(r, s);
  return s;
}

HopkinsonSetup HopkinsonSetup::from_file(const std::filesystem::path& path) {
  const std::string text = read_input_file(path, "setup file");
  HopkinsonSetup s = from_string(text, path.parent_path(), path.string());
  s.file = path;
  return s;
}

CommandInputs hopkinson_inputs(const HopkinsonSetup& setup) {
  CommandInputs in;
  if (!setup.file.empty()) in.files.push_back(setup.file);
  for (const ChannelSetup* ch : {&setup.incident, &setup.transmitted}) {
    in.files.insert(in.files.end(), ch->files.begin(), ch->files.end());
    if (!ch->run.empty()) in.directories.push_back(ch->run);
  }
  return in;
}

}  // namespace barimpact
