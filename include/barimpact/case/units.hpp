// The display systems of `[units] system`: the units the console prints a
// pile's numbers in. The case, the solver and every file stay in SI; only
// what is printed is converted, with the exact factors below.
#pragma once

#include <string_view>

namespace barimpact::units {

// US customary units in SI, exact by definition (the international foot and
// pound of 1959; the pound-force is the pound under standard gravity,
// 9.80665 m/s^2).
inline constexpr double foot = 0.3048;                      // m
inline constexpr double inch = 0.0254;                      // m
inline constexpr double pound = 0.45359237;                 // kg
inline constexpr double pound_force = 4.4482216152605;      // N
inline constexpr double kip = 1000.0 * pound_force;         // N
inline constexpr double psi = pound_force / (inch * inch);  // Pa
inline constexpr double ksi = kip / (inch * inch);          // Pa
inline constexpr double kip_foot = kip * foot;              // J

/// A unit shown: a value in SI times `scale` reads in `name`.
struct Shown {
  double scale = 1.0;
  std::string_view name;
  [[nodiscard]] double operator()(double si) const { return si * scale; }
};

/// A pile's console units in one display system.
struct Display {
  std::string_view system;
  Shown set;                    ///< a blow's set, a diesel's first set
  Shown depth;                  ///< depths, strokes
  Shown stress;                 ///< the pile's stresses
  Shown force;                  ///< capacities
  Shown energy;                 ///< hammer energy, ENTHRU, gas works
  Shown velocity;               ///< impact velocities
  double count_length = 0.25;   ///< a blow count is per this length (m)
  std::string_view count_name;  ///< "blows per 250 mm", "blows/ft"
  [[nodiscard]] double count(double blows_per_m) const { return count_length * blows_per_m; }
};

inline constexpr Display si_display{"SI",       {1e3, "mm"},  {1.0, "m"}, {1e-6, "MPa"},     {1.0, "N"},
                                    {1.0, "J"}, {1.0, "m/s"}, 0.25,       "blows per 250 mm"};
inline constexpr Display us_display{"US",
                                    {1.0 / inch, "in"},
                                    {1.0 / foot, "ft"},
                                    {1.0 / ksi, "ksi"},
                                    {1.0 / kip, "kip"},
                                    {1.0 / kip_foot, "kip-ft"},
                                    {1.0 / foot, "ft/s"},
                                    foot,
                                    "blows/ft"};

/// The display of "SI" or "US"; null for "none" (the case's own numbers, no unit).
[[nodiscard]] constexpr const Display* display(std::string_view system) {
  if (system == "SI") return &si_display;
  if (system == "US") return &us_display;
  return nullptr;
}

}  // namespace barimpact::units
