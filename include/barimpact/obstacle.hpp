// The obstacle law at x = 0: reaction and stored energy as functions of the
// end displacement U. It knows no time step and no scheme (Siconos' split).
#pragma once

#include "barimpact/case.hpp"

namespace barimpact {

class ObstacleLaw {
 public:
  explicit ObstacleLaw(const ObstacleData& data);

  [[nodiscard]] ObstacleKind kind() const { return kind_; }
  /// k, or 0 without an obstacle.
  [[nodiscard]] double stiffness() const { return k_; }
  [[nodiscard]] double gap() const { return gap_; }
  /// Penetration d = (-(U + g))^+, eq. (2.8) with the face at u = -g.
  [[nodiscard]] double penetration(double U) const {
    const double d = -(U + gap_);
    return (kind_ != ObstacleKind::none && d > 0.0) ? d : 0.0;
  }
  /// R = k d >= 0, the force the obstacle puts on the bar.
  [[nodiscard]] double reaction(double U) const { return k_ * penetration(U); }
  /// Energy stored in the obstacle, k d^2 / 2.
  [[nodiscard]] double energy(double U) const {
    const double d = penetration(U);
    return 0.5 * k_ * d * d;
  }

 private:
  ObstacleKind kind_;
  double k_;
  double gap_;
};

}  // namespace barimpact
