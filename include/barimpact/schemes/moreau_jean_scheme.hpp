// `moreau-jean`: the velocity-level event-capturing scheme of Moreau and
// Jean, as in Siconos' MoreauJeanOSI with a Newton impact law:
//
//   M (v^{n+1} - v^n) = dt (theta f^{n+1} + (1 - theta) f^n) + p e_0,  f = F - K_a u - K_b v,
//   u^{n+1} = u^n + dt (theta v^{n+1} + (1 - theta) v^n),
//   if U^n + g + (dt/2) V^n <= 0:  0 <= p  _|_  V^{n+1} + e V^n >= 0.
//
// W = M + theta dt K_b + theta^2 dt^2 K_a is factored once (from the far
// end); the one-contact LCP is solved in closed form between the two sweeps,
// with w_0 = (W^{-1} e_0)_0. History reports R = p/dt. A step is two passes:
// the right-hand side formed in the sweep towards x = 0, the update of v and
// u in the sweep back.
// The constraint holds on velocities: positions may penetrate by O(dt V).
// theta = 1/2, e = 1 conserves energy at impacts with V^n < 0; e < 1
// dissipates (1 - e^2) of the end's normal kinetic energy.
#pragma once

#include "barimpact/schemes/one_step_scheme.hpp"

namespace barimpact {

class MoreauJeanScheme final : public OneStepScheme {
 public:
  explicit MoreauJeanScheme(const Case& c);
  void start() override { start_state(); }
  void advance() override;

 private:
  template <bool loaded>
  void step();

  double theta_, restitution_;
  FactoredTridiagonal factor_;
  // The right-hand side is P v + Q u + loads, P = M - dt^2 theta (1 - theta) K_a
  // - dt (1 - theta) K_b and Q = -dt K_a, formed inside the first sweep.
  Tridiagonal P_, Q_;
  std::vector<double> rhs_;
};

}  // namespace barimpact
