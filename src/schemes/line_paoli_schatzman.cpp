#include "barimpact/schemes/line_paoli_schatzman.hpp"

#include "barimpact/model/setup_polling.hpp"

#include <algorithm>
#include <cmath>

namespace barimpact {

LinePaoliSchatzman::LinePaoliSchatzman(const Case& c, Line line) : LineScheme(c, std::move(line)), plastic_(line_) {
  const std::size_t n = line_.nodes();
  mass_ = line_.mass(true);
  Tridiagonal m = mass_;
  held_ = hold_rows(line_, m);
  factor_ = FactoredTridiagonal(m, false);
  poll_setup();  // each phase is line-sized: a study's case polls its interrupt between them
  for (const auto& b : line_.bonds) {
    k_.push_back(b.stiffness);
    c_.push_back(b.viscosity);
    viscous_ = viscous_ || b.viscosity > 0.0;
  }
  // Forces besides the bonds' act on penalty links' faces and force ends:
  // those rows are formed by special_row, outside the stretches.
  std::vector<unsigned char> special(n, 0);
  for (const auto& l : line_.links)
    for (std::size_t j : {l.a, l.b})
      if (j != Link::ground && !l.law.rigid()) special[j] = 1;
  for (const End* e : {&line_.near, &line_.far})
    if (e->kind == EndKind::force) special[e->node] = 1;
  for (std::size_t j = 0; j < n; ++j)
    if (special[j]) extra_nodes_.push_back(j);
  poll_setup();
  stretches_ = uniform_stretches(line_, special, held_);
  poll_setup();
  rigid_ = RigidLinks(line_, factor_, 1.0);
  extra_.assign(n, 0.0);
  target_.assign(held_.size(), 0.0);
  q_.assign(rigid_.size(), 0.0);
  mu_.assign(rigid_.size(), 0.0);
  all_.assign(rigid_.size(), 1);
  poll_setup();
  for (auto& l : levels_) l.assign(n, 0.0);
}

double LinePaoliSchatzman::special_row(const double* um, const double* u, std::size_t j) {
  const double inv_dt = 1.0 / dt_;
  const double* p = plastic_.active() ? plastic_.next() : nullptr;  // level n's, read before it moves on
  auto tension = [&](std::size_t b) {
    double t = k_[b] * (u[b + 1] - u[b]);
    if (viscous_) t += c_[b] * ((u[b + 1] - u[b]) - (um[b + 1] - um[b])) * inv_dt;
    if (p != nullptr) t -= line_.bonds[b].axial * p[b];
    return t;
  };
  double r = (load_zero_ ? 0.0 : load_[j]) + extra_[j];
  if (j + 1 < line_.nodes()) r += tension(j);
  if (j > 0) r -= tension(j - 1);
  return held_row(held_, j, r);
}

// The forces inside M's first sweep (the single bar's constant stencils in
// each stretch), u^{n+1} = 2 u^n - u^{n-1} + scale x inside the second; the
// first sweep's values wait in `up`.
template <bool viscous, bool loaded>
void LinePaoliSchatzman::sweeps(const double* um, const double* u, double* up, double scale) {
  const double* f = load_.data();
  const double inv_dt = 1.0 / dt_;
  const double* p = plastic_.active() ? plastic_.next() : nullptr;
  auto stencil = [&](const Stretch& s) {
    const double k = k_[s.first], c = c_[s.first] * inv_dt;
    const Bond& b = line_.bonds[s.first];
    const bool plastic =
        p != nullptr && !plastic_.pristine() && b.body < line_.plasticity.size() && line_.plasticity[b.body];
    const double axial = plastic ? b.axial : 0.0;  // the plastic strains' forces E A (p_{j-1} - p_j)
    return [=](std::size_t j) {
      double r = -k * (2.0 * u[j] - u[j - 1] - u[j + 1]);
      if constexpr (loaded) r += f[j];
      if constexpr (viscous) r -= c * (2.0 * (u[j] - um[j]) - (u[j - 1] - um[j - 1]) - (u[j + 1] - um[j + 1]));
      if (plastic) r += axial * (p[j - 1] - p[j]);
      return r;
    };
  };
  sweep_towards_near(
      factor_, stretches_, stencil, [&](std::size_t j) { return special_row(um, u, j); }, up);
  sweep_away(factor_, up, [&](std::size_t j, double x) { up[j] = 2.0 * u[j] - um[j] + scale * x; });
}

void LinePaoliSchatzman::predict(const double* um, const double* u, double* up, double t, double scale) {
  load_at(t);
  for (std::size_t j : extra_nodes_) extra_[j] = 0.0;
  if (has_penalty_) penalty_forces(u, um, extra_.data());
  if (line_.near.kind == EndKind::force) extra_[line_.near.node] += near_value(t);
  if (line_.far.kind == EndKind::force) extra_[line_.far.node] += far_value(t);
  for (std::size_t i = 0; i < held_.size(); ++i) {
    HeldRow& h = held_[i];
    const std::size_t j = h.node;
    target_[i] = h.driven ? u[j] + dt_ * (h.near ? near_value(t + 0.5 * dt_) : far_value(t + 0.5 * dt_)) : 0.0;
    h.value = (target_[i] - (2.0 * u[j] - um[j])) / scale;
  }
  if (viscous_)
    load_zero_ ? sweeps<true, false>(um, u, up, scale) : sweeps<true, true>(um, u, up, scale);
  else
    load_zero_ ? sweeps<false, false>(um, u, up, scale) : sweeps<false, true>(um, u, up, scale);
  for (std::size_t i = 0; i < held_.size(); ++i) up[held_[i].node] = target_[i];  // exactly, not through the sweep
}

void LinePaoliSchatzman::project(const double* before, double* up, double force_scale) {
  if (!has_rigid_) return;
  bool violated = false;
  for (std::size_t k = 0; k < rigid_.size(); ++k) {
    const std::size_t i = rigid_.link(k);
    q_[k] = line_.opening(i, up) + rigid_.restitution(k) * line_.opening(i, before);
    violated = violated || q_[k] < 0.0;
  }
  if (violated) {
    (void)rigid_.solve(q_.data(), all_.data(), mu_.data());
    rigid_.add_responses(mu_.data(), 1.0, up);
  } else {
    std::fill(mu_.begin(), mu_.end(), 0.0);
  }
  const double scale = force_scale / (dt_ * dt_);
  for (std::size_t k = 0; k < rigid_.size(); ++k) force_[rigid_.link(k)] = mu_[k] * scale;
}

// The held rows' supports from their equations: M x = r + S + impulses / scale.
void LinePaoliSchatzman::end_forces(const double* um, const double* u, const double* up, double t, double scale) {
  for (auto& h : held_) {
    auto x = [&](std::size_t j) { return (up[j] - 2.0 * u[j] + um[j]) / scale; };
    const double mx = h.diagonal * x(h.node) + (h.neighbour == HeldRow::none ? 0.0 : h.coupling * x(h.neighbour));
    h.support = mx - h.rhs - rigid_.on_node(h.node, mu_.data()) / scale;
  }
  const EndReport r = end_report(line_, force_, near_value(t), far_value(t), held_, 1.0);
  near_force_ = r.near;
  far_force_ = r.far;
}

void LinePaoliSchatzman::start() {
  const std::size_t n = line_.nodes();
  prev_ = levels_[2].data();
  cur_ = levels_[0].data();
  next_ = levels_[1].data();
  n_ = 0;
  std::fill(c_max_.begin(), c_max_.end(), 0.0);
  // u^1 = u^0 + dt v^0 + dt^2/2 a^0, rates at t = 0 from a level u^0 - dt v^0;
  // the constraint at the start weighs u^0 as u^{-1}.
  std::vector<double> before(n);
  for (std::size_t j = 0; j < n; ++j) {
    cur_[j] = prev_[j] = u0_[j];
    before[j] = u0_[j] - dt_ * v0_[j];
  }
  const double taylor = 0.5 * dt_ * dt_;
  if (plastic_.active()) plastic_.start(cur_);
  predict(before.data(), cur_, next_, 0.0, taylor);
  project(cur_, next_, 2.0);  // the Taylor step moves by dt^2/2 a: a correction's force is twice a full step's
  end_forces(before.data(), cur_, next_, 0.0, taylor);
  if (plastic_.active()) plastic_.advance(cur_, next_, true);
  // The first half step's share of the budget, dt/2 times the rates at t = 0.
  double power = 0.0, viscous = 0.0, contact = 0.0;
  for (std::size_t j = 0; j < n; ++j) power += (load_zero_ ? 0.0 : load_[j]) * v0_[j];
  for (const auto& h : held_) power += h.support * v0_[h.node];
  if (line_.near.kind == EndKind::force) power += near_value(0.0) * v0_[line_.near.node];
  if (line_.far.kind == EndKind::force) power += far_value(0.0) * v0_[line_.far.node];
  for (std::size_t j = 0; j + 1 < n; ++j) viscous += c_[j] * (v0_[j + 1] - v0_[j]) * (v0_[j + 1] - v0_[j]);
  for (std::size_t i = 0; i < line_.links.size(); ++i) {
    const Link& l = line_.links[i];
    const double rate = -line_.opening(i, v0_.data()) + l.gap;  // dc/dt
    // A rigid link's impulse against the mean of the rates at t = 0 and over
    // (0, dt), as central differences' start (the Taylor step's identity).
    if (l.law.rigid()) contact += 0.5 * force_[i] * (rate + (line_.opening(i, cur_) - line_.opening(i, next_)) / dt_);
    book_link_damping(i, -line_.opening(i, cur_), rate, power, viscous, contact);
  }
  budget_.start(dt_, power, viscous, contact);
}

void LinePaoliSchatzman::advance() {
  const long long m = n_ + 1;
  const double t = static_cast<double>(m) * dt_;
  const double* um = cur_;
  const double* u = next_;
  double* up = prev_;
  const double dt2 = dt_ * dt_;
  predict(um, u, up, t, dt2);
  project(um, up, 1.0);
  end_forces(um, u, up, t, dt2);
  if (plastic_.active()) plastic_.advance(u, up);
  prev_ = cur_;
  cur_ = next_;
  next_ = up;
  n_ = m;
  double dw = 0.0, dd = 0.0, dc = 0.0;
  book_budget(prev_, cur_, next_, dw, dd, dc);
  budget_.book(dw, dd, dc);
}

// Level m's increments, each force at t_m tested with (u^{m+1} - u^{m-1}) / 2.
void LinePaoliSchatzman::book_budget(const double* um, const double* u, const double* up, double& dw, double& dd,
                                     double& dc) const {
  const std::size_t n = line_.nodes();
  auto moved = [&](std::size_t j) { return 0.5 * (up[j] - um[j]); };
  if (!load_zero_)
    for (std::size_t j = 0; j < n; ++j) dw += load_[j] * moved(j);
  const double t = time();
  for (const auto& h : held_) dw += h.support * moved(h.node);
  if (line_.near.kind == EndKind::force) dw += near_value(t) * moved(line_.near.node);
  if (line_.far.kind == EndKind::force) dw += far_value(t) * moved(line_.far.node);
  if (viscous_) {
    const double inv_dt = 1.0 / dt_;
    for (std::size_t j = 0; j + 1 < n; ++j)
      dd += c_[j] * ((u[j + 1] - u[j]) - (um[j + 1] - um[j])) * inv_dt * (moved(j + 1) - moved(j));
  }
  book_link_work(um, u, up, dw, dd, dc);
}

double LinePaoliSchatzman::half_step_kinetic(const double* a, const double* b) const {
  const std::size_t n = line_.nodes();
  auto w = [&](std::size_t j) { return (b[j] - a[j]) / dt_; };
  double s = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    const double wj = w(j);
    s += mass_.diag[j] * wj * wj;
    if (j + 1 < n) s += 2.0 * mass_.off[j] * wj * w(j + 1);
  }
  return 0.5 * s;
}

