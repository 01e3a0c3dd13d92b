#include "barimpact/schemes/line_scheme.hpp"

#include "barimpact/model/setup_polling.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "barimpact/case/line_builder.hpp"

namespace barimpact {

LineScheme::LineScheme(const Case& c, Line line) : line_(std::move(line)), dt_(c.time.step), inv_dt_(1.0 / dt_) {
  const std::size_t n = line_.nodes(), links = line_.links.size();
  near_link_ = !line_.links.empty() && line_.links.front().name == "near_end";
  far_link_ = !line_.links.empty() && line_.links.back().name == "far_end";
  load_.assign(n, 0.0);
  force_.assign(links, 0.0);
  c_max_.assign(links, 0.0);
  for (const auto& l : line_.links) {
    restitution_.push_back(l.law.restitution);
    (l.law.rigid() ? has_rigid_ : has_penalty_) = true;
  }
  body_force_ = std::make_unique<Expression>(line_.body_force);
  body_zero_ = load_zero_ = body_force_->is_zero() && line_.gravity == 0.0;
  load_steady_ = !body_force_->depends_on_t();
  plastic_iteration_ = PlasticIteration(line_);
  if (line_.near.kind == EndKind::force || line_.near.kind == EndKind::velocity)
    near_value_ = std::make_unique<Expression>(line_.near.value);
  if (line_.far.kind == EndKind::force || line_.far.kind == EndKind::velocity)
    far_value_ = std::make_unique<Expression>(line_.far.value);
  if (line_.near.history) near_history_ = HistoryReader(line_.near.history);
  if (line_.far.history) far_history_ = HistoryReader(line_.far.history);
  poll_setup();  // line-sized phases: a study's case polls its interrupt between them
  u0_ = line_.initial(0);
  v0_ = line_.initial(1);
  // A held end starts as its condition says: at rest at 0 (clamped; the case
  // reader checks u0 and v0 vanish there), or at v(0) (driven: the end's
  // history, not the body's v0, moves that node from the start).
  if (line_.near.kind == EndKind::clamped) u0_[line_.near.node] = v0_[line_.near.node] = 0.0;
  if (line_.far.kind == EndKind::clamped) u0_[line_.far.node] = v0_[line_.far.node] = 0.0;
  if (line_.near.kind == EndKind::velocity) v0_[line_.near.node] = near_value(0.0);
  if (line_.far.kind == EndKind::velocity) v0_[line_.far.node] = far_value(0.0);
}

void LineScheme::load_into(double t, std::vector<double>& f) {
  if (body_zero_)
    std::fill(f.begin(), f.end(), 0.0);
  else if (!steady_body_.empty())
    std::copy(steady_body_.begin(), steady_body_.end(), f.begin());
  else
    line_.load(*body_force_, t, f);
  if (plastic_iteration_.loading()) plastic_iteration_.add_load(f.data());
}

void LineScheme::set_plastic(const Tridiagonal& a, const std::vector<std::size_t>& held, double c) {
  if (!plastic_iteration_.active()) return;
  load_steady_ = false;  // the plastic strains' load moves
  set_plastic_matrix(a, held, c, false);
}

void LineScheme::set_plastic_levels(const Tridiagonal& a, const std::vector<std::size_t>& held, double c) {
  if (!plastic_iteration_.active()) return;
  one_step_plastic_ = false;  // the scheme keeps three load levels: a steady F stays steady until p loads
  set_plastic_matrix(a, held, c, true);
}

void LineScheme::set_plastic_matrix(const Tridiagonal& a, const std::vector<std::size_t>& held, double c,
                                    bool links_in_matrix) {
  plastic_iteration_.set_matrix(a, held, c, links_in_matrix);
  // A steady body force, once: the plastic strains' load makes the loads move, not it.
  if (!body_zero_ && !body_force_->depends_on_t()) {
    steady_body_.assign(line_.nodes(), 0.0);
    line_.load(*body_force_, 0.0, steady_body_);
  }
}

void LineScheme::start_plastic(const double* u0) {
  failed_ = false;
  if (!plastic_iteration_.active()) return;
  std::fill(load_.begin(), load_.end(), 0.0);  // no plastic load of an earlier run left in it
  plastic_iteration_.start(u0);
  plastic_loads();
  since_kept_ = keep_interval_ = 1;
  yielded_since_kept_ = false;
}

void LineScheme::keep_level() {
  keep_state();
  kept_n_ = n_;
  since_kept_ = 0;
  yielded_since_kept_ = false;
}

// The schemes' loads carry G p^k while it may be nonzero.
void LineScheme::plastic_loads() {
  load_zero_ = body_zero_ && !plastic_iteration_.loading();
}

std::string LineScheme::failure() const {
  if (!failed_) return {};
  if (!failed_soil_.empty()) return failed_soil_;
  return fmt::format(
      "the elastic-plastic iteration did not settle in {} steps (the plastic strains still move by {:.3g} times "
      "the tolerance 1e-10 sigma_y / E)",
      PlasticIteration::most_iterations, failed_misfit_);
}

void LineScheme::add_plastic(Energies& e, const double* u) const {
  if (!plastic_iteration_.active()) return;
  e.strain += plastic_iteration_.strain_energy(u);
  e.work -= plastic_iteration_.load_work(u);
  e.plastic = plastic_iteration_.work();
}

void LineScheme::displacement(std::span<double> out) const {
  for (std::size_t j = 0; j < out.size(); ++j) out[j] = displacement_at(j);
}

void LineScheme::velocity(std::span<double> out) const {
  for (std::size_t j = 0; j < out.size(); ++j) out[j] = velocity_at(j);
}

double LineScheme::link_opening(std::size_t i) const {
  const Link& l = line_.links[i];
  return (l.b == Link::ground ? 0.0 : displacement_at(l.b)) - (l.a == Link::ground ? 0.0 : displacement_at(l.a)) +
         l.gap;
}

double LineScheme::link_energy(const double* u) const {
  double e = 0.0;
  for (std::size_t i = 0; i < line_.links.size(); ++i) e += line_.links[i].law.energy(-line_.opening(i, u), c_max_[i]);
  return e;
}

double LineScheme::link_hysteresis() const {
  double d = 0.0;
  for (std::size_t i = 0; i < line_.links.size(); ++i) d += line_.links[i].law.hysteresis(c_max_[i]);
  return d;
}

double line_stable_step(const Line& line, bool consistent_mass) {
  const std::size_t n = line.nodes();
  std::vector<double> stiff(n, 0.0), damp(n, 0.0);
  for (std::size_t j = 0; j + 1 < n; ++j) {
    for (std::size_t i : {j, j + 1}) {
      stiff[i] += 2.0 * line.bonds[j].stiffness;
      damp[i] += 2.0 * line.bonds[j].viscosity;
    }
  }
  for (const auto& l : line.links) {
    if (l.law.rigid()) continue;
    // A cushion unloads along k / e^2; Smith's damping J |R_s| is at most J R_u.
    const double k = l.law.largest_stiffness(), eta = l.law.largest_viscosity();
    for (std::size_t i : {l.a, l.b})
      if (i != Link::ground) {
        stiff[i] += (l.a != Link::ground && l.b != Link::ground ? 2.0 : 1.0) * k;
        damp[i] += (l.a != Link::ground && l.b != Link::ground ? 2.0 : 1.0) * eta;
      }
  }
  for (std::size_t j : line.shaft.nodes) {
    stiff[j] += line.shaft.stiffness[j];
    damp[j] += line.shaft.smith[j] * line.shaft.ultimate[j] + line.shaft.viscous[j];
  }
  const std::vector<double> m = line.lumped_mass();
  double omega2 = 0.0, eta = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    if (line.fixed(j)) continue;
    omega2 = std::max(omega2, stiff[j] / m[j]);
    eta = std::max(eta, damp[j] / m[j]);
  }
  if (consistent_mass) {
    omega2 *= 3.0;
    eta *= 3.0;
  }
  if (omega2 == 0.0) return eta > 0.0 ? 2.0 / eta : std::numeric_limits<double>::infinity();
  // (u^{n+1} - 2u^n + u^{n-1})/dt^2 + eta (u^n - u^{n-1})/dt + omega^2 u^n = 0
  // is stable for omega^2 dt^2 + 2 eta dt <= 4.
  return (-eta + std::sqrt(eta * eta + 4.0 * omega2)) / omega2;
}

}  // namespace barimpact
