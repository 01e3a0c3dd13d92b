// The laws of a unilateral link (a joint between two faces, or an end
// against the ground) as functions of the compression c = -y (y the
// opening), its rate and its history. They know no time step and no scheme
// (Siconos' split): a scheme decides how to step them.
//
//   elastic       p = k c^+                                  (the paper's (2.8))
//   viscoelastic  p = max(0, k c + l dc/dt) while c > 0
//   cushion       p = max(0, min(k c, (k / e^2)(c - (1 - e^2) c_max)))  (Smith's capblock:
//                 loads along k, unloads and reloads along k / e^2; c_max the largest c so far)
//   rigid         c <= 0, p >= 0, p c = 0: the force is the constraint's multiplier
//   smith         Smith's (1960) toe: R_s = min(R_u, k (c - s)^+), k = R_u / q, its slip
//                 s = (c_max - q)^+ (the soil's permanent set); p = max(0, R_s + J |R_s| dc/dt)
//                 (damping_law smith) or, while c > s, max(0, R_s + J R_u dc/dt) (viscous)
//   diesel        an open-end diesel hammer's cylinder between anvil (a) and ram (b): a cushion
//                 (k, e) at c > 0 plus the gas force (p - p_atm) A at any opening y = -c
//                 below the ports (DieselGas); p may pull (< p_atm) late in the expansion
//
// Energy: a cushion stores what it gives back, (k / 2 e^2)((c - (1 - e^2) c_max)^+)^2,
// and has dissipated k (1 - e^2) c_max^2 / 2, a function of c_max alone. Smith's
// soil stores k ((c - s)^+)^2 / 2 and its slip has dissipated R_u s; its damping's
// work depends on the path (the schemes book it). A diesel cylinder's gas is
// outside the line: its force's work is W_ext (the schemes book it), its
// cushion stores and dissipates as a cushion's.
#pragma once

#include <algorithm>
#include <cmath>
#include <string_view>

namespace barimpact {

enum class LawKind { elastic, viscoelastic, cushion, rigid, smith, diesel };

[[nodiscard]] std::string_view to_string(LawKind kind);

/// How Smith's soil damps: J |R_s| v (Smith 1960; GRLWEAP's "Smith"), or
/// J R_u v (GRLWEAP's "Smith-viscous"), v the velocity into the soil.
enum class DampingLaw { smith, viscous };

/// A two-way Smith spring's slip after the penetration reaches w: the spring
/// stays within its quake q of it, k |w - s| <= R_u (Smith's side springs).
[[nodiscard]] inline double smith_slip(double slip, double w, double quake) {
  return std::min(std::max(slip, w - quake), w + quake);
}

/// Smith's soil resistance at a penetration w (into the soil) with slip s:
/// the static force k (w - s) of the elastic-perfectly-plastic spring
/// (k = R_u / q), and its damping at rate v, J |R_s| v or J R_u v.
struct SoilSpring {
  double ultimate = 0.0;  ///< R_u
  double quake = 1.0;     ///< q
  double damping = 0.0;   ///< J, s/m
  DampingLaw damping_law = DampingLaw::smith;
  [[nodiscard]] double stiffness() const { return ultimate / quake; }
  [[nodiscard]] double damping_force(double r_static, double v) const {
    return damping * (damping_law == DampingLaw::smith ? std::abs(r_static) : ultimate) * v;
  }
};

/// An open-end diesel hammer's gas (project issue 32's contract): the
/// ram falls past the exhaust ports at the opening y = L_c above impact and
/// compresses the air from p_atm, p V^1.35 = const (V = A (L_ch + y)); the
/// fuel burns at impact (the first c > 0) to p_comb and the gas expands,
/// p V^1.25 = const, until the ports open again at y = L_c.
struct DieselGas {
  static constexpr double atmosphere = 101325.0;  ///< p_atm, Pa
  static constexpr double compression_exponent = 1.35, expansion_exponent = 1.25;
  double area = 0.0;                 ///< A, the cylinder's bore area (m^2)
  double compression_length = 0.0;   ///< L_c: the ports' height above impact (m)
  double chamber_length = 0.0;       ///< L_ch: the gas column at impact (m)
  double combustion_pressure = 0.0;  ///< p_comb (Pa, absolute)

  /// The absolute pressure at opening y, before (`fired` false) or after the impact.
  [[nodiscard]] double pressure(double y, bool fired) const {
    if (y >= compression_length) return atmosphere;  // the ports are open
    const double v = chamber_length + y;
    return fired ? combustion_pressure * std::pow(chamber_length / v, expansion_exponent)
                 : atmosphere * std::pow((chamber_length + compression_length) / v, compression_exponent);
  }
  /// (p - p_atm) A, pushing the faces apart.
  [[nodiscard]] double force(double y, bool fired) const { return (pressure(y, fired) - atmosphere) * area; }
  /// W_c = A int_0^L_c (p - p_atm) dy on the compression polytrope: the
  /// ram's work on the gas from the ports to impact.
  [[nodiscard]] double compression_work() const {
    return polytrope_work(atmosphere * std::pow(chamber_length + compression_length, compression_exponent),
                          compression_exponent);
  }
  /// W_e, the same on the expansion polytrope: the gas's work from impact to the ports.
  [[nodiscard]] double expansion_work() const {
    return polytrope_work(combustion_pressure * std::pow(chamber_length, expansion_exponent), expansion_exponent);
  }
  /// The stiffest slope |dF/dy| = n p A / (L_ch + y), at impact.
  [[nodiscard]] double largest_stiffness() const {
    return std::max(compression_exponent * pressure(0.0, false), expansion_exponent * pressure(0.0, true)) * area /
           chamber_length;
  }

