#include "barimpact/schemes/line_newmark.hpp"

#include <algorithm>
#include <cmath>

namespace barimpact {

namespace {

// A general tridiagonal LU (Thomas), the held rows made identity: lower
// entries, reciprocal pivots and the eliminated upper entries.
void factor(const Tridiagonal& a, const std::vector<char>& held, std::vector<double>& lower,
            std::vector<double>& inv_pivot, std::vector<double>& upper) {
  const std::size_t n = a.size();
  lower.assign(n, 0.0);
  inv_pivot.assign(n, 0.0);
  upper.assign(n, 0.0);
  for (std::size_t j = 0; j < n; ++j) {
    const double l = (j > 0 && !held[j]) ? a.off[j - 1] : 0.0;
    const double d = held[j] ? 1.0 : a.diag[j];
    const double u = (j + 1 < n && !held[j]) ? a.off[j] : 0.0;
    const double pivot = d - (j > 0 ? l * upper[j - 1] : 0.0);
    lower[j] = j > 0 ? l * inv_pivot[j - 1] : 0.0;  // the multiplier: one fma on the forward chain
    inv_pivot[j] = 1.0 / pivot;
    upper[j] = u * inv_pivot[j];
  }
}

void substitute(const std::vector<double>& lower, const std::vector<double>& inv_pivot,
                const std::vector<double>& upper, std::vector<double>& x) {
  const std::size_t n = x.size();
  for (std::size_t j = 1; j < n; ++j) x[j] -= lower[j] * x[j - 1];
  x[n - 1] *= inv_pivot[n - 1];
  for (std::size_t j = n - 1; j-- > 0;) x[j] = x[j] * inv_pivot[j] - upper[j] * x[j + 1];
}

}  // namespace

LineNewmark::LineNewmark(const Case& c, Line line)
    : LineScheme(c, std::move(line)), beta_(c.time.beta), gamma_(c.time.gamma) {
  const std::size_t n = line_.nodes(), links = line_.links.size();
  mass_ = line_.mass(true);
  stiff_ = line_.stiffness();
  visc_ = line_.viscosity();
  const Tridiagonal a =
      Tridiagonal::combine(1.0, Tridiagonal::combine(1.0, mass_, gamma_ * dt_, visc_), beta_ * dt_ * dt_, stiff_);
  std::vector<char> held(n, 0);
  for (std::size_t j = 0; j < n; ++j)
    if (line_.fixed(j)) {
      held[j] = 1;
      held_.push_back(j);
    }
  factor(a, held, lower_, inv_pivot_, upper_);
  // The penalty links' responses to a unit force (none on held rows) and their Delassus matrix.
  response_.assign(links, std::vector<double>(n, 0.0));
  for (std::size_t i = 0; i < links; ++i) {
    const Link& l = line_.links[i];
    if (l.a != Link::ground && !held[l.a]) response_[i][l.a] = -1.0;
    if (l.b != Link::ground && !held[l.b]) response_[i][l.b] = 1.0;
    substitute(lower_, inv_pivot_, upper_, response_[i]);
  }
  std::vector<double> delassus(links * links, 0.0);
  std::vector<ContactLaw> laws;
  for (std::size_t i = 0; i < links; ++i) {
    laws.push_back(line_.links[i].law);
    for (std::size_t j = 0; j < links; ++j)
      delassus[i * links + j] = line_.opening(i, response_[j].data()) - line_.links[i].gap;
  }
  penalty_ = PenaltyLinks(std::move(laws), std::move(delassus), beta_ * dt_ * dt_, gamma_ * dt_);
  for (auto* x : {&u_, &v_, &acc_, &rhs_, &work_, &load_old_}) x->assign(n, 0.0);
  p_old_.assign(links, 0.0);
  c_old_.assign(links, 0.0);
  c_free_.assign(links, 0.0);
  rate_free_.assign(links, 0.0);
  active_.reserve(links);
  for (const auto& b : line_.bonds) {
    stiff_bond_.push_back(b.stiffness);
    visc_bond_.push_back(b.viscosity);
    viscous_ = viscous_ || b.viscosity != 0.0;
  }
}

void LineNewmark::residual(const std::vector<double>& u, const std::vector<double>& v, double t,
                           std::vector<double>& r) {
  const std::size_t n = line_.nodes();
  stiff_.multiply(u, r);
  visc_.multiply(v, work_);
  for (std::size_t j = 0; j < n; ++j) r[j] = (load_zero_ ? 0.0 : load_[j]) - r[j] - work_[j];
  if (line_.near.kind == EndKind::force) r[line_.near.node] += near_value(t);
  if (line_.far.kind == EndKind::force) r[line_.far.node] += far_value(t);
}

void LineNewmark::hold_ends(double t) {
  for (const End* e : {&line_.near, &line_.far}) {
    if (e->kind == EndKind::clamped) rhs_[e->node] = 0.0;
    if (e->kind == EndKind::velocity) {  // v^{n+1} = v(t): a^{n+1} from v^{n+1} = v^* + gamma dt a^{n+1}
      const double target = e == &line_.near ? near_value(t) : far_value(t);
      rhs_[e->node] = (target - v_[e->node]) / (gamma_ * dt_);
    }
  }
}

// The support's force along +x on a held node at the current state: what
// its equation of motion needs beyond the line's own forces.
double LineNewmark::support(std::size_t j, double t) const {
  const std::size_t n = line_.nodes();
  auto row = [&](const Tridiagonal& m, const std::vector<double>& x) {
    double s = m.diag[j] * x[j];
    if (j > 0) s += m.off[j - 1] * x[j - 1];
    if (j + 1 < n) s += m.off[j] * x[j + 1];
    return s;
  };
  double s = row(mass_, acc_) + row(visc_, v_) + row(stiff_, u_) - (load_zero_ ? 0.0 : load_[j]);
  for (std::size_t i = 0; i < line_.links.size(); ++i) {
    if (line_.links[i].a == j) s += force_[i];
    if (line_.links[i].b == j) s -= force_[i];
  }
  (void)t;
  return s;
}

void LineNewmark::start() {
  const std::size_t n = line_.nodes();
  n_ = 0;
  u_ = u0_;
  v_ = v0_;
  std::fill(c_max_.begin(), c_max_.end(), 0.0);
  // a^0 = M^{-1} (F^0 - K u^0 - C v^0 + links), held rows at their ends' accelerations.
  load_at(0.0);
  residual(u_, v_, 0.0, acc_);
  for (std::size_t i = 0; i < line_.links.size(); ++i) {
    const ContactLaw& law = line_.links[i].law;
    const double c = -line_.opening(i, u_.data());
    c_max_[i] = std::max(0.0, c);
    force_[i] = law.rigid() ? 0.0 : law.force(c, -(line_.opening(i, v_.data()) - line_.links[i].gap), c_max_[i]);
    add_link_force(i, force_[i], acc_.data());
  }
  std::vector<char> held(n, 0);
  for (std::size_t j : held_) held[j] = 1;
  std::vector<double> lower, inv_pivot, upper;
  factor(mass_, held, lower, inv_pivot, upper);
  for (const End* e : {&line_.near, &line_.far}) {
    if (e->kind == EndKind::clamped) acc_[e->node] = 0.0;
    if (e->kind == EndKind::velocity)  // the history's slope over the first step
      acc_[e->node] = ((e == &line_.near ? near_value(dt_) : far_value(dt_)) - v_[e->node]) / dt_;
  }
  substitute(lower, inv_pivot, upper, acc_);
  load_old_ = load_;
  for (std::size_t i = 0; i < force_.size(); ++i) {
    p_old_[i] = force_[i];
    c_old_[i] = -line_.opening(i, u_.data());
  }
  support_old_[0] = support(line_.near.node, 0.0);
  support_old_[1] = support(line_.far.node, 0.0);
  near_force_ = !line_.links.empty() && line_.links.front().name == "near_end" ? force_.front()
                : line_.near.kind == EndKind::force                            ? near_value(0.0)
                : line_.fixed(line_.near.node)                                 ? support_old_[0]
                                                                               : 0.0;
  far_force_ = !line_.links.empty() && line_.links.back().name == "far_end" ? force_.back()
               : line_.far.kind == EndKind::force                           ? -far_value(0.0)
               : line_.fixed(line_.far.node)                                ? -support_old_[1]
                                                                            : 0.0;
  ext_work_ = dissipation_ = 0.0;
}

// The links' compressions and rates with the free acceleration (every
// force 0), then their forces at t_{n+1} by the active-set iteration.
void LineNewmark::solve_links() {
  if (!has_penalty_) return;
  const std::size_t links = line_.links.size();
  const double bdt2 = beta_ * dt_ * dt_, gdt = gamma_ * dt_;
  for (std::size_t i = 0; i < links; ++i) {
    const double free = line_.opening(i, rhs_.data()) - line_.links[i].gap;  // h_i . a_free
    c_free_[i] = -(line_.opening(i, u_.data()) + bdt2 * free);
    rate_free_[i] = -(line_.opening(i, v_.data()) - line_.links[i].gap + gdt * free);
  }
  penalty_.solve(c_free_.data(), rate_free_.data(), c_max_.data(), force_.data());
}

// One step in three passes: predictors, right-hand side and the forward
// elimination together; the back substitution (the free a^{n+1}); then, the
// links' forces found from it, a, u, v and the budget's sums together, the
// levels at t_n recovered from the predictors instead of copied.
void LineNewmark::advance() {
  const double t = static_cast<double>(n_ + 1) * dt_;
  load_at(t);
  forward(t);
  const std::size_t n = line_.nodes();
  // Back substitution: the free a^{n+1}.
  double* __restrict x = rhs_.data();
  const double* __restrict inv = inv_pivot_.data();
  const double* __restrict up = upper_.data();
  x[n - 1] *= inv[n - 1];
  for (std::size_t j = n - 1; j-- > 0;) x[j] = x[j] * inv[j] - up[j] * x[j + 1];
  solve_links();
  update(t);
  ++n_;
  book_links(t);
}

// u^*, v^* in place; r = F + end forces - K u^* - C v^* (held rows: their
// prescribed a); the forward elimination y_j = (r_j - l_j y_{j-1}) / pivot_j
// in the same pass.
void LineNewmark::forward(double t) {
  const std::size_t n = line_.nodes();
  const double dt = dt_, c1 = (0.5 - beta_) * dt * dt, c2 = (1.0 - gamma_) * dt;
  double* __restrict u = u_.data();
  double* __restrict v = v_.data();
  const double* __restrict a = acc_.data();
  double* __restrict y = rhs_.data();
  const double* __restrict k = stiff_bond_.data();
  const double* __restrict c = visc_bond_.data();
  const double* __restrict l = lower_.data();
  const double* __restrict f = load_.data();
  const std::size_t near = line_.near.node, far = line_.far.node;
  const double near_force = line_.near.kind == EndKind::force ? near_value(t) : 0.0;
  const double far_force = line_.far.kind == EndKind::force ? far_value(t) : 0.0;
  u[0] += dt * v[0] + c1 * a[0];
  v[0] += c2 * a[0];
  double tension_below = 0.0, carry = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    double r = (load_zero_ ? 0.0 : f[j]) - tension_below;
    if (j + 1 < n) {
      u[j + 1] += dt * v[j + 1] + c1 * a[j + 1];
      v[j + 1] += c2 * a[j + 1];
      tension_below = k[j] * (u[j + 1] - u[j]) + c[j] * (v[j + 1] - v[j]);
      r += tension_below;
    }
    if (j == near || j == far) r = end_row(j, r + (j == near ? near_force : 0.0) + (j == far ? far_force : 0.0), t);
    carry = r - l[j] * carry;
    y[j] = carry;
  }
}

