#include "barimpact/newmark_scheme.hpp"

#include <algorithm>

namespace barimpact {

NewmarkScheme::NewmarkScheme(const Case& c)
    : OneStepScheme(c, Mesh(c.bar.length, c.bar.elements).mass(c.bar.density)),
      beta_(c.time.beta),
      gamma_(c.time.gamma) {
  const Tridiagonal A = Tridiagonal::combine(1.0, Tridiagonal::combine(1.0, mass_, gamma_ * dt_, stiffness_b_),
                                             beta_ * dt_ * dt_, stiffness_a_);
  factor_ = FactoredTridiagonal(A, clamped_);
  const std::size_t n = mesh_.nodes();
  response_ = factor_.response_to_end_force();
  acc_.assign(n, 0.0);
  rhs_.assign(n, 0.0);
}

void NewmarkScheme::start() {
  start_state();
  // a^0 = M^{-1} (F^0 - K_a u^0 - K_b v^0 + R^0 e0).
  const std::size_t n = mesh_.nodes();
  stiffness_a_.multiply(u_, rhs_);
  stiffness_b_.multiply(v_, acc_);
  for (std::size_t j = 0; j < n; ++j) acc_[j] = load_[j] - rhs_[j] - acc_[j];
  acc_[0] += reaction_;
  if (clamped_) acc_[n - 1] = 0.0;
  FactoredTridiagonal(mass_, clamped_).solve(acc_);
}

void NewmarkScheme::advance() {
  begin_step();
  const std::size_t n = mesh_.nodes();
  const double dt = dt_, bdt2 = beta_ * dt * dt, gdt = gamma_ * dt;
  // Predictors, kept in u_ and v_.
  for (std::size_t j = 0; j < n; ++j) {
    u_[j] += dt * v_[j] + (0.5 - beta_) * dt * dt * acc_[j];
    v_[j] += (1.0 - gamma_) * dt * acc_[j];
  }
  // a_lin = A^{-1} (F^{n+1} - K_b v_pred - K_a u_pred).
  stiffness_a_.multiply(u_, rhs_);
  stiffness_b_.multiply(v_, acc_);
  for (std::size_t j = 0; j < n; ++j) acc_[j] = load_next_[j] - rhs_[j] - acc_[j];
  if (clamped_) acc_[n - 1] = 0.0;
  factor_.solve(acc_);

  // R from d(R) = d_lin - beta dt^2 w0 R, dd/dt(R) = rate_lin - gamma dt w0 R.
  const double w0 = response_[0], k = law_.stiffness(), l = law_.viscosity();
  const double d_lin = -(u_[0] + bdt2 * acc_[0] + law_.gap());
  const double rate_lin = -(v_[0] + gdt * acc_[0]);
  double R = 0.0;
  if (law_.kind() != ObstacleKind::none && d_lin > 0.0) {
    const double s = k * d_lin + l * rate_lin;
    if (s > 0.0) {
      R = s / (1.0 + (k * bdt2 + l * gdt) * w0);
      if (bdt2 > 0.0 && d_lin - bdt2 * w0 * R <= 0.0) R = d_lin / (bdt2 * w0);  // stops at the face
    }
  }
  for (std::size_t j = 0; j < n; ++j) {
    acc_[j] += R * response_[j];
    u_[j] += bdt2 * acc_[j];
    v_[j] += gdt * acc_[j];
  }
  // The dashpot's share of the obstacle's work, trapezoidal like the rest.
  double dashpot = 0.0;
  if (l > 0.0 && (R > 0.0 || reaction_ > 0.0)) {
    const double rate = 0.5 * (v_[0] + v_old_[0]);
    dashpot = dt * l * rate * rate;
  }
  reaction_ = R;
  end_step(dashpot);
}

}  // namespace barimpact