Energies LinePaoliSchatzman::energies() const {
  Energies e;
  e.obstacle = link_energy(cur_);
  if (n_ == 0) {
    e.kinetic = 0.5 * mass_.quadratic_form(v0_);
    e.strain = 0.5 * line_.bond_form(BondKind::element, false, u0_.data(), u0_.data());
    e.obstacle += 0.5 * line_.bond_form(BondKind::spring, false, u0_.data(), u0_.data());
    if (plastic_.active()) e.strain += plastic_.strain_energy(u0_.data());
    return e;
  }
  e.kinetic = 0.5 * (half_step_kinetic(prev_, cur_) + half_step_kinetic(cur_, next_));
  e.strain = 0.25 * (line_.bond_form(BondKind::element, false, prev_, cur_) +
                     line_.bond_form(BondKind::element, false, cur_, next_));
  if (plastic_.active()) {
    e.strain += plastic_.strain_energy(prev_, cur_, next_);
    e.plastic = plastic_.work();
  }
  e.obstacle += 0.25 * (line_.bond_form(BondKind::spring, false, prev_, cur_) +
                        line_.bond_form(BondKind::spring, false, cur_, next_));
  e.work = budget_.work();
  e.dissipation = budget_.dissipation();
  e.contact = budget_.contact() + link_hysteresis();
  return e;
}

bool LinePaoliSchatzman::finite() const {
  const std::size_t last = line_.nodes() - 1;
  return std::isfinite(cur_[0]) && std::isfinite(cur_[last]) && std::isfinite(next_[0]) && std::isfinite(next_[last]) &&
         std::isfinite(budget_.work_half) && std::isfinite(budget_.dissipation_half);
}

}  // namespace barimpact