// An end node's row: its right-hand side, or a held end's prescribed
// acceleration (clamped: 0; driven: v^{n+1} = v(t) = v^* + gamma dt a^{n+1}).
double LineNewmark::end_row(std::size_t j, double r, double t) const {
  for (const End* e : {&line_.near, &line_.far}) {
    if (e->node != j) continue;
    if (e->kind == EndKind::clamped) return 0.0;
    if (e->kind == EndKind::velocity)
      return ((e == &line_.near ? near_value(t) : far_value(t)) - v_[j]) / (gamma_ * dt_);
  }
  return r;
}

// a^{n+1} = a_free + sum p_i w_i; u, v from the predictors; the step's
// external work (load) and viscous dissipation from the levels at t_n,
// recovered: v^n = v^* - (1 - gamma) dt a^n, u^{n+1} - u^n = dt v^n + (1/2 - beta) dt^2 a^n + beta dt^2 a^{n+1}.
void LineNewmark::update(double t) {
  (void)t;
  const std::size_t n = line_.nodes(), links = line_.links.size();
  const double dt = dt_, bdt2 = beta_ * dt * dt, gdt = gamma_ * dt;
  const double c1 = (0.5 - beta_) * dt * dt, c2 = (1.0 - gamma_) * dt;
  active_.clear();
  for (std::size_t i = 0; i < links; ++i)
    if (force_[i] != 0.0) active_.push_back(i);  // reserved for every link: no allocation
  double* __restrict u = u_.data();
  double* __restrict v = v_.data();
  double* __restrict a = acc_.data();
  const double* __restrict x = rhs_.data();
  const double* __restrict c = visc_bond_.data();
  // At most two links push on most steps: their responses by raw pointers.
  const double* w0 = active_.size() > 0 ? response_[active_[0]].data() : nullptr;
  const double* w1 = active_.size() > 1 ? response_[active_[1]].data() : nullptr;
  const double p0 = w0 ? force_[active_[0]] : 0.0, p1 = w1 ? force_[active_[1]] : 0.0;
  auto accel = [&](std::size_t j) {
    double anew = x[j];
    if (w0) anew += p0 * w0[j];
    if (w1) anew += p1 * w1[j];
    for (std::size_t m = 2; m < active_.size(); ++m) anew += force_[active_[m]] * response_[active_[m]][j];
    return anew;
  };
  for (int e = 0; e < 2; ++e) {  // the ends' u^{n+1} - u^n, for their forces' work
    const std::size_t j = e == 0 ? line_.near.node : line_.far.node;
    du_end_[e] = dt * (v[j] - c2 * a[j]) + c1 * a[j] + bdt2 * accel(j);
  }
  const bool loaded = !load_zero_;
  double dw = 0.0, dd = 0.0, vbar_below = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    const double anew = accel(j);
    const double vold = v[j] - c2 * a[j];
    const double du = dt * vold + c1 * a[j] + bdt2 * anew;
    u[j] += bdt2 * anew;
    v[j] += gdt * anew;
    a[j] = anew;
    if (loaded) dw += du * 0.5 * (load_old_[j] + load_[j]);
    if (viscous_) {
      const double vbar = 0.5 * (v[j] + vold);
      if (j > 0) dd += dt * c[j - 1] * (vbar - vbar_below) * (vbar - vbar_below);
      vbar_below = vbar;
    }
  }
  step_work_ = dw;
  step_dissipation_ = dd;
}

