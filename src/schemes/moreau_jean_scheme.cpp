#include "barimpact/schemes/moreau_jean_scheme.hpp"

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
  rhs_.assign(n, 0.0);
  P_ = Tridiagonal::combine(1.0, Tridiagonal::combine(1.0, mass_, -dt_ * dt_ * theta_ * (1.0 - theta_), stiffness_a_),
                            -dt_ * (1.0 - theta_), stiffness_b_);
  Q_ = Tridiagonal::combine(-dt_, stiffness_a_, 0.0, stiffness_a_);
}

void MoreauJeanScheme::advance() {
  if (load_zero_)
    step<false>();
  else
    step<true>();
}

// One pass towards x = 0 forms r = P v + Q u + dt (theta F^{n+1} + (1 - theta) F^n)
// inside the first sweep of W; the impulse p is then a scalar problem at node
// 0; one pass back finishes the solve with p e_0 in the right-hand side and
// updates v and u. Interior rows use the uniform mesh's constant stencils.
template <bool loaded>
void MoreauJeanScheme::step() {
  // Contact predicted active at t_n: U^n + g + (dt/2) V^n <= 0 (read before the step).
  const double U = u_[0], V = v_[0], dt = dt_, th = theta_;
  const bool active = law_.kind() == ObstacleKind::rigid && U + law_.gap() + 0.5 * dt * V <= 0.0;
  begin_step(budget_needs_old());
  const std::size_t n = mesh_.nodes(), last = n - 1;
  const double* __restrict f0 = load_.data();
  const double* __restrict f1 = load_next_.data();
  const double* __restrict inv = factor_.inverse_pivots();
  const double* __restrict cp = factor_.coupling();
  double* __restrict u = u_.data();
  double* __restrict v = v_.data();
  double* __restrict y = rhs_.data();
  const double pd = P_.diag[1], po = P_.off[0], qd = Q_.diag[1], qo = Q_.off[0];
  const double cf1 = dt * th, cf0 = dt * (1.0 - th);
  auto force = [&](std::size_t j) {
    if constexpr (loaded) return cf1 * f1[j] + cf0 * f0[j];
    (void)j;
    return 0.0;
  };
  const double r_last = P_.diag[last] * v[last] + P_.off[last - 1] * v[last - 1] +
                        (Q_.diag[last] * u[last] + Q_.off[last - 1] * u[last - 1]) + force(last);
  double carry = clamped_ ? 0.0 : r_last;
  y[last] = carry;
  for (std::size_t j = last - 1; j > 0; --j) {
    const double rj = pd * v[j] + po * (v[j - 1] + v[j + 1]) + (qd * u[j] + qo * (u[j - 1] + u[j + 1])) + force(j);
    carry = rj - cp[j + 1] * carry;
    y[j] = carry;
  }
  const double r0 = P_.diag[0] * v[0] + P_.off[0] * v[1] + (Q_.diag[0] * u[0] + Q_.off[0] * u[1]) + force(0);
  const double y0 = r0 - cp[1] * carry;
  // Newton's law when active: 0 <= p _|_ V^{n+1} + e V^n >= 0, V^{n+1} = (y0 + p) w0, w0 = inv_0.
  double p = 0.0;
  if (active) p = std::max(0.0, (-restitution_ * V) / inv[0] - y0);
  // Away from x = 0: v^{n+1}, and u += dt (theta v^{n+1} + (1 - theta) v^n) in the same pass.
  double x = (y0 + p) * inv[0];
  // The impulse against the mean velocity of the step: at theta = 1/2 the
  // step's energy identity then closes with it in D_contact.
  contact_ -= p * 0.5 * (x + V);
  auto update = [&](std::size_t j) {
    u[j] += dt * (th * x + (1.0 - th) * v[j]);
    v[j] = x;
  };
  update(0);
  for (std::size_t j = 1; j < n; ++j) {
    x = y[j] * inv[j] - cp[j] * x;
    update(j);
  }
  reaction_ = p / dt;
  end_step(0.0);
}

}  // namespace barimpact
