#include "barimpact/schemes/plastic_iteration.hpp"

#include <algorithm>
#include <cmath>

#include "yield_check.hpp"

namespace barimpact {

PlasticIteration::PlasticIteration(const Line& line) {
  ranges_ = plastic_bodies(line);
  const std::size_t bonds = line.bonds.size();
  for (auto* v : {&p_, &alpha_, &pk_, &alphak_, &trial_p_, &trial_alpha_}) v->assign(bonds, 0.0);
  flowing_.assign(bonds, 0);
  q_.assign(ranges_.size(), 0.0);
  start_.assign(ranges_.size(), Sums{});
  for (const Link& l : line.links) links_.push_back({l.a, l.b, l.law.rigid() ? 0.0 : l.law.stiffness});
}

void PlasticIteration::set_matrix(const Tridiagonal& a, const std::vector<std::size_t>& held, double c,
                                  bool links_in_matrix) {
  a_ = a;
  links_in_matrix_ = links_in_matrix;
  held_ = held;
  c_ = c;
  // The tangent's arrays reserved, not filled: newton() writes them whole,
  // so a bar that never yields never faults their pages in.
  for (auto* v : {&diag_, &off_, &du_}) v->clear();
  diag_.reserve(a.size());
  off_.reserve(a.off.size());
  du_.reserve(a.size());
}

void PlasticIteration::start(const double* u0) {
  std::fill(p_.begin(), p_.end(), 0.0);
  std::fill(alpha_.begin(), alpha_.end(), 0.0);
  // From a virgin state: u0 reached in one step from u = 0.
  iterate_p_ = p_.data();
  (void)trial(u0, 1.0);
  p_ = trial_p_;
  alpha_ = trial_alpha_;
  pristine_ = std::all_of(p_.begin(), p_.end(), [](double x) { return x == 0.0; });
  std::fill(q_.begin(), q_.end(), 0.0);
  effort_ = Effort{};
  for (std::size_t i = 0; i < ranges_.size(); ++i) start_[i] = sums(ranges_[i], u0);
  begin_step();
}

void PlasticIteration::begin_step() {
  iterate_p_ = p_.data();
  loading_ = !pristine_;
}

void PlasticIteration::add_load(double* f) const {
  for (const Range& r : ranges_)
    for (std::size_t j = r.first; j < r.last; ++j) {
      const double g = r.axial * iterate_p_[j];
      f[j] -= g;
      f[j + 1] += g;
    }
}

double PlasticIteration::trial(const double* u, double scale) {
  double worst = 0.0;
  for (const Range& r : ranges_) {
    const double e = r.law.modulus, hm = r.law.plastic_modulus, sy = r.law.yield_stress, inv_h = r.inv_h * scale;
    // 1e-10 of the yield strain: far above the return map's round-off (a few
    // ulps of the strain), far below any strain a user reads.
    const double inv = 1.0 / (e + hm), inv_tol = 1.0 / (1e-10 * r.yield_strain());
    for (std::size_t j = r.first; j < r.last; ++j) {
      double p = p_[j], a = alpha_[j];
      const double trial = e * ((u[j + 1] - u[j]) * inv_h - p);
      const double dgamma = r.law.isotropic ? Plasticity::return_map<true>(trial, hm, sy, inv, p, a)
                                            : Plasticity::return_map<false>(trial, hm, sy, inv, p, a);
      trial_p_[j] = p;
      trial_alpha_[j] = a;
      flowing_[j] = dgamma > 0.0 ? 1 : 0;
      worst = std::max(worst, std::abs(p - iterate_p_[j]) * inv_tol);
    }
  }
  return worst;
}

bool PlasticIteration::settled(const double* u, const double* force, double scale) {
  // k = 0: a read-only check first, the common answer
  if (iterate_p_ == p_.data() && !detail::any_yields(ranges_, pristine_, scale, u, p_.data(), alpha_.data())) {
    misfit_ = 0.0;
    return true;
  }
  misfit_ = trial(u, scale);
  if (misfit_ <= 1.0) return true;
  newton(u, force, scale);
  return false;
}

bool PlasticIteration::take(const double* u, double scale) {
  begin_step();
  (void)trial(u, scale);
  if (std::equal(trial_p_.begin(), trial_p_.end(), p_.begin()) &&
      std::equal(trial_alpha_.begin(), trial_alpha_.end(), alpha_.begin()))
    return false;
  pk_ = trial_p_;
  alphak_ = trial_alpha_;
  use_iterate();
  accept(nullptr, u);
  return true;
}

// T du = c G (p^ - p^k), T = A - c K_loss over the flowing elements (held
// rows the identity), by the Thomas algorithm; then p^{k+1} = P(u + du).
void PlasticIteration::add_links(const double* force) {
  for (std::size_t i = 0; i < links_.size(); ++i) {
    if (!(force[i] > 0.0)) continue;
    const LinkTangent& l = links_[i];
    double s = c_ * l.stiffness;
    if (s == 0.0)
      for (std::size_t j : {l.a, l.b})
        if (j != Link::ground) s = std::max(s, 1e8 * std::abs(a_.diag[j]));
    for (std::size_t j : {l.a, l.b})
      if (j != Link::ground) diag_[j] += s;
    if (l.a != Link::ground && l.b != Link::ground) off_[std::min(l.a, l.b)] -= s;
  }
}

void PlasticIteration::newton(const double* u, const double* force, double scale) {
  const std::size_t n = a_.size();
  diag_.assign(a_.diag.begin(), a_.diag.end());  // within set_matrix's reserve: no allocation
  off_.assign(a_.off.begin(), a_.off.end());
  du_.assign(n, 0.0);
  for (const Range& r : ranges_) {
    // E / (E + H), kept below 1 so that a massless node between perfectly
    // plastic elements (mass-redistribution's faces) keeps a pivot.
    const double loss = c_ * r.k * std::min(r.law.modulus / (r.law.modulus + r.law.plastic_modulus), 1.0 - 1e-6);
    for (std::size_t j = r.first; j < r.last; ++j) {
      const double g = c_ / scale * r.axial * (trial_p_[j] - iterate_p_[j]);  // z's units (u / scale)
      du_[j] -= g;
      du_[j + 1] += g;
      if (!flowing_[j]) continue;
      diag_[j] -= loss;
      diag_[j + 1] -= loss;
      off_[j] += loss;
    }
  }
  if (!links_in_matrix_) add_links(force);
  solve_tangent(diag_, off_, held_, du_);
  for (std::size_t j = 0; j < n; ++j) du_[j] += u[j];  // u^{n+1} + du
  (void)trial(du_.data(), scale);
  std::swap(pk_, trial_p_);
  std::swap(alphak_, trial_alpha_);
  use_iterate();
}

void PlasticIteration::accept(const double* u_old, const double* u) {
  for (std::size_t i = 0; u_old != nullptr && i < ranges_.size(); ++i) {
    const Range& r = ranges_[i];
    const double scale = r.volume * r.law.modulus * 0.5 * r.inv_h;
    double s = 0.0;
    for (std::size_t j = r.first; j < r.last; ++j)
      s += ((u_old[j + 1] - u_old[j]) + (u[j + 1] - u[j])) * (pk_[j] - p_[j]);
    q_[i] += scale * s;
  }
  std::swap(p_, pk_);
  std::swap(alpha_, alphak_);
  pristine_ = false;
  begin_step();
}

PlasticIteration::Sums PlasticIteration::sums(const Range& r, const double* u) const {
  Sums s;
  const double* a = r.law.isotropic ? alpha_.data() : p_.data();
  for (std::size_t j = r.first; j < r.last; ++j) {
    s.p_p += 0.5 * p_[j] * p_[j];
    s.hardening += 0.5 * a[j] * a[j];
  }
  if (u != nullptr)
    for (std::size_t j = r.first; j < r.last; ++j) s.p_eps += p_[j] * (u[j + 1] - u[j]) * r.inv_h;
  const double scale = r.volume * r.law.modulus;
  s.p_eps *= scale;
  s.p_p *= scale;
  s.hardening *= r.volume * r.law.plastic_modulus;
  return s;
}

double PlasticIteration::strain_energy(const double* u) const {
  double e = 0.0;
  for (const Range& r : ranges_) {
    const Sums s = sums(r, u);
    e += s.p_p - s.p_eps + s.hardening;
  }
  return e;
}

double PlasticIteration::load_work(const double* u) const {
  double w = 0.0;
  for (std::size_t i = 0; i < ranges_.size(); ++i) w += sums(ranges_[i], u).p_eps - start_[i].p_eps - q_[i];
  return w;
}

double PlasticIteration::range_work(std::size_t i) const {
  const Sums s = sums(ranges_[i], nullptr);
  return q_[i] - (s.p_p - start_[i].p_p) - (s.hardening - start_[i].hardening);
}

double PlasticIteration::work() const {
  double w = 0.0;
  for (std::size_t i = 0; i < ranges_.size(); ++i) w += range_work(i);
  return w;
}

double PlasticIteration::body_work(std::size_t body) const {
  for (std::size_t i = 0; i < ranges_.size(); ++i)
    if (ranges_[i].body == body) return range_work(i);
  return 0.0;
}

}  // namespace barimpact