// The links' c_max, the ends' forces and supports, and the budget's end and link terms.
void LineNewmark::book_links(double t) {
  double dw = step_work_, dd = step_dissipation_;
  const double s_near = support(line_.near.node, t), s_far = support(line_.far.node, t);
  if (line_.fixed(line_.near.node)) dw += 0.5 * (support_old_[0] + s_near) * du_end_[0];
  if (line_.fixed(line_.far.node)) dw += 0.5 * (support_old_[1] + s_far) * du_end_[1];
  if (line_.near.kind == EndKind::force) dw += 0.5 * (near_value(t - dt_) + near_value(t)) * du_end_[0];
  if (line_.far.kind == EndKind::force) dw += 0.5 * (far_value(t - dt_) + far_value(t)) * du_end_[1];
  for (std::size_t i = 0; i < line_.links.size(); ++i) {
    const ContactLaw& law = line_.links[i].law;
    const double c = -line_.opening(i, u_.data());
    c_max_[i] = std::max(c_max_[i], c);
    if (law.kind == LawKind::viscoelastic)  // the force beyond the spring's, trapezoidal (as the single bar's)
      dd += 0.5 *
            ((p_old_[i] - law.stiffness * std::max(0.0, c_old_[i])) + (force_[i] - law.stiffness * std::max(0.0, c))) *
            (c - c_old_[i]);
    p_old_[i] = force_[i];
    c_old_[i] = c;
  }
  ext_work_ += dw;
  dissipation_ += dd;
  if (!load_zero_ && !load_steady_) load_old_ = load_;
  support_old_[0] = s_near;
  support_old_[1] = s_far;
  const bool near_link = !line_.links.empty() && line_.links.front().name == "near_end";
  const bool far_link = !line_.links.empty() && line_.links.back().name == "far_end";
  near_force_ = near_link                           ? force_.front()
                : line_.near.kind == EndKind::force ? near_value(t)
                : line_.fixed(line_.near.node)      ? s_near
                                                    : 0.0;
  far_force_ = far_link                           ? force_.back()
               : line_.far.kind == EndKind::force ? -far_value(t)
               : line_.fixed(line_.far.node)      ? -s_far
                                                  : 0.0;
}

Energies LineNewmark::energies() const {
  Energies e;
  e.kinetic = 0.5 * mass_.quadratic_form(v_);
  e.strain = 0.5 * line_.bond_form(BondKind::element, false, u_.data(), u_.data());
  e.obstacle = 0.5 * line_.bond_form(BondKind::spring, false, u_.data(), u_.data()) + link_energy(u_.data());
  e.work = ext_work_;
  e.dissipation = dissipation_;
  e.contact = link_hysteresis();
  return e;
}

bool LineNewmark::finite() const {
  const std::size_t last = line_.nodes() - 1;
  return std::isfinite(u_[0]) && std::isfinite(u_[last]) && std::isfinite(v_[0]) && std::isfinite(v_[last]) &&
         std::isfinite(ext_work_) && std::isfinite(dissipation_);
}

}  // namespace barimpact
