// `characteristic`: the reference solution for a uniform elastic bar and a
// rigid obstacle. At Courant number 1 (dt = h/c, set by Case validation) the
// lumped central-difference stencil is the method of characteristics,
//   u_j^{n+1} = u_{j+1}^n + u_{j-1}^n - u_j^{n-1},
// exact at the nodes for every d'Alembert solution u = F(x - ct) + G(x + ct)
// (and, inside the bar, for a constant body force). The end x = 0 is where
// the plain stencil is not exact: when the end leaves the obstacle at a grid
// time it would need G between grid points. So the end is advanced in
// characteristic variables instead: the incoming G(c t_{n+1}) = u_1^n - F(-c t_{n-1})
// is read off the grid, the outgoing F follows from the boundary condition
// (on the obstacle: F = -g - G; free: F(-c t_{n+1}) = F(-c t_n) + G(c t_{n+1}) - G(c t_n)),
// and the end is free when that leaves it at or above the face. The
// reaction is R = -2 rho c^2 G'(ct) while on the obstacle. Without a body
// force this is exact at the nodes at every step (tested against exact
// solutions (a) and (d) to round-off); with one, the end uses the plain
// stencil and is exact while the contact status does not change.
#pragma once

#include "barimpact/schemes/central_difference_scheme.hpp"

namespace barimpact {

class CharacteristicScheme final : public CentralDifferenceScheme {
 public:
  /// Preconditions: c.time.step = h/c, bar.viscosity = 0 (Case validation).
  explicit CharacteristicScheme(const Case& c);
  void start() override;

 protected:
  double enforce_contact(const double* prev, const double* cur, double* next) override;
  [[nodiscard]] bool impulsive_contact() const override { return false; }

 private:
  double impedance_;     // rho c^2 / h = a / h
  bool exact_boundary_;  // no body force
  bool started_ = false;
  // F(-c t) and G(c t) at x = 0 for the last two steps: index 0 is t_{m-1}, 1 is t_m.
  double F_[2] = {0, 0}, G_[2] = {0, 0};
  bool held_ = false;  // the end was on the obstacle over the last step
};

}  // namespace barimpact
