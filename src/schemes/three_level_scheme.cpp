#include "barimpact/schemes/three_level_scheme.hpp"

#include <cmath>

namespace barimpact {

ThreeLevelScheme::ThreeLevelScheme(const Case& c, bool consistent_mass)
    : mesh_(c.bar.length, c.bar.elements),
      law_(c.obstacle),
      dt_(c.time.step),
      inv_dt_(1.0 / c.time.step),
      a_(c.bar.stiffness),
      clamped_(c.bar.far_end == FarEnd::clamped),
      mass_(mesh_.mass(c.bar.density)),
      stiffness_a_(mesh_.stiffness(c.bar.stiffness)),
      stiffness_b_(mesh_.stiffness(c.bar.viscosity)) {
  const std::size_t n = mesh_.nodes();
  lumped_.assign(n, 0.0);
  for (std::size_t j = 0; j < n; ++j)
    lumped_[j] = mass_.diag[j] + (j > 0 ? mass_.off[j - 1] : 0.0) + (j + 1 < n ? mass_.off[j] : 0.0);
  kinetic_mass_ = consistent_mass ? mass_ : Tridiagonal{lumped_, std::vector<double>(n - 1, 0.0)};
  lumped_step_ = !consistent_mass;
  kb_positive_ = c.bar.viscosity > 0.0;
  inverse_lumped_.resize(n);
  for (std::size_t j = 0; j < n; ++j) inverse_lumped_[j] = 1.0 / lumped_[j];
  for (auto& l : levels_) l.assign(n, 0.0);
  rhs_.assign(n, 0.0);
  load_.assign(n, 0.0);
  u0_.assign(n, 0.0);
  v0_.assign(n, 0.0);
  body_force_ = std::make_unique<Expression>(c.load.body_force);
  load_zero_ = body_force_->is_zero();
  load_steady_ = !body_force_->depends_on_t();
  initial_displacement_ = std::make_unique<Expression>(c.initial.displacement);
  initial_velocity_ = std::make_unique<Expression>(c.initial.velocity);
}

void ThreeLevelScheme::load_at(long long n) {
  if (load_zero_ || (load_steady_ && n > 0)) return;  // zero, or computed at n = 0
  mesh_.load(*body_force_, static_cast<double>(n) * dt_, load_);
}

void ThreeLevelScheme::start() {
  const std::size_t n = mesh_.nodes();
  mesh_.interpolate(*initial_displacement_, u0_);
  mesh_.interpolate(*initial_velocity_, v0_);
  prev_ = levels_[2].data();
  cur_ = levels_[0].data();
  next_ = levels_[1].data();
  n_ = 0;
  work_half_ = dissipation_half_ = work_last_ = dissipation_last_ = 0.0;
  // u^1 = u^0 + dt v^0 + dt^2/2 a^0, a^0 = M^{-1}(F^0 - K_a u^0 - K_b v^0 + R^0 e0):
  // second order, and exact for a rigid motion.
  load_at(0);
  stiffness_a_.multiply(u0_, rhs_);
  std::vector<double> viscous(n, 0.0);
  stiffness_b_.multiply(v0_, viscous);
  for (std::size_t j = 0; j < n; ++j) rhs_[j] = load_[j] - rhs_[j] - viscous[j];
  rhs_[0] += law_.reaction(u0_[0], v0_[0]);
  if (clamped_) rhs_[n - 1] = 0.0;
  apply_inverse_mass(rhs_);
  for (std::size_t j = 0; j < n; ++j) {
    cur_[j] = prev_[j] = u0_[j];
    next_[j] = u0_[j] + dt_ * v0_[j] + 0.5 * dt_ * dt_ * rhs_[j];
  }
  if (clamped_) next_[n - 1] = 0.0;
  book_first_half_step(viscous);
  // A rigid obstacle holds from the first step. The start is a Taylor step,
  // dt^2/2 a^0, so the force behind a correction is twice that of a full step.
  const double impulse = 2.0 * enforce_contact(prev_, cur_, next_);
  reaction_ = law_.reaction(u0_[0], v0_[0]) + impulse;
  // D_contact: the rigid obstacle's work over the first half step, its force
  // against the mean of the end's velocity at t = 0 and over (0, dt): the
  // Taylor step's own identity, (1/2) m (w^2 - v0^2) = F (dt/2) (v0 + w) / 2.
  // A scheme whose force is the obstacle's exact reaction (characteristic),
  // not an impulse, books it against the rate at t = 0, as the load's power.
  contact_half_ = impulsive_contact() ? -0.25 * dt_ * impulse * (v0_[0] + (next_[0] - cur_[0]) / dt_)
                                      : -0.5 * dt_ * impulse * v0_[0];
  contact_last_ = 0.0;
}

// The row at t_n sums level m's increments, each centred on t_m, from m = 1:
// the budget would start at t_{1/2}. The first half step's share, dt/2 times
// the rates at t = 0, is booked here: the load's power F^0 . v^0, the bar's
// dissipation v^0 . K_b v^0 and the viscoelastic obstacle's (R - k d) dd/dt.
void ThreeLevelScheme::book_first_half_step(std::span<const double> viscous) {
  double power = 0.0, dissipation = 0.0;
  for (std::size_t j = 0; j < v0_.size(); ++j) {
    power += load_[j] * v0_[j];
    dissipation += viscous[j] * v0_[j];
  }
  if (law_.viscosity() > 0.0)
    dissipation -= (law_.reaction(u0_[0], v0_[0]) - law_.stiffness() * law_.penetration(u0_[0])) * v0_[0];
  work_half_ = 0.5 * dt_ * power;
  dissipation_half_ = 0.5 * dt_ * dissipation;
}

double ThreeLevelScheme::clamp_end(double* next) const {
  const double face = -law_.gap();
  if (law_.kind() != ObstacleKind::rigid || next[0] >= face) return 0.0;
  const double force = lumped_[0] * (face - next[0]) / (dt_ * dt_);
  next[0] = face;
  return force;
}

namespace {
// F_j - (K_a u)_j - (K_b (u - u_old))_j / dt on an interior row, with the
// uniform mesh's constant stencils.
struct InteriorRow {
  double kd, ko, bd, bo, inv_dt;
  template <bool viscous, bool loaded>
  [[nodiscard]] double force(const double* __restrict f, const double* __restrict um, const double* __restrict u,
                             std::size_t j) const {
    double rj = -(kd * u[j] + ko * (u[j - 1] + u[j + 1]));
    if constexpr (loaded) rj = f[j] + rj;
    if constexpr (viscous)
      rj -= (bd * (u[j] - um[j]) + bo * ((u[j - 1] - um[j - 1]) + (u[j + 1] - um[j + 1]))) * inv_dt;
    return rj;
  }
};
}  // namespace

// u^{m+1} = 2 u^m - u^{m-1} + dt^2 M^{-1} r, r = F^m - K_a u^m - K_b (u^m - u^{m-1})/dt
// (+ the penalty at node 0). Interior rows without branches; with lumped mass
// the update is fused into the same pass (vectorised over nodes), with
// consistent mass into the sweeps of M_h's factors. Returns the obstacle's
// impulse force.
template <bool viscous, bool loaded>
double ThreeLevelScheme::step_rows(const double* __restrict um, const double* __restrict u, double* __restrict up,
                                   double penalty) {
  const std::size_t n = mesh_.nodes(), last = n - 1;
  const Tridiagonal &ka = stiffness_a_, &kb = stiffness_b_;
  const double* __restrict f = load_.data();
  const double inv_dt = inv_dt_, dt2 = dt_ * dt_;
  const InteriorRow row{ka.diag[1], ka.off[0], kb.diag[1], kb.off[0], inv_dt};
  // Boundary rows.
  double d0 = 0.0, dl = 0.0;
  if constexpr (viscous) {
    d0 = (kb.diag[0] * (u[0] - um[0]) + kb.off[0] * (u[1] - um[1])) * inv_dt;
    dl = (kb.diag[last] * (u[last] - um[last]) + kb.off[last - 1] * (u[last - 1] - um[last - 1])) * inv_dt;
  }
  const double f0 = loaded ? f[0] : 0.0, fl = loaded ? f[last] : 0.0;
  const double r0 = f0 - (ka.diag[0] * u[0] + ka.off[0] * u[1]) - d0 + penalty;
  const double rl = clamped_ ? 0.0 : fl - (ka.diag[last] * u[last] + ka.off[last - 1] * u[last - 1]) - dl;
  if (lumped_step_) {
    const double* __restrict inv_m = inverse_lumped_.data();
    const double inv_mi = inv_m[1];
    // The ends first, and the obstacle on node 0 before the interior pass:
    // node 0 then leaves the pass's critical path from step to step.
    up[0] = 2.0 * u[0] - um[0] + dt2 * (r0 * inv_m[0]);
    up[last] = 2.0 * u[last] - um[last] + dt2 * (rl * inv_m[last]);
    double impulse_force = 0.0;
    if (lumped_end_ == LumpedEnd::clamp)
      impulse_force = clamp_end(up);
    else if (lumped_end_ == LumpedEnd::scheme)
      impulse_force = enforce_contact(um, u, up);
    for (std::size_t j = 1; j < last; ++j)
      up[j] = 2.0 * u[j] - um[j] + dt2 * (row.force<viscous, loaded>(f, um, u, j) * inv_mi);
    return impulse_force;
  }
  // Consistent mass: the right-hand side formed inside the sweep of M_h's
  // factors towards x = 0; the obstacle's impulse decided at node 0; the
  // update inside the sweep back.
  const FactoredTridiagonal& factor = *mass_factor();
  const double* __restrict inv = factor.inverse_pivots();
  const double* __restrict cp = factor.coupling();
  double y = rl;
  up[last] = y;
  for (std::size_t j = last - 1; j > 0; --j) {
    y = row.force<viscous, loaded>(f, um, u, j) - cp[j + 1] * y;
    up[j] = y;
  }
  const double y0 = r0 - cp[1] * y;
  // next += mu M^{-1} e_0 is r_0 += mu / dt^2.
  const double free0 = 2.0 * u[0] - um[0] + dt2 * (y0 * inv[0]);
  const double mu = end_impulse(um[0], free0);
  double x = (y0 + mu / dt2) * inv[0];
  // Node 0 as the projection puts it (w_0 = inv_0), on the constraint to the
  // last bit rather than through the sweep's roundings.
  up[0] = mu == 0.0 ? 2.0 * u[0] - um[0] + dt2 * x : free0 + mu * inv[0];
  for (std::size_t j = 1; j < n; ++j) {
    x = up[j] * inv[j] - cp[j] * x;
    up[j] = 2.0 * u[j] - um[j] + dt2 * x;
  }
  return mu / dt2;
}

void ThreeLevelScheme::advance() {
  const long long m = n_ + 1;  // the equation at level m gives u^{m+1}
  const double* um = cur_;     // u^{m-1}
  const double* u = next_;     // u^m
  double* up = prev_;          // becomes u^{m+1}
  if (!load_zero_ && !load_steady_) load_at(m);
  // The penalty force at t_m, its rate by a backward difference (explicit).
  // (A multiply by 1/dt, not a division: u_0 carries a chain from step to step.)
  const double penalty = law_.reaction(u[0], (u[0] - um[0]) * inv_dt_);
  const bool viscous = kb_positive_;
  double impulse_force = 0.0;
  if (viscous)
    impulse_force = load_zero_ ? step_rows<true, false>(um, u, up, penalty) : step_rows<true, true>(um, u, up, penalty);
  else
    impulse_force =
        load_zero_ ? step_rows<false, false>(um, u, up, penalty) : step_rows<false, true>(um, u, up, penalty);
  prev_ = cur_;
  cur_ = next_;
  next_ = up;
  n_ = m;
  reaction_ = penalty + impulse_force;
  contact_last_ = impulse_force * 0.5 * (prev_[0] - next_[0]);  // the impulse against (d^{m+1} - d^{m-1}) / 2
  contact_half_ += contact_last_;

  // Budget of level m: dW = F^m . (u^{m+1} - u^{m-1}) / 2, dD = viscous force . same.
  double dw = 0.0, dd = 0.0;
  if (!load_zero_ || viscous) bar_budget(dw, dd);
  // The viscoelastic obstacle's force beyond its spring's, R - k d, tested
  // like the rest: the dashpot's l dd/dt while pushing, and -k d while the
  // law clips (R = 0), the spring's energy k d^2 / 2 released.
  if (law_.viscosity() > 0.0)
    dd += (penalty - law_.stiffness() * law_.penetration(cur_[0])) * 0.5 * (prev_[0] - next_[0]);
  work_last_ = dw;
  dissipation_last_ = dd;
  work_half_ += dw;
  dissipation_half_ += dd;
}

void ThreeLevelScheme::bar_budget(double& dw, double& dd) const {
  const std::size_t n = mesh_.nodes();
  const auto& kb = stiffness_b_;
  const double inv_dt = inv_dt_;
  if (!load_zero_)
    for (std::size_t j = 0; j < n; ++j) dw += load_[j] * 0.5 * (next_[j] - prev_[j]);
  if (kb_positive_) {
    for (std::size_t j = 0; j < n; ++j) {
      double d = kb.diag[j] * (cur_[j] - prev_[j]);
      if (j > 0) d += kb.off[j - 1] * (cur_[j - 1] - prev_[j - 1]);
      if (j + 1 < n) d += kb.off[j] * (cur_[j + 1] - prev_[j + 1]);
      dd += d * inv_dt * 0.5 * (next_[j] - prev_[j]);
    }
  }
}

double ThreeLevelScheme::end_velocity() const {
  if (n_ == 0) return v0_[0];
  return (next_[0] - prev_[0]) / (2.0 * dt_);
}

void ThreeLevelScheme::displacement(std::span<double> out) const {
  for (std::size_t j = 0; j < out.size(); ++j) out[j] = cur_[j];
}

void ThreeLevelScheme::velocity(std::span<double> out) const {
  for (std::size_t j = 0; j < out.size(); ++j) out[j] = n_ == 0 ? v0_[j] : (next_[j] - prev_[j]) / (2.0 * dt_);
}

void ThreeLevelScheme::half_step_energy(const double* a, const double* b, double& kinetic, double& strain) const {
  const std::size_t n = mesh_.nodes();
  double wm = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    const double w = (b[j] - a[j]) / dt_;
    double mw = kinetic_mass_.diag[j] * w;
    if (j > 0) mw += kinetic_mass_.off[j - 1] * (b[j - 1] - a[j - 1]) / dt_;
    if (j + 1 < n) mw += kinetic_mass_.off[j] * (b[j + 1] - a[j + 1]) / dt_;
    wm += w * mw;
  }
  kinetic = 0.5 * wm;
  strain = 0.5 * mesh_.stiffness_form(a_, {a, n}, {b, n});
}

Energies ThreeLevelScheme::energies() const {
  Energies e;
  e.obstacle = law_.energy(cur_[0]);
  if (n_ == 0) {
    e.kinetic = 0.5 * kinetic_mass_.quadratic_form(v0_);
    e.strain = 0.5 * mesh_.stiffness_form(a_, u0_, u0_);
    return e;
  }
  double k1 = 0, s1 = 0, k2 = 0, s2 = 0;
  half_step_energy(prev_, cur_, k1, s1);
  half_step_energy(cur_, next_, k2, s2);
  e.kinetic = 0.5 * (k1 + k2);
  e.strain = 0.5 * (s1 + s2);
  e.work = work_half_ - 0.5 * work_last_;
  e.dissipation = dissipation_half_ - 0.5 * dissipation_last_;
  e.contact = contact_half_ - 0.5 * contact_last_;
  return e;
}

bool ThreeLevelScheme::finite() const {
  const std::size_t last = mesh_.nodes() - 1;
  return std::isfinite(cur_[0]) && std::isfinite(cur_[last]) && std::isfinite(next_[0]) && std::isfinite(next_[last]) &&
         std::isfinite(work_half_) && std::isfinite(dissipation_half_);
}

}  // namespace barimpact
