#include "barimpact/schemes/line_mass_redistribution.hpp"

#include "barimpact/model/setup_polling.hpp"

#include <algorithm>
#include <cmath>

namespace barimpact {

Tridiagonal redistributed_mass(const Line& line) {
  Tridiagonal m = line.mass(true);
  for (const auto& l : line.links) {
    if (!l.law.rigid()) continue;
    for (std::size_t f : {l.a, l.b}) {
      if (f == Link::ground) continue;
      const std::size_t inner = f == l.a ? f - 1 : f + 1, bond = std::min(f, inner);
      // [[2, 1], [1, 2]] m/6 -> [[0, 0], [0, 6]] m/6 on (face, inner).
      m.diag[inner] += 2.0 * line.bonds[bond].mass / 3.0;
      m.diag[f] = 0.0;  // exactly, not round-off: the face has no other element
      m.off[bond] = 0.0;
    }
  }
  return m;
}

LineMassRedistribution::LineMassRedistribution(const Case& c, Line line) : LineScheme(c, std::move(line)) {
  const std::size_t n = line_.nodes();
  mass_ = redistributed_mass(line_);
  const Tridiagonal k = line_.stiffness();
  Tridiagonal a = Tridiagonal::combine(2.0 / (dt_ * dt_), mass_, 0.5, k);
  held_ = hold_rows(line_, a);
  factor_ = FactoredTridiagonal(a, false);
  poll_setup();  // each phase is line-sized: a study's case polls its interrupt between them
  for (const auto& b : line_.bonds) k_.push_back(b.stiffness);
  // The faces and their inner neighbours (M~ changed there) are special rows.
  face_.assign(n, 0);
  std::vector<unsigned char> special(n, 0);
  for (const auto& l : line_.links)
    for (std::size_t f : {l.a, l.b})
      if (l.law.rigid() && f != Link::ground) {
        face_[f] = special[f] = 1;
        special[f == l.a ? f - 1 : f + 1] = 1;
      }
  for (std::size_t j = 0; j < n; ++j)
    if (face_[j]) faces_.push_back(j);
  stretches_ = uniform_stretches(line_, special, held_);
  rigid_ = RigidLinks(line_, factor_, 0.5);  // lambda enters a face's halved equilibrium as lambda h / 2
  poll_setup();
  for (auto* v : {&u_, &v_, &u_old_, &y_, &load_old_}) v->assign(n, 0.0);
  face_u_old_.assign(faces_.size(), 0.0);
  face_rho_.assign(faces_.size(), 0.0);
  q_.assign(rigid_.size(), 0.0);
  lambda_.assign(rigid_.size(), 0.0);
  all_.assign(rigid_.size(), 1);
  set_plastic(a, held_nodes(held_), 0.5);  // a load at t_{n+1} enters Fbar (and a face's halved equilibrium) by half
  if (plastic_iteration_.active()) kept_.keep(state());  // primed: keeping never allocates
}

template <bool loaded>
double LineMassRedistribution::row(std::size_t j) const {
  const double* u = u_.data();
  const double* v = v_.data();
  const double c2 = 2.0 / (dt_ * dt_), dt = dt_;
  auto s = [&](std::size_t i) { return u[i] + dt * v[i]; };
  double r = c2 * mass_.diag[j] * s(j);
  if (j > 0) r += c2 * mass_.off[j - 1] * s(j - 1) - 0.5 * k_[j - 1] * (u[j] - u[j - 1]);
  if (j + 1 < line_.nodes()) r += c2 * mass_.off[j] * s(j + 1) + 0.5 * k_[j] * (u[j + 1] - u[j]);
  if constexpr (loaded) r += 0.5 * (load_[j] + load_old_[j]);
  return r;
}

template <bool loaded>
double LineMassRedistribution::special_row(std::size_t j) {
  double r = 0.0;
  if (face_[j]) {
    r = loaded ? 0.5 * load_[j] : 0.0;  // (K u^{n+1})_f = F_f^{n+1}, halved
  } else {
    r = row<loaded>(j);
    if (j == line_.near.node && line_.near.kind == EndKind::force) r += near_mean_;
    if (j == line_.far.node && line_.far.kind == EndKind::force) r += far_mean_;
  }
  return held_row(held_, j, r);
}

// One pass towards x = 0 forms the right-hand sides inside A's first sweep
// (the single bar's constant stencils inside each stretch); one pass back
// gives u^{n+1} and v^{n+1} = 2 (u^{n+1} - u^n) / dt - v^n.
template <bool loaded>
void LineMassRedistribution::free_step() {
  const double* u = u_.data();
  const double* v = v_.data();
  const double* f1 = load_.data();
  const double* f0 = load_old_.data();
  const double c2 = 2.0 / (dt_ * dt_), dt = dt_;
  auto stencil = [&](const Stretch& s) {
    const double md = c2 * mass_.diag[s.first], mo = c2 * mass_.off[s.first], kh = 0.5 * k_[s.first];
    return [=](std::size_t j) {
      double r = md * (u[j] + dt * v[j]) + mo * ((u[j - 1] + dt * v[j - 1]) + (u[j + 1] + dt * v[j + 1])) +
                 kh * ((u[j - 1] + u[j + 1]) - 2.0 * u[j]);
      if constexpr (loaded) r += 0.5 * (f1[j] + f0[j]);
      return r;
    };
  };
  sweep_towards_near(
      factor_, stretches_, stencil, [&](std::size_t j) { return special_row<loaded>(j); }, y_.data());
  double* __restrict uu = u_.data();
  double* __restrict vv = v_.data();
  const double two_over_dt = 2.0 / dt;
  sweep_away(factor_, y_.data(), [&](std::size_t j, double x) {
    vv[j] = two_over_dt * (x - uu[j]) - vv[j];
    uu[j] = x;
  });
}

void LineMassRedistribution::settle_contacts() {
  bool closed = false;
  for (std::size_t k = 0; k < rigid_.size(); ++k) {
    q_[k] = line_.opening(rigid_.link(k), u_.data());
    closed = closed || q_[k] < 0.0;
  }
  if (closed) {
    (void)rigid_.solve(q_.data(), all_.data(), lambda_.data());
    rigid_.add_responses(lambda_.data(), 1.0, u_.data());
    rigid_.add_responses(lambda_.data(), 2.0 / dt_, v_.data());  // v^{n+1} = 2 (u^{n+1} - u^n) / dt - v^n
  } else {
    std::fill(lambda_.begin(), lambda_.end(), 0.0);
  }
  for (std::size_t k = 0; k < rigid_.size(); ++k) force_[rigid_.link(k)] = lambda_[k];
  for (std::size_t i = 0; i < faces_.size(); ++i) {
    const std::size_t f = faces_[i];
    v_[f] = (u_[f] - face_u_old_[i]) / dt_;  // the massless face: a backward difference
  }
}

double LineMassRedistribution::imbalance(std::size_t f, double t) const {
  double r = -(load_zero_ ? 0.0 : load_[f]);
  if (f > 0) r += k_[f - 1] * (u_[f] - u_[f - 1]);
  if (f + 1 < line_.nodes()) r -= k_[f] * (u_[f + 1] - u_[f]);
  if (f == line_.near.node && line_.near.kind == EndKind::force) r -= near_value(t);
  if (f == line_.far.node && line_.far.kind == EndKind::force) r -= far_value(t);
  return r;
}

void LineMassRedistribution::book_budget(double t0, double t1) {
  double dw = 0.0, dc = 0.0;
  if (!load_zero_)
    for (std::size_t j = 0; j < line_.nodes(); ++j) dw += (u_[j] - u_old_[j]) * 0.5 * (load_[j] + load_old_[j]);
  if (line_.near.kind == EndKind::force) dw += (u_[line_.near.node] - near_u_old_) * near_mean_;
  if (line_.far.kind == EndKind::force) dw += (u_[line_.far.node] - far_u_old_) * far_mean_;
  for (const auto& h : held_) dw += h.support * (u_[h.node] - h.before);
  for (std::size_t i = 0; i < faces_.size(); ++i) {
    const double rho = imbalance(faces_[i], t1);
    dc -= (u_[faces_[i]] - face_u_old_[i]) * 0.5 * (face_rho_[i] + rho);
    face_rho_[i] = rho;
  }
  (void)t0;
  work_ += dw;
  contact_ += dc;
}

void LineMassRedistribution::advance() {
  if (plastic_iteration_.active())
    advance_plastic([this] { advance_elastic(); }, u_);
  else
    advance_elastic();
}

void LineMassRedistribution::advance_elastic() {
  const double t0 = time(), t1 = static_cast<double>(n_ + 1) * dt_;
  if (!load_zero_ && !load_steady_) {
    std::swap(load_, load_old_);
    load_at(t1);
  }
  near_mean_ = 0.5 * (near_value(t0) + near_value(t1));
  far_mean_ = 0.5 * (far_value(t0) + far_value(t1));
  near_u_old_ = u_[line_.near.node];
  far_u_old_ = u_[line_.far.node];
  for (auto& h : held_) {
    const std::size_t j = h.node;
    h.before = u_[j];
    h.value = h.driven ? u_[j] + dt_ * (h.near ? near_mean_ : far_mean_) : 0.0;
  }
  for (std::size_t i = 0; i < faces_.size(); ++i) face_u_old_[i] = u_[faces_[i]];
  if (!load_zero_) std::copy(u_.begin(), u_.end(), u_old_.begin());
  load_zero_ ? free_step<false>() : free_step<true>();
  settle_contacts();
  for (auto& h : held_) h.support = h.residual(u_.data());  // the mean support force over the step
  const EndReport r = end_report(line_, force_, near_value(t1), far_value(t1), held_, 1.0);
  near_force_ = r.near;
  far_force_ = r.far;
  book_budget(t0, t1);
  ++n_;
}

void LineMassRedistribution::start() {
  u_ = u0_;
  v_ = v0_;
  for (const auto& h : held_)
    if (h.driven) v_[h.node] = h.near ? near_value(0.0) : far_value(0.0);
  start_plastic(u_.data());
  load_at(0.0);
  load_old_ = load_;
  n_ = 0;
  work_ = contact_ = 0.0;
  std::fill(force_.begin(), force_.end(), 0.0);
  for (auto& h : held_) h.support = 0.0;
  for (std::size_t i = 0; i < faces_.size(); ++i) face_rho_[i] = imbalance(faces_[i], 0.0);
  const EndReport r = end_report(line_, force_, near_value(0.0), far_value(0.0), held_, 1.0);
  near_force_ = r.near;
  far_force_ = r.far;
}

Energies LineMassRedistribution::energies() const {
  Energies e;
  e.kinetic = 0.5 * mass_.quadratic_form(v_);
  e.strain = 0.5 * line_.bond_form(BondKind::element, false, u_.data(), u_.data());
  e.obstacle = 0.5 * line_.bond_form(BondKind::spring, false, u_.data(), u_.data());
  e.work = work_;
  e.contact = contact_;
  add_plastic(e, u_.data());
  return e;
}

bool LineMassRedistribution::finite() const {
  const std::size_t last = line_.nodes() - 1;
  return !failed_ && std::isfinite(u_[0]) && std::isfinite(u_[last]) && std::isfinite(v_[0]) &&
         std::isfinite(v_[last]) && std::isfinite(work_) && std::isfinite(contact_);
}

}  // namespace barimpact
