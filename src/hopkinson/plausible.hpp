// Plausibility of a Hopkinson setup's numbers in SI: a number far outside
// what any bar, specimen or record can have is a unit slip, refused with the
// unit it was probably meant in ("bar.modulus = 200: GPa? ...").
#pragma once

#include <cmath>
#include <initializer_list>
#include <limits>
#include <string>

#include <fmt/format.h>

namespace barimpact::hopkinson_plausible {

/// What a quantity can be, and what it usually is (which unit a slip was in
/// is the one that brings it nearest that).
struct Bounds {
  double lo, hi, typical;
  [[nodiscard]] bool holds(double v) const { return v >= lo && v <= hi; }
};

/// A unit a number may have been given in: its value in SI is v x factor.
struct Unit {
  double factor;
  const char* name;
};

/// "GPa? " when v in one of the units falls within the bounds (the one
/// nearest the typical value), else "".
inline std::string meant(double v, const Bounds& b, std::initializer_list<Unit> units) {
  const char* best = nullptr;
  double distance = std::numeric_limits<double>::infinity();
  for (const auto& u : units) {
    const double si = v * u.factor;
    if (!b.holds(si)) continue;
    const double d = std::abs(std::log(si / b.typical));
    if (d < distance) distance = d, best = u.name;
  }
  return best ? fmt::format("{}? ", best) : std::string();
}

/// A record's sample interval, s: the fastest digitisers (1e-11 s) to a rate
/// that leaves a pulse (20 us to a few ms) a sample or two; usually 1e-7.
inline constexpr Bounds sample_interval{1e-12, 1e-3, 1e-7};
/// An incident pulse's duration, s: 2 L / c0 of a striker, from 20 us (a
/// short striker in steel) to 4 ms (3 m in a polymer bar, c0 about 1500 m/s).
inline constexpr Bounds pulse_duration{0.0, 1e-2, 1e-4};
/// A specimen's results beyond which no bar test reaches: strain rates of
/// 1e2 to 1e4 /s (1e5 in miniature bars; 1e6 is plate impact's), stresses
/// of a few GPa (the bars yield near 2 GPa; a specimen a quarter of their
/// area sees four times that), a modulus above diamond's 1.2 TPa.
inline constexpr double highest_strain_rate = 1e6, highest_stress = 5e10, highest_modulus = 1.5e12;
/// The units a record's clock is often in.
inline constexpr std::initializer_list<Unit> time_units{{1e-3, "ms"}, {1e-6, "us"}, {1e-9, "ns"}};

}  // namespace barimpact::hopkinson_plausible
