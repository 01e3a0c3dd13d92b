#include "barimpact/case/case.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include <memory>
#include "barimpact/model/expression.hpp"
#include "barimpact/schemes/scheme.hpp"
#include "toml_input.hpp"

namespace barimpact {

namespace {

// The largest mesh a case may ask for. Reading a case evaluates its
// expressions at every node: a fuzzing build (the usual
// FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION) caps meshes lower, so that an
// input asking for 10^8 nodes is still tested rather than a timeout.
#ifdef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
constexpr long long max_elements = 100'000;
#else
constexpr long long max_elements = 100'000'000;
#endif

struct SectionKeys {
  std::string_view section;
  std::vector<std::string_view> keys;
};

// The case-file contract: sections and keys, in file order.
const std::array<SectionKeys, 6>& contract() {
  static const std::array<SectionKeys, 6> c{{
      {"bar", {"length", "density", "stiffness", "viscosity", "elements", "far_end"}},
      {"load", {"body_force"}},
      {"initial", {"displacement", "velocity"}},
      {"obstacle", {"kind", "stiffness", "gap", "viscosity"}},
      {"time", {"end", "step", "scheme", "alpha", "lambda", "beta", "gamma", "theta", "restitution"}},
      {"output", {"every", "fields_at"}},
  }};
  return c;
}

const SectionKeys* find_section(std::string_view name) {
  for (const auto& s : contract())
    if (s.section == name) return &s;
  return nullptr;
}

bool has_key(const SectionKeys& s, std::string_view key) {
  for (auto k : s.keys)
    if (k == key) return true;
  return false;
}

// Reads the table, remembering where each key came from so that every error
// names the file and line, or the --set option, that set it.
class Reader {
 public:
  Reader(toml::table root, std::string origin, std::map<std::string, std::string> overridden, bool cite_lines)
      : root_(std::move(root)),
        origin_(std::move(origin)),
        overridden_(std::move(overridden)),
        cite_lines_(cite_lines) {}

  [[noreturn]] void fail(std::string_view section, std::string_view key, std::string_view rule) const {
    throw InputError(fmt::format("{}: {}.{} {}", where(section, key), section, key, rule));
  }

  std::string where(std::string_view section, std::string_view key) const {
    const std::string dotted = fmt::format("{}.{}", section, key);
    if (auto it = overridden_.find(dotted); it != overridden_.end()) return it->second;
    if (const auto* n = node(section, key)) return located(*n);
    if (const auto* t = root_.get(section)) return located(*t);
    return origin_;
  }

  std::string located(const toml::node& n) const {
    const auto& src = n.source();
    if (src.begin.line == 0 || !cite_lines_) return origin_;
    return fmt::format("{}:{}", origin_, src.begin.line);
  }

  void check_layout() const {
    for (auto&& [name, value] : root_) {
      const std::string_view sname = name.str();
      const auto* section = find_section(sname);
      std::vector<std::string_view> names;
      for (const auto& s : contract()) names.push_back(s.section);
      const std::string loc =
          overridden_.count(std::string(sname) + ".") ? overridden_.at(std::string(sname) + ".") : located(value);
      if (section == nullptr || !value.is_table()) {
        if (section == nullptr)
          throw InputError(fmt::format("{}: unknown section [{}] (known: {})", loc, sname, fmt::join(names, ", ")));
        throw InputError(fmt::format("{}: {} must be a section [{}], not a value", loc, sname, sname));
      }
      for (auto&& [key, v] : *value.as_table()) {
        if (!has_key(*section, key.str())) {
          const std::string dotted = fmt::format("{}.{}", sname, key.str());
          auto it = overridden_.find(dotted);
          throw InputError(fmt::format("{}: unknown key {} (known in [{}]: {})",
                                       it != overridden_.end() ? it->second : located(v), dotted, sname,
                                       fmt::join(section->keys, ", ")));
        }
      }
    }
  }

  const toml::node* node(std::string_view section, std::string_view key) const {
    const auto* t = root_.get_as<toml::table>(section);
    return t ? t->get(key) : nullptr;
  }

