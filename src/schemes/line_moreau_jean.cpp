#include "barimpact/schemes/line_moreau_jean.hpp"

#include "barimpact/model/setup_polling.hpp"

#include <algorithm>
#include <cmath>

namespace barimpact {

LineMoreauJean::LineMoreauJean(const Case& c, Line line) : LineScheme(c, std::move(line)), theta_(c.time.theta) {
  const std::size_t n = line_.nodes();
  const double dt = dt_, th = theta_;
  mass_ = line_.mass(true);
  Tridiagonal w = Tridiagonal::combine(1.0, Tridiagonal::combine(1.0, mass_, th * dt, line_.viscosity()),
                                       th * th * dt * dt, line_.stiffness());
  held_ = hold_rows(line_, w);
  factor_ = FactoredTridiagonal(w, false);
  poll_setup();  // each phase is line-sized: a study's case polls its interrupt between them
  // P = M - dt^2 theta (1 - theta) K - dt (1 - theta) C and Q = -dt K, bond by
  // bond: -(P - M) v - Q u = -(K (a v + dt u) + b C v), a bond's tension.
  for (const auto& b : line_.bonds) {
    alpha_.push_back(dt * dt * th * (1.0 - th) * b.stiffness + dt * (1.0 - th) * b.viscosity);
    beta_.push_back(dt * b.stiffness);
    viscosity_.push_back(b.viscosity);
    viscous_ = viscous_ || b.viscosity > 0.0;
  }
  stretches_ = uniform_stretches(line_, std::vector<unsigned char>(n, 0), held_);
  rigid_ = RigidLinks(line_, factor_, 1.0);
  poll_setup();
  for (auto* v : {&u_, &v_, &u_old_, &v_old_, &y_, &load_old_}) v->assign(n, 0.0);
  for (auto* v : {&rate_old_, &q_, &p_}) v->assign(rigid_.size(), 0.0);
  active_.assign(rigid_.size(), 0);
  set_plastic(w, held_nodes(held_),
              th * th * dt * dt);  // a load at t_{n+1}: v^{n+1} += theta dt W^{-1} g, u^{n+1} by theta dt that
  if (plastic_iteration_.active()) kept_.keep(state());  // primed: keeping never allocates
}

template <bool loaded>
double LineMoreauJean::row(std::size_t j) const {
  const double* u = u_.data();
  const double* v = v_.data();
  double r = mass_.diag[j] * v[j];
  if (j > 0) {
    const std::size_t b = j - 1;
    r += mass_.off[b] * v[b] - (alpha_[b] * (v[j] - v[b]) + beta_[b] * (u[j] - u[b]));
  }
  if (j + 1 < line_.nodes())
    r += mass_.off[j] * v[j + 1] + alpha_[j] * (v[j + 1] - v[j]) + beta_[j] * (u[j + 1] - u[j]);
  if constexpr (loaded) r += dt_ * theta_ * load_[j] + dt_ * (1.0 - theta_) * load_old_[j];
  return r;
}

template <bool loaded>
double LineMoreauJean::special_row(std::size_t j) {
  double r = row<loaded>(j);
  if (j == line_.near.node && line_.near.kind == EndKind::force) r += near_impulse_;
  if (j == line_.far.node && line_.far.kind == EndKind::force) r += far_impulse_;
  return held_row(held_, j, r);
}

// One pass towards x = 0 forms P v + Q u + loads inside W's first sweep (the
// single bar's constant stencils inside each stretch); one pass back gives
// v^{n+1} and u^{n+1} = u^n + dt (theta v^{n+1} + (1 - theta) v^n).
template <bool loaded>
void LineMoreauJean::free_step() {
  const double* u = u_.data();
  const double* v = v_.data();
  const double* f1 = load_.data();
  const double* f0 = load_old_.data();
  const double cf1 = dt_ * theta_, cf0 = dt_ * (1.0 - theta_);
  auto stencil = [&](const Stretch& s) {
    const std::size_t b = s.first;
    const double pd = mass_.diag[b] - 2.0 * alpha_[b], po = mass_.off[b] + alpha_[b];
    const double qd = -2.0 * beta_[b], qo = beta_[b];
    return [=](std::size_t j) {
      double r = pd * v[j] + po * (v[j - 1] + v[j + 1]) + (qd * u[j] + qo * (u[j - 1] + u[j + 1]));
      if constexpr (loaded) r += cf1 * f1[j] + cf0 * f0[j];
      return r;
    };
  };
  sweep_towards_near(
      factor_, stretches_, stencil, [&](std::size_t j) { return special_row<loaded>(j); }, y_.data());
  double* __restrict uu = u_.data();
  double* __restrict vv = v_.data();
  const double dt = dt_, th = theta_;
  sweep_away(factor_, y_.data(), [&](std::size_t j, double x) {
    uu[j] += dt * (th * x + (1.0 - th) * vv[j]);
    vv[j] = x;
  });
}

void LineMoreauJean::predict_contacts() {
  any_active_ = false;
  for (std::size_t k = 0; k < rigid_.size(); ++k) {
    rate_old_[k] = rigid_.along(k, v_.data());
    // The single bar's rule: the gap predicted at t_{n+1/2} is closed.
    const bool on = line_.opening(rigid_.link(k), u_.data()) + 0.5 * dt_ * rate_old_[k] <= 0.0;
    active_[k] = on ? 1 : 0;
    any_active_ = any_active_ || on;
  }
}

void LineMoreauJean::settle_contacts() {
  std::fill(p_.begin(), p_.end(), 0.0);
  if (any_active_) {
    for (std::size_t k = 0; k < rigid_.size(); ++k)
      q_[k] = active_[k] ? rigid_.along(k, v_.data()) + rigid_.restitution(k) * rate_old_[k] : 0.0;
    (void)rigid_.solve(q_.data(), active_.data(), p_.data());
    rigid_.add_responses(p_.data(), 1.0, v_.data());
    rigid_.add_responses(p_.data(), dt_ * theta_, u_.data());
  }
  for (std::size_t k = 0; k < rigid_.size(); ++k) force_[rigid_.link(k)] = p_[k] / dt_;
}

void LineMoreauJean::end_forces(double t1) {
  for (auto& h : held_) h.support = h.residual(v_.data()) - rigid_.on_node(h.node, p_.data());  // an impulse
  const EndReport r = end_report(line_, force_, near_value(t1), far_value(t1), held_, 1.0 / dt_);
  near_force_ = r.near;
  far_force_ = r.far;
}

void LineMoreauJean::book_budget(double t0, double t1) {
  const std::size_t n = line_.nodes();
  double dw = 0.0, dd = 0.0, dc = 0.0;
  if (!load_zero_)
    for (std::size_t j = 0; j < n; ++j) dw += (u_[j] - u_old_[j]) * 0.5 * (load_[j] + load_old_[j]);
  if (line_.near.kind == EndKind::force)
    dw += (u_[line_.near.node] - near_u_old_) * 0.5 * (near_value(t0) + near_value(t1));
  if (line_.far.kind == EndKind::force) dw += (u_[line_.far.node] - far_u_old_) * 0.5 * (far_value(t0) + far_value(t1));
  for (const auto& h : held_) dw += h.support * 0.5 * (h.before + v_[h.node]);
  if (viscous_) {
    for (std::size_t b = 0; b + 1 < n; ++b) {
      const double dv = 0.5 * ((v_[b + 1] + v_old_[b + 1]) - (v_[b] + v_old_[b]));
      dd += dt_ * viscosity_[b] * dv * dv;
    }
  }
  for (std::size_t k = 0; k < rigid_.size(); ++k)
    if (p_[k] != 0.0) dc -= p_[k] * 0.5 * (rate_old_[k] + rigid_.along(k, v_.data()));
  work_ += dw;
  dissipation_ += dd;
  contact_ += dc;
}

void LineMoreauJean::advance() {
  if (plastic_iteration_.active())
    advance_plastic([this] { advance_elastic(); }, u_);
  else
    advance_elastic();
}

void LineMoreauJean::advance_elastic() {
  const double t0 = time(), t1 = static_cast<double>(n_ + 1) * dt_;
  if (!load_zero_ && !load_steady_) {
    std::swap(load_, load_old_);
    load_at(t1);
  }
  near_impulse_ = dt_ * (theta_ * near_value(t1) + (1.0 - theta_) * near_value(t0));
  far_impulse_ = dt_ * (theta_ * far_value(t1) + (1.0 - theta_) * far_value(t0));
  near_u_old_ = u_[line_.near.node];
  far_u_old_ = u_[line_.far.node];
  for (auto& h : held_) {
    h.before = v_[h.node];
    h.value = h.driven ? (h.near ? near_value(t1) : far_value(t1)) : 0.0;
  }
  predict_contacts();
  if (!load_zero_ ||
      viscous_) {  // the budget's load work and viscous loss need level n (plastic loads toggle load_zero_)
    std::copy(u_.begin(), u_.end(), u_old_.begin());
    std::copy(v_.begin(), v_.end(), v_old_.begin());
  }
  load_zero_ ? free_step<false>() : free_step<true>();
  settle_contacts();
  end_forces(t1);
  book_budget(t0, t1);
  ++n_;
}

void LineMoreauJean::start() {
  u_ = u0_;
  v_ = v0_;
  for (const auto& h : held_)
    if (h.driven) v_[h.node] = h.near ? near_value(0.0) : far_value(0.0);
  start_plastic(u_.data());
  load_at(0.0);
  load_old_ = load_;
  n_ = 0;
  work_ = dissipation_ = contact_ = 0.0;
  std::fill(force_.begin(), force_.end(), 0.0);
  std::fill(p_.begin(), p_.end(), 0.0);
  for (auto& h : held_) h.support = 0.0;
  const EndReport r = end_report(line_, force_, near_value(0.0), far_value(0.0), held_, 1.0);
  near_force_ = r.near;
  far_force_ = r.far;
}

Energies LineMoreauJean::energies() const {
  Energies e;
  e.kinetic = 0.5 * mass_.quadratic_form(v_);
  e.strain = 0.5 * line_.bond_form(BondKind::element, false, u_.data(), u_.data());
  e.obstacle = 0.5 * line_.bond_form(BondKind::spring, false, u_.data(), u_.data());
  e.work = work_;
  e.dissipation = dissipation_;
  e.contact = contact_;
  add_plastic(e, u_.data());
  return e;
}

bool LineMoreauJean::finite() const {
  const std::size_t last = line_.nodes() - 1;
  return !failed_ && std::isfinite(u_[0]) && std::isfinite(u_[last]) && std::isfinite(v_[0]) &&
         std::isfinite(v_[last]) && std::isfinite(work_) && std::isfinite(dissipation_) && std::isfinite(contact_);
}

}  // namespace barimpact
