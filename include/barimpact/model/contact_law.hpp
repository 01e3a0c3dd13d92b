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
//
// Energy: a cushion stores what it gives back, (k / 2 e^2)((c - (1 - e^2) c_max)^+)^2,
// and has dissipated k (1 - e^2) c_max^2 / 2, a function of c_max alone.
#pragma once

#include <algorithm>
#include <string_view>

namespace barimpact {

enum class LawKind { elastic, viscoelastic, cushion, rigid };

[[nodiscard]] std::string_view to_string(LawKind kind);

struct ContactLaw {
  LawKind kind = LawKind::elastic;
  double stiffness = 0.0;    ///< k (loading, for a cushion)
  double viscosity = 0.0;    ///< l, viscoelastic
  double restitution = 1.0;  ///< e: a cushion's; a rigid link's for the event-capturing schemes

  [[nodiscard]] bool rigid() const { return kind == LawKind::rigid; }
  /// p >= 0 for compression c, its rate, and c_max >= c.
  [[nodiscard]] double force(double c, double rate, double c_max) const {
    if (c <= 0.0) return 0.0;
    switch (kind) {
      case LawKind::elastic:
        return stiffness * c;
      case LawKind::viscoelastic:
        return std::max(0.0, stiffness * c + viscosity * rate);
      case LawKind::cushion: {
        const double e2 = restitution * restitution;
        return std::max(0.0, std::min(stiffness * c, stiffness / e2 * (c - (1.0 - e2) * c_max)));
      }
      case LawKind::rigid:
        break;
    }
    return 0.0;
  }
  /// The energy the law stores at compression c (and gives back on unloading).
  [[nodiscard]] double energy(double c, double c_max) const {
    if (kind == LawKind::cushion) {
      const double e2 = restitution * restitution;
      const double s = std::max(0.0, c - (1.0 - e2) * c_max);
      return 0.5 * stiffness / e2 * s * s;
    }
    if (kind == LawKind::rigid || c <= 0.0) return 0.0;
    return 0.5 * stiffness * c * c;
  }
  /// What a cushion's hysteresis has dissipated once compressed to c_max.
  [[nodiscard]] double hysteresis(double c_max) const {
    if (kind != LawKind::cushion) return 0.0;
    return 0.5 * stiffness * (1.0 - restitution * restitution) * c_max * c_max;
  }
};

}  // namespace barimpact