 private:
  // A int_0^L_c (C (L_ch + y)^-n - p_atm) dy, C = p V^n per unit area.
  [[nodiscard]] double polytrope_work(double c, double n) const {
    const double top = chamber_length + compression_length;
    return area * (c * (std::pow(chamber_length, 1.0 - n) - std::pow(top, 1.0 - n)) / (n - 1.0) -
                   atmosphere * compression_length);
  }
};

struct ContactLaw {
  LawKind kind = LawKind::elastic;
  double stiffness = 0.0;    ///< k (loading, for a cushion)
  double viscosity = 0.0;    ///< l, viscoelastic
  double restitution = 1.0;  ///< e: a cushion's; a rigid link's for the event-capturing schemes
  SoilSpring soil;           ///< smith: R_u, q, J, its damping law (stiffness is R_u / q)
  DieselGas gas{};           ///< diesel: the cylinder (stiffness and restitution: the impact cushion's)

  [[nodiscard]] bool rigid() const { return kind == LawKind::rigid; }
  /// p >= 0 for compression c, its rate, and c_max >= c (a diesel gas may pull, p < 0).
  [[nodiscard]] double force(double c, double rate, double c_max) const {
    if (kind == LawKind::diesel) return cushion_force(c, c_max) + gas_force(c, c_max);
    if (c <= 0.0) return 0.0;
    switch (kind) {
      case LawKind::elastic:
        return stiffness * c;
      case LawKind::viscoelastic:
        return std::max(0.0, stiffness * c + viscosity * rate);
      case LawKind::cushion:
        return cushion_force(c, c_max);
      case LawKind::smith: {
        const double slip = std::max(0.0, c_max - soil.quake);
        if (c <= slip) return 0.0;  // above its slipped position: the toe has left the soil
        const double r = std::min(soil.ultimate, stiffness * (c - slip));
        return std::max(0.0, r + soil.damping_force(r, rate));
      }
      case LawKind::rigid:
      case LawKind::diesel:
        break;
    }
    return 0.0;
  }
  /// A diesel cylinder's gas force (p - p_atm) A at compression c, burnt once
  /// the ram struck (c_max > 0); 0 for the other laws.
  [[nodiscard]] double gas_force(double c, double c_max) const {
    return kind == LawKind::diesel ? gas.force(-c, c_max > 0.0) : 0.0;
  }
  /// Smith's static part R_s alone (the law's force for the others without
  /// their dashpot): what the damping's work is measured against.
  [[nodiscard]] double static_force(double c, double c_max) const {
    if (c <= 0.0) return 0.0;
    if (kind == LawKind::smith) {
      const double slip = std::max(0.0, c_max - soil.quake);
      return c <= slip ? 0.0 : std::min(soil.ultimate, stiffness * (c - slip));
    }
    if (kind == LawKind::viscoelastic) return stiffness * c;
    return force(c, 0.0, c_max);
  }
  /// What of the force p at compression c is damping (a viscoelastic law's
  /// dashpot, Smith's soil damping): p less the static part; 0 for the others.
  [[nodiscard]] double damping_part(double p, double c, double c_max) const {
    return kind == LawKind::viscoelastic || kind == LawKind::smith ? p - static_force(c, c_max) : 0.0;
  }
  /// The largest dashpot coefficient the law can show (l, or J R_u), for stable steps.
  [[nodiscard]] double largest_viscosity() const {
    return kind == LawKind::smith ? soil.damping * soil.ultimate : kind == LawKind::viscoelastic ? viscosity : 0.0;
  }
  /// The stiffest slope of the law (k, or a cushion's unloading k / e^2, and a diesel gas's).
  [[nodiscard]] double largest_stiffness() const {
    if (kind == LawKind::diesel) return stiffness / (restitution * restitution) + gas.largest_stiffness();
    return kind == LawKind::cushion ? stiffness / (restitution * restitution) : stiffness;
  }
  /// The energy the law stores at compression c (and gives back on unloading);
  /// a diesel cylinder's cushion's (its gas's work is external).
  [[nodiscard]] double energy(double c, double c_max) const {
    if (kind == LawKind::cushion || kind == LawKind::diesel) {
      const double e2 = restitution * restitution;
      const double s = std::max(0.0, c - (1.0 - e2) * c_max);
      return 0.5 * stiffness / e2 * s * s;
    }
    if (kind == LawKind::smith) {
      const double e = std::min(soil.quake, c - std::max(0.0, c_max - soil.quake));
      return e > 0.0 ? 0.5 * stiffness * e * e : 0.0;
    }
    if (kind == LawKind::rigid || c <= 0.0) return 0.0;
    return 0.5 * stiffness * c * c;
  }
  /// What a cushion's hysteresis, or Smith's slip R_u s, has dissipated once compressed to c_max.
  [[nodiscard]] double hysteresis(double c_max) const {
    if (kind == LawKind::smith) return soil.ultimate * std::max(0.0, c_max - soil.quake);
    if (kind != LawKind::cushion && kind != LawKind::diesel) return 0.0;
    return 0.5 * stiffness * (1.0 - restitution * restitution) * c_max * c_max;
  }

 private:
  // Smith's capblock: along k loading, k / e^2 unloading from c_max.
  [[nodiscard]] double cushion_force(double c, double c_max) const {
    if (c <= 0.0) return 0.0;
    const double e2 = restitution * restitution;
    return std::max(0.0, std::min(stiffness * c, stiffness / e2 * (c - (1.0 - e2) * c_max)));
  }
};

}  // namespace barimpact
