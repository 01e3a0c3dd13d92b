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
  const double v0_old = v_[0];
  begin_step(budget_needs_old());
  const std::size_t n = mesh_.nodes(), last = n - 1;
  const double dt = dt_, bdt2 = beta_ * dt * dt, gdt = gamma_ * dt;
  const double c1 = (0.5 - beta_) * dt * dt, c2 = (1.0 - gamma_) * dt;
  double* __restrict u = u_.data();
  double* __restrict v = v_.data();
  double* __restrict acc = acc_.data();
  double* __restrict y = rhs_.data();
  // Pass 1: the predictors, in place (vectorised).
  for (std::size_t j = 0; j < n; ++j) {
    u[j] += dt * v[j] + c1 * acc[j];
    v[j] += c2 * acc[j];
  }
  // Pass 2: r = F^{n+1} - K_a u_pred - K_b v_pred inside the forward sweep of A.
  const double* __restrict kd = stiffness_a_.diag.data();
  const double* __restrict ko = stiffness_a_.off.data();
  const double* __restrict bd = stiffness_b_.diag.data();
  const double* __restrict bo = stiffness_b_.off.data();
  const double* __restrict f = load_next_.data();
  const double* __restrict lower = factor_.lower();
  const double* __restrict inv = factor_.inverse_pivots();
  const double* __restrict su = factor_.scaled_upper();
  double carry = f[0] - (kd[0] * u[0] + ko[0] * u[1]) - (bd[0] * v[0] + bo[0] * v[1]);
  y[0] = carry;
  for (std::size_t j = 1; j < last; ++j) {
    const double r = f[j] - (kd[j] * u[j] + ko[j - 1] * u[j - 1] + ko[j] * u[j + 1]) -
                     (bd[j] * v[j] + bo[j - 1] * v[j - 1] + bo[j] * v[j + 1]);
    carry = r - lower[j] * carry;
    y[j] = carry;
  }
  const double r_last = clamped_ ? 0.0
                                 : f[last] - (kd[last] * u[last] + ko[last - 1] * u[last - 1]) -
                                       (bd[last] * v[last] + bo[last - 1] * v[last - 1]);
  y[last] = r_last - lower[last] * carry;
  // Pass 3: backward sweep, a_lin, and the update as if R = 0.
  double x = y[last] * inv[last];
  acc[last] = x;
  u[last] += bdt2 * x;
  v[last] += gdt * x;
  for (std::size_t j = last; j-- > 0;) {
    x = y[j] * inv[j] - su[j] * x;
    acc[j] = x;
    u[j] += bdt2 * x;
    v[j] += gdt * x;
  }

  // R from d(R) = d_lin - beta dt^2 w0 R, dd/dt(R) = rate_lin - gamma dt w0 R,
  // where d_lin and rate_lin are the R = 0 values now in u_0, v_0.
  const double w0 = response_[0], k = law_.stiffness(), l = law_.viscosity();
  const double d_lin = -(u[0] + law_.gap());
  const double rate_lin = -v[0];
  double R = 0.0;
  if (law_.kind() != ObstacleKind::none && d_lin > 0.0) {
    const double s = k * d_lin + l * rate_lin;
    if (s > 0.0) {
      R = s / (1.0 + (k * bdt2 + l * gdt) * w0);
      if (bdt2 > 0.0 && d_lin - bdt2 * w0 * R <= 0.0) R = d_lin / (bdt2 * w0);  // stops at the face
    }
  }
  if (R > 0.0) {  // pass 4, in contact only: a += R w
    const double* __restrict w = response_.data();
    for (std::size_t j = 0; j < n; ++j) {
      acc[j] += R * w[j];
      u[j] += bdt2 * R * w[j];
      v[j] += gdt * R * w[j];
    }
  }
  // The dashpot's share of the obstacle's work, trapezoidal like the rest.
  double dashpot = 0.0;
  if (l > 0.0 && (R > 0.0 || reaction_ > 0.0)) {
    const double rate = 0.5 * (v[0] + v0_old);
    dashpot = dt * l * rate * rate;
  }
  reaction_ = R;
  end_step(dashpot);
}

}  // namespace barimpact