  double number(std::string_view section, std::string_view key, double fallback) const {
    const auto* n = node(section, key);
    if (n == nullptr) return fallback;
    double v = 0.0;
    if (const auto* i = n->as_integer())
      v = static_cast<double>(i->get());
    else if (const auto* f = n->as_floating_point())
      v = f->get();
    else
      fail(section, key, fmt::format("must be a number (got {})", type_name(*n)));
    if (!std::isfinite(v)) fail(section, key, fmt::format("must be a finite number (got {})", v));
    return v;
  }

  long long integer(std::string_view section, std::string_view key, long long fallback) const {
    const auto* n = node(section, key);
    if (n == nullptr) return fallback;
    if (const auto* i = n->as_integer()) return i->get();
    fail(section, key, fmt::format("must be an integer (got {})", type_name(*n)));
  }

  std::string word(std::string_view section, std::string_view key, std::string_view fallback) const {
    const auto* n = node(section, key);
    if (n == nullptr) return std::string(fallback);
    if (const auto* s = n->as_string()) return s->get();
    fail(section, key, fmt::format("must be a string (got {})", type_name(*n)));
  }

  // An expression: a string, or a number written without quotes.
  std::string expression(std::string_view section, std::string_view key, std::string_view fallback) const {
    const auto* n = node(section, key);
    if (n == nullptr) return std::string(fallback);
    if (const auto* s = n->as_string()) return s->get();
    if (const auto* i = n->as_integer()) return fmt::format("{}", i->get());
    if (const auto* f = n->as_floating_point()) {
      if (!std::isfinite(f->get())) fail(section, key, "must be finite");
      return fmt::format("{}", f->get());
    }
    fail(section, key, fmt::format("must be an expression in x and t (got {})", type_name(*n)));
  }

  std::vector<double> numbers(std::string_view section, std::string_view key) const {
    const auto* n = node(section, key);
    std::vector<double> out;
    if (n == nullptr) return out;
    auto one = [&](const toml::node& e) {
      if (const auto* i = e.as_integer()) return static_cast<double>(i->get());
      if (const auto* f = e.as_floating_point()) {
        if (!std::isfinite(f->get())) fail(section, key, "must hold finite numbers");
        return f->get();
      }
      fail(section, key, fmt::format("must be an array of numbers (found {})", type_name(e)));
    };
    if (const auto* a = n->as_array()) {
      for (const auto& e : *a) out.push_back(one(e));
    } else {
      out.push_back(one(*n));
    }
    return out;
  }

 private:
  static std::string_view type_name(const toml::node& n) {
    switch (n.type()) {
      case toml::node_type::string:
        return "a string";
      case toml::node_type::integer:
        return "an integer";
      case toml::node_type::floating_point:
        return "a float";
      case toml::node_type::boolean:
        return "a boolean";
      case toml::node_type::array:
        return "an array";
      case toml::node_type::table:
        return "a table";
      default:
        return "a date or time";
    }
  }

