// `newmark`: the textbook baseline, Newmark (beta, gamma) with consistent
// mass and the penalty obstacle (elastic or viscoelastic) treated implicitly.
//
//   M a^{n+1} + K_b v^{n+1} + K_a u^{n+1} = F^{n+1} + R^{n+1} e_0,
//   u^{n+1} = u^n + dt v^n + dt^2 ((1/2 - beta) a^n + beta a^{n+1}),
//   v^{n+1} = v^n + dt ((1 - gamma) a^n + gamma a^{n+1}),
//   R^{n+1} = max(0, k d + l dd/dt) while d = -(u_0^{n+1} + g) > 0.
//
// Only node 0 is nonlinear: with A = M + gamma dt K_b + beta dt^2 K_a
// factored once (from the far end), a^{n+1}_0 = a_lin + R w_0, and R solves
// a scalar piecewise-linear equation in closed form (no iteration) between
// the two sweeps of the solve. beta = 1/4,
// gamma = 1/2 (the defaults) is the trapezoidal rule: energy-conserving
// without contact; the penalty's trapezoidal work is not, at impacts.
// D_visc takes the work of R - k d, the force beyond the spring's: the
// dashpot's, and the spring's k d^2 / 2 released while the law clips.
#pragma once

#include "barimpact/schemes/one_step_scheme.hpp"

namespace barimpact {

class NewmarkScheme final : public OneStepScheme {
 public:
  explicit NewmarkScheme(const Case& c);
  void start() override;
  void advance() override;

 private:
  template <bool loaded, bool viscous>
  void step();
  /// The viscoelastic obstacle's dissipation over the step (D_visc).
  [[nodiscard]] double obstacle_dissipation(double u0_old, double R) const;

  double beta_, gamma_;
  FactoredTridiagonal factor_;
  std::vector<double> acc_, rhs_;
};

}  // namespace barimpact
