// `mass-redistribution` (Khenous, Laborde & Renard 2008): the contact node's
// mass is moved to its neighbour (element 0's mass rho h sits on node 1, the
// total mass is kept), so that node 0 carries no inertia and the
// semi-discrete Signorini problem is well posed. Node 0 is then in static
// equilibrium with the obstacle at every t_{n+1}:
//   (a/h)(u_0 - u_1) = F_0 + lambda,  lambda >= 0,  u_0 + g >= 0,  lambda (u_0 + g) = 0,
// i.e. u_0 = max(-g, u_1 + h F_0 / a); the other nodes follow the
// Crank-Nicolson (midpoint) rule
//   M~ (v^{n+1} - v^n) = dt (Fbar - K_a (u^n + u^{n+1}) / 2),  u^{n+1} - u^n = dt (v^n + v^{n+1}) / 2.
// Two factorisations (node 0 free: u_0 tied to u_1; on the obstacle: u_0 = -g)
// are made once, from the far end, so that they differ only in node 1's
// pivot: a step sweeps towards x = 0 once, tries the previous status at
// node 1 and switches if it is inconsistent, then sweeps back. Energy is conserved while the status does not
// change, and no chatter arises (node 0 has nothing to bounce with). Elastic
// bar only; V at x = 0 is the backward difference of the massless node.
#pragma once

#include "barimpact/schemes/one_step_scheme.hpp"

namespace barimpact {

class MassRedistributionScheme final : public OneStepScheme {
 public:
  explicit MassRedistributionScheme(const Case& c);
  void start() override;
  void advance() override;

 private:
  template <bool loaded>
  void step();

  double a_over_h_;
  Tridiagonal reduced_;  // 2/dt^2 M~ + K_a/2 on nodes 1..M
  FactoredTridiagonal contact_factor_;
  double free_inverse_pivot_ = 0.0;  // node 1's, when node 0 is free
  std::vector<double> reduced_rhs_;
  bool on_obstacle_ = false;
};

/// The redistributed mass matrix M~ (element 0's mass on node 1).
[[nodiscard]] Tridiagonal redistributed_mass(const Mesh& mesh, double density);

}  // namespace barimpact
