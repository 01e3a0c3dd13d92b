#include "barimpact/schemes/newmark_scheme.hpp"

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
  const bool loaded = !load_zero_, viscous = stiffness_b_.diag[0] > 0.0;
  if (loaded)
    viscous ? step<true, true>() : step<true, false>();
  else
    viscous ? step<false, true>() : step<false, false>();
}

// One pass towards x = 0 forms r = F^{n+1} - K_a u_pred - K_b v_pred (the
// predictors computed on the fly) inside the first sweep of A; R^{n+1} is
// then a scalar problem at node 0; one pass back finishes the solve with
// R e_0 in the right-hand side and updates a, u, v. Interior rows use the
// uniform mesh's constant stencils.
template <bool loaded, bool viscous>
void NewmarkScheme::step() {
  const double u0_old = u_[0];
  begin_step(budget_needs_old());
  const std::size_t n = mesh_.nodes(), last = n - 1;
  const double dt = dt_, bdt2 = beta_ * dt * dt, gdt = gamma_ * dt;
  const double c1 = (0.5 - beta_) * dt * dt, c2 = (1.0 - gamma_) * dt;
  double* __restrict u = u_.data();
  double* __restrict v = v_.data();
  double* __restrict acc = acc_.data();
  double* __restrict y = rhs_.data();
  const double* __restrict f = load_next_.data();
  const double* __restrict inv = factor_.inverse_pivots();
  const double* __restrict cp = factor_.coupling();
  const Tridiagonal &ka = stiffness_a_, &kb = stiffness_b_;
  const double kd = ka.diag[1], ko = ka.off[0], bd = kb.diag[1], bo = kb.off[0];
  auto u_pred = [&](std::size_t j) { return u[j] + dt * v[j] + c1 * acc[j]; };
  auto v_pred = [&](std::size_t j) { return v[j] + c2 * acc[j]; };
  auto force = [&](std::size_t j) {
    if constexpr (loaded) return f[j];
    (void)j;
    return 0.0;
  };
  // Towards x = 0, the predictors of nodes j - 1, j, j + 1 in registers.
  double up_r = u_pred(last), up_c = u_pred(last - 1), vp_r = 0.0, vp_c = 0.0;
  if constexpr (viscous) vp_r = v_pred(last), vp_c = v_pred(last - 1);
  double r = force(last) - (ka.diag[last] * up_r + ka.off[last - 1] * up_c);
  if constexpr (viscous) r -= kb.diag[last] * vp_r + kb.off[last - 1] * vp_c;
  double carry = clamped_ ? 0.0 : r;
  y[last] = carry;
  for (std::size_t j = last - 1; j > 0; --j) {
    const double up_l = u_pred(j - 1);
    double rj = force(j) - (kd * up_c + ko * (up_l + up_r));
    if constexpr (viscous) {
      const double vp_l = v_pred(j - 1);
      rj -= bd * vp_c + bo * (vp_l + vp_r);
      vp_r = vp_c;
      vp_c = vp_l;
    }
    up_r = up_c;
    up_c = up_l;
    carry = rj - cp[j + 1] * carry;
    y[j] = carry;
  }
  double r0 = force(0) - (ka.diag[0] * up_c + ka.off[0] * up_r);
  if constexpr (viscous) r0 -= kb.diag[0] * vp_c + kb.off[0] * vp_r;
  const double y0 = r0 - cp[1] * carry;

  // R from d(R) = d_lin - beta dt^2 w0 R, dd/dt(R) = rate_lin - gamma dt w0 R,
  // where w0 = inv_0 is the answer of node 0 to a unit force there.
  const double w0 = inv[0], k = law_.stiffness(), l = law_.viscosity();
  const double a_lin = y0 * inv[0];
  const double d_lin = -(up_c + bdt2 * a_lin + law_.gap());
  const double rate_lin = -(v_pred(0) + gdt * a_lin);
  double R = 0.0;
  if (law_.kind() != ObstacleKind::none && d_lin > 0.0) {
    const double s = k * d_lin + l * rate_lin;
    if (s > 0.0) {
      R = s / (1.0 + (k * bdt2 + l * gdt) * w0);
      if (bdt2 > 0.0 && d_lin - bdt2 * w0 * R <= 0.0) R = d_lin / (bdt2 * w0);  // stops at the face
    }
  }
  // Away from x = 0: the solve with R e_0, and a, u, v in the same pass.
  double x = (y0 + R) * inv[0];
  auto update = [&](std::size_t j) {
    const double uj = u_pred(j), vj = v_pred(j);  // recomputed, not stored: one stream less
    acc[j] = x;
    u[j] = uj + bdt2 * x;
    v[j] = vj + gdt * x;
  };
  update(0);
  for (std::size_t j = 1; j < n; ++j) {
    x = y[j] * inv[j] - cp[j] * x;
    update(j);
  }
  const double dissipated = l > 0.0 ? obstacle_dissipation(u0_old, R) : 0.0;
  reaction_ = R;
  end_step(dissipated);
}

// The trapezoidal work of the obstacle's force beyond its spring's,
// (1/2) sum over the step's ends of (R - k d) (u_0^n - u_0^{n+1}): the
// dashpot's l dd/dt while pushing, and -k d while the law clips (R = 0), i.e.
// the spring's energy k d^2 / 2 as it is released. With E_obstacle = k d^2 / 2
// the budget then closes but for the spring's trapezoidal error across the face.
double NewmarkScheme::obstacle_dissipation(double u0_old, double R) const {
  const double k = law_.stiffness();
  const double beyond_spring = (reaction_ - k * law_.penetration(u0_old)) + (R - k * law_.penetration(u_[0]));
  return 0.5 * beyond_spring * (u0_old - u_[0]);
}

}  // namespace barimpact
