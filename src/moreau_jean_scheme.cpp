#include "barimpact/moreau_jean_scheme.hpp"

#include <algorithm>

namespace barimpact {

MoreauJeanScheme::MoreauJeanScheme(const Case& c)
    : OneStepScheme(c, Mesh(c.bar.length, c.bar.elements).mass(c.bar.density)),
      theta_(c.time.theta),
      restitution_(c.time.restitution) {
  const double th = theta_ * dt_;
  const Tridiagonal W =
      Tridiagonal::combine(1.0, Tridiagonal::combine(1.0, mass_, th, stiffness_b_), th * th, stiffness_a_);
  factor_ = FactoredTridiagonal(W, clamped_);
  const std::size_t n = mesh_.nodes();
  response_ = factor_.response_to_end_force();
  rhs_.assign(n, 0.0);
  P_ = Tridiagonal::combine(1.0, Tridiagonal::combine(1.0, mass_, -dt_ * dt_ * theta_ * (1.0 - theta_), stiffness_a_),
                            -dt_ * (1.0 - theta_), stiffness_b_);
  Q_ = Tridiagonal::combine(-dt_, stiffness_a_, 0.0, stiffness_a_);
}

void MoreauJeanScheme::advance() {
  // Contact predicted active at t_n: U^n + g + (dt/2) V^n <= 0 (read before the step).
  const double U = u_[0], V = v_[0], dt = dt_, th = theta_;
  const bool active = law_.kind() == ObstacleKind::rigid && U + law_.gap() + 0.5 * dt * V <= 0.0;
  begin_step(budget_needs_old());
  const std::size_t n = mesh_.nodes(), last = n - 1;
  const double* __restrict pd = P_.diag.data();
  const double* __restrict po = P_.off.data();
  const double* __restrict qd = Q_.diag.data();
  const double* __restrict qo = Q_.off.data();
  const double* __restrict f0 = load_.data();
  const double* __restrict f1 = load_next_.data();
  const double* __restrict lower = factor_.lower();
  const double* __restrict inv = factor_.inverse_pivots();
  const double* __restrict su = factor_.scaled_upper();
  double* __restrict u = u_.data();
  double* __restrict v = v_.data();
  double* __restrict y = rhs_.data();
  const double cf1 = dt * th, cf0 = dt * (1.0 - th);
  // Forward: r = P v + Q u + dt (theta F^{n+1} + (1 - theta) F^n), then y_j = r_j - lower_j y_{j-1}.
  auto r = [&](std::size_t j, double pv, double qu) { return pv + qu + (cf1 * f1[j] + cf0 * f0[j]); };
  double carry = r(0, pd[0] * v[0] + po[0] * v[1], qd[0] * u[0] + qo[0] * u[1]);
  y[0] = carry;
  for (std::size_t j = 1; j < last; ++j) {
    const double rj = r(j, pd[j] * v[j] + po[j - 1] * v[j - 1] + po[j] * v[j + 1],
                        qd[j] * u[j] + qo[j - 1] * u[j - 1] + qo[j] * u[j + 1]);
    carry = rj - lower[j] * carry;
    y[j] = carry;
  }
  const double r_last = clamped_ ? 0.0
                                 : r(last, pd[last] * v[last] + po[last - 1] * v[last - 1],
                                     qd[last] * u[last] + qo[last - 1] * u[last - 1]);
  y[last] = r_last - lower[last] * carry;
  // Backward: v_free, and the update u += dt (theta v_new + (1 - theta) v_old) in the same pass.
  double x = y[last] * inv[last];
  u[last] += dt * (th * x + (1.0 - th) * v[last]);
  v[last] = x;
  for (std::size_t j = last; j-- > 0;) {
    x = y[j] * inv[j] - su[j] * x;
    const double v_old = v[j];
    v[j] = x;
    u[j] += dt * (th * x + (1.0 - th) * v_old);
  }
  // Newton's law when active: 0 <= p _|_ V^{n+1} + e V^n >= 0; then v += p w, u += dt theta p w.
  double p = 0.0;
  if (active) p = std::max(0.0, (-restitution_ * V - v[0]) / response_[0]);
  if (p > 0.0)
    for (std::size_t j = 0; j < n; ++j) {
      v[j] += p * response_[j];
      u[j] += dt * th * p * response_[j];
    }
  reaction_ = p / dt;
  end_step(0.0);
}

}  // namespace barimpact
