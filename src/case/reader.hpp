// The case file's reader: its contract (sections and keys) and a Reader
// that remembers where each key came from, so that every refusal names the
// file and line, or the --set option, that set it. Internal to src/case/.
#pragma once

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <array>
#include <cmath>
#include <map>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "barimpact/model/input_error.hpp"
#include "quantity.hpp"
#include "toml_input.hpp"

namespace barimpact::detail {

struct SectionKeys {
  std::string_view section;
  std::vector<std::string_view> keys;
};

// The case-file contract: sections and keys, in file order.
inline const std::array<SectionKeys, 12>& contract() {
  static const std::array<SectionKeys, 12> c{{
      {"bar",
       {"length", "density", "stiffness", "viscosity", "elements", "far_end", "material", "yield_stress",
        "hardening_modulus", "hardening"}},
      {"load", {"body_force", "gravity"}},
      {"initial", {"displacement", "velocity"}},
      {"obstacle", {"kind", "stiffness", "gap", "viscosity"}},
      {"near_end",
       {"law", "stiffness", "viscosity", "restitution", "gap", "value", "ultimate", "quake", "damping", "damping_law"}},
      {"far_end",
       {"law", "stiffness", "viscosity", "restitution", "gap", "value", "ultimate", "quake", "damping", "damping_law"}},
      {"blow", {"gauge", "ram", "pile", "rest_window"}},
      {"hammer",
       {"model", "table", "kind", "ram", "stroke", "energy", "efficiency", "pile_cushion", "ram_mass", "anvil_mass",
        "cylinder_area", "compression_length", "chamber_length", "combustion_pressure", "max_stroke",
        "impact_stiffness", "impact_restitution"}},
      {"drive", {"pile", "perimeter", "toe_area", "depths", "refusal", "blow_rate", "blows", "depth"}},
      {"time", {"end", "step", "scheme", "alpha", "lambda", "beta", "gamma", "theta", "restitution", "partitions"}},
      {"output", {"every", "fields_at", "format", "compression"}},
      {"units", {"system"}},
  }};
  return c;
}

// The arrays of tables: [[body]], [[joint]], [[gauge]].
inline const std::array<SectionKeys, 4>& array_contract() {
  static const std::array<SectionKeys, 4> c{{
      {"body",
       {"name", "kind", "length", "elements", "area", "modulus", "density", "viscosity", "mass", "displacement",
        "velocity", "material", "yield_stress", "hardening_modulus", "hardening", "shaft"}},
      {"joint",
       {"name", "between", "law", "stiffness", "viscosity", "restitution", "gap", "cylinder_area", "compression_length",
        "chamber_length", "combustion_pressure", "impact_stiffness", "impact_restitution"}},
      {"gauge", {"name", "body", "at"}},
      {"layer",
       {"top", "bottom", "shaft", "toe", "shaft_quake", "toe_quake", "shaft_damping", "toe_damping", "damping_law",
        "setup"}},
  }};
  return c;
}

inline const SectionKeys* find_array(std::string_view name) {
  for (const auto& s : array_contract())
    if (s.section == name) return &s;
  return nullptr;
}

inline const SectionKeys* find_section(std::string_view name) {
  for (const auto& s : contract())
    if (s.section == name) return &s;
  return nullptr;
}

inline bool has_key(const SectionKeys& s, std::string_view key) {
  for (auto k : s.keys)
    if (k == key) return true;
  return false;
}

// A string's hash that also takes a string_view, for look-ups without a copy.
struct TextHash {
  using is_transparent = void;
  std::size_t operator()(std::string_view text) const { return std::hash<std::string_view>{}(text); }
};

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
    if (const auto* t = viewed(section)) return located(*t);
    if (const auto* t = root_.get(section)) return located(*t);
    return origin_;
  }

  std::string located(const toml::node& n) const {
    const auto& src = n.source();
    if (src.begin.line == 0 || !cite_lines_) return origin_;
    return fmt::format("{}:{}", origin_, src.begin.line);
  }

  void check_layout() const {
    std::vector<std::string_view> names;
    for (const auto& s : contract()) names.push_back(s.section);
    for (const auto& s : array_contract()) names.push_back(s.section);
    for (auto&& [name, value] : root_) {
      const std::string_view sname = name.str();
      const std::string loc =
          overridden_.count(std::string(sname) + ".") ? overridden_.at(std::string(sname) + ".") : located(value);
      if (const auto* array = find_array(sname)) {
        check_array(*array, value, loc);
        continue;
      }
      const auto* section = find_section(sname);
      if (section == nullptr || !value.is_table()) {
        if (section == nullptr)
          throw InputError(fmt::format("{}: unknown section [{}] (known: {})", loc, sname, fmt::join(names, ", ")));
        throw InputError(fmt::format("{}: {} must be a section [{}], not a value", loc, sname, sname));
      }
      check_keys(*section, *value.as_table(), std::string(sname));
    }
  }

  // [[body]], [[joint]], [[gauge]]: arrays of tables with known keys.
  void check_array(const SectionKeys& array, const toml::node& value, const std::string& loc) const {
    const auto* a = value.as_array();
    if (a == nullptr || !a->is_array_of_tables())
      throw InputError(fmt::format("{}: {} must be an array of tables [[{}]]", loc, array.section, array.section));
    for (std::size_t i = 0; i < a->size(); ++i)
      check_keys(array, *(*a)[i].as_table(), fmt::format("{}[{}]", array.section, i + 1));
  }

  void check_keys(const SectionKeys& section, const toml::table& table, const std::string& label) const {
    for (auto&& [key, v] : table) {
      if (has_key(section, key.str())) continue;
      const std::string dotted = fmt::format("{}.{}", label, key.str());
      auto it = overridden_.find(dotted);
      throw InputError(fmt::format("{}: unknown key {} (known in [{}]: {})",
                                   it != overridden_.end() ? it->second : located(v), dotted, section.section,
                                   fmt::join(section.keys, ", ")));
    }
  }

  /// Lets `label` ("body.pile") name a table of an array, for node() and messages.
  void view(const std::string& label, const toml::table* table) { views_[label] = table; }
  /// The same for as long as this table is read, until the next glance:
  /// for the names a table goes by only while it is read ("joint[3]",
  /// "joint.a-b"), with no entry kept for each of 10^5 tables.
  void glance(std::string label, const toml::table* table) { glanced_ = {std::move(label), table}; }
  /// Room for a view of every [[body]], made once.
  void reserve_views() {
    if (const auto* bodies = root_.get_as<toml::array>("body")) views_.reserve(bodies->size());
  }
  [[nodiscard]] const toml::table& root() const { return root_; }
  /// The file (or text) read, as messages name it.
  [[nodiscard]] const std::string& origin() const { return origin_; }

  const toml::node* node(std::string_view section, std::string_view key) const {
    const auto* t = table(section);
    return t ? t->get(key) : nullptr;
  }

  /// The table `section` names (a view, or a section of the file), or null.
  const toml::table* table(std::string_view section) const {
    if (const auto* t = viewed(section)) return t;
    return root_.get_as<toml::table>(section);
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
      fail(section, key, fmt::format("must be a number (got {})", toml_type_name(*n)));
    if (!std::isfinite(v)) fail(section, key, fmt::format("must be a finite number (got {})", v));
    return v;
  }

  /// A number in SI, or a text of a number and a unit of `d` ("900 kN"), converted to SI.
  double quantity(std::string_view section, std::string_view key, double fallback, Dimension d) const {
    const auto* n = node(section, key);
    if (n == nullptr || !n->is_string()) return number(section, key, fallback);
    std::string why;
    const auto v = si_value(n->as_string()->get(), d, why);
    if (!v) fail(section, key, why);
    return *v;
  }

  /// An expression, whose text may instead be a number and a unit of `d`
  /// ("-14.5 ft/s"): then that number in SI, as text.
  std::string expression_or_quantity(std::string_view section, std::string_view key, std::string_view fallback,
                                     Dimension d) const {
    std::string text = expression(section, key, fallback);
    std::string why;
    const auto v = suffixed_value(text, d, why);
    if (!why.empty()) fail(section, key, why);
    return v ? fmt::format("{}", *v) : text;
  }

  long long integer(std::string_view section, std::string_view key, long long fallback) const {
    const auto* n = node(section, key);
    if (n == nullptr) return fallback;
    if (const auto* i = n->as_integer()) return i->get();
    fail(section, key, fmt::format("must be an integer (got {})", toml_type_name(*n)));
  }

  std::string word(std::string_view section, std::string_view key, std::string_view fallback) const {
    const auto* n = node(section, key);
    if (n == nullptr) return std::string(fallback);
    if (const auto* s = n->as_string()) return s->get();
    fail(section, key, fmt::format("must be a string (got {})", toml_type_name(*n)));
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
    fail(section, key, fmt::format("must be an expression in x and t (got {})", toml_type_name(*n)));
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
      fail(section, key, fmt::format("must be an array of numbers (found {})", toml_type_name(e)));
    };
    if (const auto* a = n->as_array()) {
      for (const auto& e : *a) out.push_back(one(e));
    } else {
      out.push_back(one(*n));
    }
    return out;
  }

 private:
  toml::table root_;
  std::string origin_;
  std::map<std::string, std::string> overridden_;
  bool cite_lines_;
  std::unordered_map<std::string, const toml::table*, TextHash, std::equal_to<>> views_;  // found by a string_view
  std::pair<std::string, const toml::table*> glanced_{"", nullptr};

  const toml::table* viewed(std::string_view label) const {
    if (glanced_.second != nullptr && glanced_.first == label) return glanced_.second;
    const auto it = views_.find(label);
    return it == views_.end() ? nullptr : it->second;
  }
};

}  // namespace barimpact::detail
