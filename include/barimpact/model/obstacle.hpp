// The obstacle law at x = 0: the reaction and stored energy as functions of
// the end's displacement U and velocity V. It knows no time step and no
// scheme (Siconos' split). A rigid obstacle has no law of this kind: its
// reaction is the constraint's multiplier, which the scheme computes.
#pragma once

#include <algorithm>

#include <string_view>

namespace barimpact {

enum class ObstacleKind { none, elastic, viscoelastic, rigid };
struct ObstacleData {
  ObstacleKind kind = ObstacleKind::elastic;
  double stiffness = 100.0;  ///< k, eq. (2.8)
  double gap = 0.0;          ///< g: the face is at u = -g
  double viscosity = 0.0;    ///< l, viscoelastic: R = max(0, k d + l dd/dt) while d > 0
};

[[nodiscard]] std::string_view to_string(ObstacleKind kind);

class ObstacleLaw {
 public:
  explicit ObstacleLaw(const ObstacleData& data);

  [[nodiscard]] ObstacleKind kind() const { return kind_; }
  /// k for the penalty kinds (elastic, viscoelastic), else 0.
  [[nodiscard]] double stiffness() const { return k_; }
  /// l for the viscoelastic kind, else 0.
  [[nodiscard]] double viscosity() const { return l_; }
  [[nodiscard]] double gap() const { return gap_; }
  /// Penetration d = (-(U + g))^+: the face is at u = -g.
  [[nodiscard]] double penetration(double U) const {
    const double d = -(U + gap_);
    return (kind_ != ObstacleKind::none && d > 0.0) ? d : 0.0;
  }
  /// R >= 0, the force on the bar: k d (2.8), or max(0, k d + l dd/dt)
  /// while d > 0 for the viscoelastic obstacle (dd/dt = -V).
  [[nodiscard]] double reaction(double U, double V) const {
    const double d = penetration(U);
    if (d <= 0.0) return 0.0;
    return std::max(0.0, k_ * d - l_ * V);
  }
  /// Energy stored in the obstacle's spring, k d^2 / 2.
  [[nodiscard]] double energy(double U) const {
    const double d = penetration(U);
    return 0.5 * k_ * d * d;
  }

 private:
  ObstacleKind kind_;
  double k_;
  double l_;
  double gap_;
};

}  // namespace barimpact
