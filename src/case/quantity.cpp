#include "quantity.hpp"

#include <fmt/format.h>

#include <array>
#include <charconv>
#include <cmath>
#include <system_error>

#include "barimpact/case/units.hpp"

namespace barimpact {

namespace {

// A unit: metric ones shift the decimal exponent (exact as the literal);
// US customary ones multiply by their factor, or divide (per a length).
struct Unit {
  std::string_view name;
  Dimension dimension;
  int decimal = 0;      // metric: SI = number x 10^decimal
  double factor = 0.0;  // US customary: SI = number x factor (or / factor when per)
  bool per = false;
};

using units::foot, units::inch, units::kip, units::pound, units::pound_force;

constexpr std::array<Unit, 43> unit_table{{
    {"N", Dimension::force},
    {"kN", Dimension::force, 3},
    {"MN", Dimension::force, 6},
    {"lbf", Dimension::force, 0, pound_force},
    {"kip", Dimension::force, 0, kip},
    {"m", Dimension::length},
    {"cm", Dimension::length, -2},
    {"mm", Dimension::length, -3},
    {"in", Dimension::length, 0, inch},
    {"ft", Dimension::length, 0, foot},
    {"m2", Dimension::area},
    {"cm2", Dimension::area, -4},
    {"mm2", Dimension::area, -6},
    {"in2", Dimension::area, 0, inch* inch},
    {"ft2", Dimension::area, 0, foot* foot},
    {"Pa", Dimension::stress},
    {"kPa", Dimension::stress, 3},
    {"MPa", Dimension::stress, 6},
    {"GPa", Dimension::stress, 9},
    {"psi", Dimension::stress, 0, units::psi},
    {"ksi", Dimension::stress, 0, units::ksi},
    {"psf", Dimension::stress, 0, pound_force / (foot * foot)},
    {"ksf", Dimension::stress, 0, kip / (foot * foot)},
    {"kg", Dimension::mass},
    {"t", Dimension::mass, 3},
    {"lb", Dimension::mass, 0, pound},
    {"kg/m3", Dimension::density},
    {"t/m3", Dimension::density, 3},
    {"g/cm3", Dimension::density, 3},
    {"lb/ft3", Dimension::density, 0, pound / (foot * foot * foot)},
    {"m/s", Dimension::velocity},
    {"ft/s", Dimension::velocity, 0, foot},
    {"N/m", Dimension::stiffness},
    {"kN/m", Dimension::stiffness, 3},
    {"MN/m", Dimension::stiffness, 6},
    {"kN/mm", Dimension::stiffness, 6},
    {"GN/m", Dimension::stiffness, 9},
    {"lbf/in", Dimension::stiffness, 0, pound_force / inch},
    {"kip/in", Dimension::stiffness, 0, kip / inch},
    {"kip/ft", Dimension::stiffness, 0, kip / foot},
    {"s/m", Dimension::damping},
    {"s/ft", Dimension::damping, 0, foot, true},
    {"ms/m", Dimension::damping, -3},
}};

std::string_view dimension_name(Dimension d) {
  constexpr std::array<std::string_view, 9> names{"a force",    "a length",    "an area",
                                                  "a stress",   "a mass",      "a density",
                                                  "a velocity", "a stiffness", "a damping (Smith's J)"};
  return names[static_cast<std::size_t>(d)];
}

// "m^2", "kg/m³" as the table spells them: "m2", "kg/m3".
std::string spelled(std::string_view unit) {
  std::string out;
  for (std::size_t i = 0; i < unit.size(); ++i) {
    if (unit[i] == '^') continue;
    if (unit.substr(i).starts_with("\xC2\xB2") || unit.substr(i).starts_with("\xC2\xB3")) {
      out += unit[i + 1] == '\xB2' ? '2' : '3';
      ++i;
      continue;
    }
    out += unit[i];
  }
  return out;
}

const Unit* find_unit(std::string_view name) {
  const std::string s = spelled(name);
  for (const auto& u : unit_table)
    if (u.name == s) return &u;
  return nullptr;
}

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// A number then the rest of the text ("2.5 mm" -> "2.5", "mm"); nullopt
// when the text does not start with a number.
std::optional<std::pair<std::string_view, std::string_view>> split(std::string_view text) {
  text = trimmed(text);
  double ignored = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), ignored);
  if (ec == std::errc::invalid_argument) return std::nullopt;
  const auto n = static_cast<std::size_t>(end - text.data());
  return std::pair{text.substr(0, n), trimmed(text.substr(n))};
}

// The number times 10^shift, read from its text with the exponent moved:
// the nearest double, as a literal of that value would be.
double shifted(std::string_view number, int shift) {
  const auto e = number.find_first_of("eE");
  long long exponent = 0;
  if (e != std::string_view::npos) {
    std::string_view digits = number.substr(e + 1);
    if (digits.starts_with('+')) digits.remove_prefix(1);
    if (std::from_chars(digits.data(), digits.data() + digits.size(), exponent).ec != std::errc()) return std::nan("");
  }
  const std::string text = fmt::format("{}e{}", number.substr(0, e), exponent + shift);
  double v = 0.0;
  if (std::from_chars(text.data(), text.data() + text.size(), v).ec != std::errc()) return std::nan("");
  return v;
}

double converted(std::string_view number, const Unit& u) {
  if (u.factor == 0.0) return shifted(number, u.decimal);
  const double v = shifted(number, 0);
  return u.per ? v / u.factor : v * u.factor;
}

}  // namespace

std::string dimension_units(Dimension d) {
  std::string out = fmt::format("{}:", dimension_name(d));
  const char* sep = " ";
  for (const auto& u : unit_table)
    if (u.dimension == d) {
      out += fmt::format("{}{}", sep, u.name);
      sep = ", ";
    }
  return out;
}

std::optional<double> si_value(std::string_view text, Dimension d, std::string& why) {
  const auto parts = split(text);
  const Unit* u = parts ? find_unit(parts->second) : nullptr;
  if (u == nullptr || u->dimension != d) {
    const std::string found = !parts || parts->second.empty() ? std::string("no unit given; ")
                              : u == nullptr                  ? fmt::format("\"{}\" is no unit known; ", parts->second)
                                             : fmt::format("{} is {}; ", u->name, dimension_name(u->dimension));
    why = fmt::format("= \"{}\": {}{} (or a plain number, in SI)", text, found, dimension_units(d));
    return std::nullopt;
  }
  const double v = converted(parts->first, *u);
  if (!std::isfinite(v)) {
    why = fmt::format("= \"{}\" must be a finite number with its unit", text);
    return std::nullopt;
  }
  return v;
}

std::optional<double> suffixed_value(std::string_view text, Dimension d, std::string& why) {
  const auto parts = split(text);
  if (!parts || parts->second.empty() || find_unit(parts->second) == nullptr) return std::nullopt;
  return si_value(text, d, why);
}

}  // namespace barimpact