  toml::table root_;
  std::string origin_;
  std::map<std::string, std::string> overridden_;
  bool cite_lines_;
};

// Applies one `section.key=value` override; returns the dotted key.
std::string apply_override(toml::table& root, const std::string& text) {
  const auto where = fmt::format("--set {}", text);
  const auto eq = text.find('=');
  if (eq == std::string::npos) throw InputError(fmt::format("{}: expected section.key=value", where));
  const std::string path = text.substr(0, eq);
  const std::string value = text.substr(eq + 1);
  const auto dot = path.find('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 == path.size() || path.find('.', dot + 1) != std::string::npos)
    throw InputError(fmt::format("{}: expected section.key=value, with one dot in section.key", where));
  const std::string section = path.substr(0, dot);
  const std::string key = path.substr(dot + 1);
  if (value.empty()) throw InputError(fmt::format("{}: the value is empty", where));

  toml::table holder;
  try {
    holder = parse_toml("v = " + value, "--set");
  } catch (const InputError&) {
    holder = toml::table{{"v", value}};  // a bare word is a string
  }
  if (holder.size() != 1 || !holder.contains("v")) holder = toml::table{{"v", value}};

  auto* sec = root.get(section);
  if (sec == nullptr) {
    root.insert(section, toml::table{});
    sec = root.get(section);
  }
  if (!sec->is_table()) throw InputError(fmt::format("{}: {} is not a section", where, section));
  sec->as_table()->insert_or_assign(key, std::move(*holder.get("v")));
  return path;
}

// Compiles the expression and evaluates it at every node at t = 0 (and, for
// the body force, at t = end): a value that is NaN or infinite there is bad
// input, not a failed run.
void check_expression(const Reader& r, std::string_view section, std::string_view key, const std::string& text,
                      const BarData& bar, std::initializer_list<double> times) {
  std::unique_ptr<Expression> e;
  try {
    e = std::make_unique<Expression>(text);
  } catch (const InputError& err) {
    r.fail(section, key, fmt::format("= \"{}\" is not a valid expression in x and t: {}", text, err.what()));
  }
  // Where the value cannot change, once is enough: a constant on a mesh of
  // 10^8 elements must not cost seconds.
  const double h = bar.length / bar.elements;
  const int last = e->depends_on_x() ? bar.elements : 0;
  for (double t : times) {
    if (!e->depends_on_t() && t != *times.begin()) break;
    for (int j = 0; j <= last; ++j) {
      const double x = j * h;
      const double v = (*e)(x, t);
      if (!std::isfinite(v))
        r.fail(section, key,
               fmt::format("= \"{}\" must evaluate to a finite number (got {} at x = {}, t = {})", text, v, x, t));
    }
  }
}

Case read_case(const Reader& r) {
  r.check_layout();
  Case c;
  BarData& bar = c.bar;
  bar.length = r.number("bar", "length", bar.length);
  bar.density = r.number("bar", "density", bar.density);
  bar.stiffness = r.number("bar", "stiffness", bar.stiffness);
  bar.viscosity = r.number("bar", "viscosity", bar.viscosity);
  const long long elements = r.integer("bar", "elements", bar.elements);
  if (bar.length <= 0) r.fail("bar", "length", fmt::format("must be > 0 (got {})", bar.length));
  if (bar.density <= 0) r.fail("bar", "density", fmt::format("must be > 0 (got {})", bar.density));
  if (bar.stiffness <= 0) r.fail("bar", "stiffness", fmt::format("must be > 0 (got {})", bar.stiffness));
  if (bar.viscosity < 0) r.fail("bar", "viscosity", fmt::format("must be >= 0 (got {})", bar.viscosity));
  if (elements < 1) r.fail("bar", "elements", fmt::format("must be >= 1 (got {})", elements));
  if (elements > max_elements) r.fail("bar", "elements", fmt::format("must be <= {} (got {})", max_elements, elements));
  bar.elements = static_cast<int>(elements);
  const std::string far_end = r.word("bar", "far_end", "free");
  if (far_end == "free")
    bar.far_end = FarEnd::free;
  else if (far_end == "clamped")
    bar.far_end = FarEnd::clamped;
  else
    r.fail("bar", "far_end", fmt::format("must be one of free, clamped (got \"{}\")", far_end));

  c.load.body_force = r.expression("load", "body_force", c.load.body_force);
  c.initial.displacement = r.expression("initial", "displacement", c.initial.displacement);
  c.initial.velocity = r.expression("initial", "velocity", c.initial.velocity);

  const std::string kind = r.word("obstacle", "kind", "elastic");
  if (kind == "none")
    c.obstacle.kind = ObstacleKind::none;
  else if (kind == "elastic")
    c.obstacle.kind = ObstacleKind::elastic;
  else if (kind == "viscoelastic")
    c.obstacle.kind = ObstacleKind::viscoelastic;
  else if (kind == "rigid")
    c.obstacle.kind = ObstacleKind::rigid;
  else
    r.fail("obstacle", "kind", fmt::format("must be one of none, elastic, viscoelastic, rigid (got \"{}\")", kind));
  c.obstacle.stiffness = r.number("obstacle", "stiffness", c.obstacle.stiffness);
  c.obstacle.gap = r.number("obstacle", "gap", c.obstacle.gap);
  c.obstacle.viscosity = r.number("obstacle", "viscosity", c.obstacle.viscosity);
  if (c.obstacle.stiffness < 0)
    r.fail("obstacle", "stiffness", fmt::format("must be >= 0 (got {})", c.obstacle.stiffness));
  if (c.obstacle.viscosity < 0)
    r.fail("obstacle", "viscosity", fmt::format("must be >= 0 (got {})", c.obstacle.viscosity));

  TimeData& time = c.time;
  time.end = r.number("time", "end", time.end);
  time.step = r.number("time", "step", time.step);
  time.scheme = r.word("time", "scheme", time.scheme);
  time.alpha = r.number("time", "alpha", time.alpha);
  time.lambda = r.number("time", "lambda", time.lambda);
  if (time.step <= 0) r.fail("time", "step", fmt::format("must be > 0 (got {})", time.step));
  if (time.end / time.step > 1e10)
    r.fail("time", "step", fmt::format("gives {:.3g} steps to time.end; at most 1e10", time.end / time.step));
  if (time.alpha < 0 || time.alpha > 0.5)
    r.fail("time", "alpha", fmt::format("must be in [0, 1/2] (got {})", time.alpha));
  if (time.lambda < 0) r.fail("time", "lambda", fmt::format("must be >= 0 (got {})", time.lambda));
  time.beta = r.number("time", "beta", time.beta);
  time.gamma = r.number("time", "gamma", time.gamma);
  time.theta = r.number("time", "theta", time.theta);
  time.restitution = r.number("time", "restitution", time.restitution);
  if (time.beta < 0 || time.beta > 0.5) r.fail("time", "beta", fmt::format("must be in [0, 1/2] (got {})", time.beta));
  if (time.gamma < 0.5 || time.gamma > 1)
    r.fail("time", "gamma", fmt::format("must be in [1/2, 1] (got {})", time.gamma));
  if (time.theta < 0.5 || time.theta > 1)
    r.fail("time", "theta", fmt::format("must be in [1/2, 1] (got {})", time.theta));
  if (time.restitution < 0 || time.restitution > 1)
    r.fail("time", "restitution", fmt::format("must be in [0, 1] (got {})", time.restitution));
  const auto names = scheme_names();
  if (std::find(names.begin(), names.end(), time.scheme) == names.end())
    r.fail("time", "scheme", fmt::format("must be one of {} (got \"{}\")", fmt::join(names, ", "), time.scheme));
  if (const auto misfit = scheme_misfit(c, r.node("time", "step") != nullptr))
    r.fail("time", misfit->key, misfit->rule);
  if (time.end < time.step)
    r.fail("time", "end", fmt::format("must be >= time.step = {} (got {})", time.step, time.end));

  const long long every = r.integer("output", "every", c.output.every);
  if (every < 1) r.fail("output", "every", fmt::format("must be >= 1 (got {})", every));
  if (every > 2'000'000'000) r.fail("output", "every", fmt::format("must be <= 2000000000 (got {})", every));
  c.output.every = static_cast<int>(every);
  c.output.fields_at = r.numbers("output", "fields_at");
  const double t_last = static_cast<double>(c.step_count()) * time.step;
  for (double t : c.output.fields_at)
    if (t < 0 || t > t_last)
      r.fail("output", "fields_at", fmt::format("times must lie in [0, {}] (got {})", t_last, t));
  if (c.step_count() / every > 100'000'000)
    r.fail("output", "every",
           fmt::format("gives {} history rows; at most 1e8 (raise output.every)", c.step_count() / every));

  check_expression(r, "initial", "displacement", c.initial.displacement, bar, {0.0});
  check_expression(r, "initial", "velocity", c.initial.velocity, bar, {0.0});
  check_expression(r, "load", "body_force", c.load.body_force, bar, {0.0, t_last});
  if (bar.far_end == FarEnd::clamped) {
    for (const auto& [key, text] :
         {std::pair{"displacement", c.initial.displacement}, std::pair{"velocity", c.initial.velocity}}) {
      const double at_end = Expression(text)(bar.length, 0.0);
      if (std::abs(at_end) > 1e-12)
        r.fail("initial", key, fmt::format("must vanish at the clamped end x = {} (got {})", bar.length, at_end));
    }
  }
  return c;
}

Case make_case(toml::table root, const std::vector<Case::Override>& overrides, std::string_view origin,
               bool cite_lines) {
  std::map<std::string, std::string> overridden;
  for (const auto& o : overrides) {
    const auto dotted = apply_override(root, o.text);
    overridden[dotted] = fmt::format("--set {}", o.text);
    overridden[dotted.substr(0, dotted.find('.') + 1)] = fmt::format("--set {}", o.text);
  }
  return read_case(Reader(std::move(root), std::string(origin), std::move(overridden), cite_lines));
}

}  // namespace

Case Case::from_string(std::string_view text, const std::vector<Override>& overrides, std::string_view origin,
                       bool cite_lines) {
  return make_case(parse_toml(text, origin), overrides, origin, cite_lines);
}

Case Case::from_file(const std::filesystem::path& path, const std::vector<Override>& overrides) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(fmt::format("{}: no such case file", path.string()));
  if (std::filesystem::is_directory(path, ec))
    throw InputError(fmt::format("{}: is a directory, not a case file", path.string()));
  return from_string(read_input_file(path, "case file"), overrides, path.string());
}

std::string read_input_file(const std::filesystem::path& path, std::string_view what) {
  // Read in chunks, not by stream insertion: an empty file is a valid (all
  // defaults) input, and a device or pipe that never ends must not exhaust memory.
  constexpr std::size_t limit = 64u << 20;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot read the {}", path.string(), what));
  std::string text;
  std::array<char, 1 << 16> chunk{};
  while (in.read(chunk.data(), chunk.size()) || in.gcount() > 0) {
    text.append(chunk.data(), static_cast<std::size_t>(in.gcount()));
    if (text.size() > limit) throw InputError(fmt::format("{}: the {} is larger than 64 MiB", path.string(), what));
  }
  if (in.bad()) throw InputError(fmt::format("{}: cannot read the {}", path.string(), what));
  return text;
}

long long Case::step_count() const {
  const double r = time.end / time.step;
  const double nearest = std::round(r);
  if (std::abs(r - nearest) <= 1e-9 * std::max(1.0, r)) return static_cast<long long>(nearest);
  return static_cast<long long>(std::ceil(r));
}

std::string_view to_string(FarEnd end) {
  return end == FarEnd::free ? "free" : "clamped";
}

std::string_view to_string(BodyKind kind) {
  return kind == BodyKind::bar ? "bar" : "mass";
}

std::string_view to_string(JointLaw law) {
  switch (law) {
    case JointLaw::free:
      return "free";
    case JointLaw::clamped:
      return "clamped";
    case JointLaw::welded:
      return "welded";
    case JointLaw::spring:
      return "spring";
    case JointLaw::elastic:
      return "elastic";
    case JointLaw::viscoelastic:
      return "viscoelastic";
    case JointLaw::rigid:
      return "rigid";
    case JointLaw::cushion:
      return "cushion";
    case JointLaw::force:
      return "force";
    case JointLaw::velocity:
      return "velocity";
  }
  return "?";
}

std::string Case::to_toml() const {
  const toml::table root{
      {"bar", toml::table{{"length", bar.length},
                          {"density", bar.density},
                          {"stiffness", bar.stiffness},
                          {"viscosity", bar.viscosity},
                          {"elements", bar.elements},
                          {"far_end", std::string(to_string(bar.far_end))}}},
      {"load", toml::table{{"body_force", load.body_force}}},
      {"initial", toml::table{{"displacement", initial.displacement}, {"velocity", initial.velocity}}},
      {"obstacle", toml::table{{"kind", std::string(to_string(obstacle.kind))},
                               {"stiffness", obstacle.stiffness},
                               {"gap", obstacle.gap},
                               {"viscosity", obstacle.viscosity}}},
      {"time", toml::table{{"end", time.end},
                           {"step", time.step},
                           {"scheme", time.scheme},
                           {"alpha", time.alpha},
                           {"lambda", time.lambda},
                           {"beta", time.beta},
                           {"gamma", time.gamma},
                           {"theta", time.theta},
                           {"restitution", time.restitution}}},
  };
  // [output] is written by hand: toml++ 3.3's formatter sizes an array of
  // floats with size_t(log10(x)), undefined for |x| < 1 (tomlplusplus#276).
  std::string times;
  for (double t : output.fields_at) {
    std::string text = fmt::format("{}", t);                          // shortest form that reads back exactly
    if (text.find_first_of(".e") == std::string::npos) text += ".0";  // and stays a TOML float
    times += (times.empty() ? "" : ", ") + text;
  }
  std::ostringstream out;
  out << "# barimpact resolved case: every key, defaults filled in\n";
  out << toml::toml_formatter(root) << "\n\n[output]\nevery = " << output.every << "\nfields_at = [" << times << "]\n";
  return out.str();
}

}  // namespace barimpact
