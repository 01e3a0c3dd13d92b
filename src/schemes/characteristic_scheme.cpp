#include "barimpact/schemes/characteristic_scheme.hpp"

#include <cmath>

#include "barimpact/model/expression.hpp"

namespace barimpact {

CharacteristicScheme::CharacteristicScheme(const Case& c)
    : CentralDifferenceScheme(c),
      impedance_(c.bar.stiffness / mesh_.h()),
      exact_boundary_(Expression(c.load.body_force).is_zero()) {
  lumped_end_ = LumpedEnd::scheme;  // the end in characteristic variables
}

void CharacteristicScheme::start() {
  started_ = false;
  ThreeLevelScheme::start();
  started_ = true;
}

double CharacteristicScheme::enforce_contact(const double* prev, const double* cur, double* next) {
  if (!exact_boundary_) return CentralDifferenceScheme::enforce_contact(prev, cur, next);
  const double face = -law_.gap();
  const bool rigid = law_.kind() == ObstacleKind::rigid;
  double G_new = 0.0;
  if (!started_) {
    // t = 0: split u0(0) evenly; G(h) = u0(h)/2 + (1/2c) int_0^h v0 (trapezoid,
    // exact for the P1 interpolant): int_0^h v0 / c = dt (v0_0 + v0_1) / 2.
    F_[1] = G_[1] = 0.5 * cur[0];
    G_new = 0.5 * cur[1] + 0.25 * dt_ * (v0_[0] + v0_[1]);
    F_[0] = F_[1];
    G_[0] = G_[1];
    held_ = false;  // nothing before t = 0
  } else {
    G_new = cur[1] - F_[0];  // G(c t_{m+1}) = u_1^m - F(h - c t_m), and h - c t_m = -c t_{m-1}
  }
  double F_new = F_[1] + G_new - G_[1];  // free end
  const bool held = rigid && F_new + G_new < face;
  if (held) F_new = face - G_new;
  // R = -sigma(0) = (a/h)(dF - dG) over a step (0 when free, where dF = dG;
  // -2 (a/h) dG on the obstacle), R^m the mean over the two steps around t_m,
  // i.e. the impulse of [t_m - dt/2, t_m + dt/2] over dt.
  const double right = held ? impedance_ * ((F_new - F_[1]) - (G_new - G_[1])) : 0.0;
  const double left = held_ ? impedance_ * ((F_[1] - F_[0]) - (G_[1] - G_[0])) : 0.0;
  const double force = 0.5 * (left + right);
  held_ = held;
  next[0] = F_new + G_new;
  F_[0] = F_[1];
  G_[0] = G_[1];
  F_[1] = F_new;
  G_[1] = G_new;
  // The base reports twice the force returned at the Taylor start step.
  return started_ ? force : 0.5 * force;
}

}  // namespace barimpact
