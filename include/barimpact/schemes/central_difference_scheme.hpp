// `central-difference`: the explicit central-difference scheme with lumped
// mass (three_level_scheme.hpp gives the equation and the energy).
//
// Obstacles: the penalty kinds as a force at t_n (the dashpot's rate by a
// backward difference); the rigid obstacle as a kinematic constraint on the
// predicted position, u_0^{n+1} = max(u_0^{n+1,free}, -g), the impulse
// m_0 (u_0^{n+1} - u_0^{n+1,free}) / dt reported as the force impulse / dt.
// Conditionally stable: Case validation refuses a step above stable_step().
#pragma once

#include "barimpact/schemes/three_level_scheme.hpp"

namespace barimpact {

class CentralDifferenceScheme : public ThreeLevelScheme {
 public:
  explicit CentralDifferenceScheme(const Case& c) : ThreeLevelScheme(c, false) {
    lumped_end_ = law_.kind() == ObstacleKind::rigid ? LumpedEnd::clamp : LumpedEnd::free;
  }

 protected:
  void apply_inverse_mass(std::span<double> r) const override;
  double enforce_contact(const double* prev, const double* cur, double* next) override;
};

}  // namespace barimpact
