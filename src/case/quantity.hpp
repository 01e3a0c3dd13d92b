// A value with a unit, as the pile and Hopkinson keys accept it:
// "900 kN", "2.5 mm", "210 GPa", "65.6 ft", "0.15 s/ft". Converted to SI
// where it is read; a plain number is SI already. Internal to src/.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace barimpact {

/// What a key measures, each with its own units.
enum class Dimension { force, length, area, stress, mass, density, velocity, stiffness, damping };

/// The dimension in words, with its units: "a force: N, kN, MN, lbf, kip".
[[nodiscard]] std::string dimension_units(Dimension d);

/// The SI value of `text`, a number then a unit of `d` ("900 kN" -> 9e5).
/// Metric units shift the number's decimal exponent ("2.5 mm" is read as
/// 2.5e-3, the same double as the literal); US customary units multiply by
/// their exact factor. Returns nullopt with `why` set ("a force: N, kN, ...
/// (kPa is a stress)") when `text` is no number with a unit of `d`.
[[nodiscard]] std::optional<double> si_value(std::string_view text, Dimension d, std::string& why);

/// For a key that also takes an expression (a velocity): the SI value when
/// `text` is a number then a unit ("-14.5 ft/s"), nullopt for anything else
/// (an expression: "-4.43", "x*2"). A number then a unit of another
/// dimension is refused through `why` (set, with nullopt returned).
[[nodiscard]] std::optional<double> suffixed_value(std::string_view text, Dimension d, std::string& why);

}  // namespace barimpact
