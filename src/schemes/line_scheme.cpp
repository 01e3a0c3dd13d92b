#include "barimpact/schemes/line_scheme.hpp"

#include <fmt/format.h>

#include "barimpact/case/line_builder.hpp"
#include "barimpact/schemes/line_central_difference.hpp"

namespace barimpact {

LineScheme::LineScheme(const Case& c, Line line) : line_(std::move(line)), dt_(c.time.step) {
  const std::size_t n = line_.nodes(), links = line_.links.size();
  load_.assign(n, 0.0);
  force_.assign(links, 0.0);
  c_max_.assign(links, 0.0);
  for (const auto& l : line_.links) {
    restitution_.push_back(l.law.restitution);
    (l.law.rigid() ? has_rigid_ : has_penalty_) = true;
  }
  body_force_ = std::make_unique<Expression>(line_.body_force);
  load_zero_ = body_force_->is_zero() && line_.gravity == 0.0;
  load_steady_ = !body_force_->depends_on_t();
  if (line_.near.kind == EndKind::force || line_.near.kind == EndKind::velocity)
    near_value_ = std::make_unique<Expression>(line_.near.value);
  if (line_.far.kind == EndKind::force || line_.far.kind == EndKind::velocity)
    far_value_ = std::make_unique<Expression>(line_.far.value);
  u0_ = line_.initial(0);
  v0_ = line_.initial(1);
  for (std::size_t j = 0; j < n; ++j)
    if (line_.fixed(j) && (j == line_.near.node ? line_.near : line_.far).kind == EndKind::clamped)
      u0_[j] = v0_[j] = 0.0;
}

void LineScheme::load_at(double t) {
  if (load_zero_ || (load_steady_ && t > 0.0)) return;  // zero, or computed at t = 0
  line_.load(*body_force_, t, load_);
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

void LineScheme::add_link_force(std::size_t i, double p, double* r) const {
  const Link& l = line_.links[i];
  if (l.a != Link::ground) r[l.a] -= p;
  if (l.b != Link::ground) r[l.b] += p;
}

void LineScheme::penalty_forces(const double* u, const double* u_old, double* r) {
  const double inv_dt = 1.0 / dt_;
  for (std::size_t i = 0; i < line_.links.size(); ++i) {
    const Link& l = line_.links[i];
    if (l.law.rigid()) {
      force_[i] = 0.0;
      continue;
    }
    const double c = -line_.opening(i, u);
    const double rate = (line_.opening(i, u_old) - line_.opening(i, u)) * inv_dt;  // dc/dt, backward
    if (c > c_max_[i]) c_max_[i] = c;
    force_[i] = l.law.force(c, rate, c_max_[i]);
    if (force_[i] != 0.0) add_link_force(i, force_[i], r);
  }
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

std::unique_ptr<Scheme> make_line_scheme(const Case& c) {
  if (c.time.scheme == "central-difference") return std::make_unique<LineCentralDifference>(c, build_line(c));
  throw InputError(fmt::format("time.scheme = \"{}\" cannot run a line of bodies yet", c.time.scheme));
}

}  // namespace barimpact
