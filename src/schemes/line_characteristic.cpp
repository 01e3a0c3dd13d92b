#include "barimpact/schemes/line_characteristic.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "barimpact/case/line_builder.hpp"

namespace barimpact {

LineCharacteristic::LineCharacteristic(const Case& c, Line line) : LineScheme(c, std::move(line)) {
  const std::size_t n = line_.nodes();
  m_ = line_.lumped_mass();
  for (auto& l : levels_) l.assign(n, 0.0);
  port_of_.assign(n, none);
  // Interior nodes between two equal elements, no mass, not held: the stencil.
  auto uniform = [&](std::size_t j) {
    if (j == 0 || j + 1 >= n || line_.fixed(j) || line_.point_mass[j] != 0.0) return false;
    const Bond &a = line_.bonds[j - 1], &b = line_.bonds[j];
    return a.kind == BondKind::element && b.kind == BondKind::element && a.stiffness == b.stiffness && a.mass == b.mass;
  };
  for (std::size_t j = 0; j < n; ++j) {
    if (!uniform(j)) {
      port_of_[j] = ports_.size();
      ports_.push_back(make_port(j));
    } else if (!stretches_.empty() && stretches_.back().last == j) {
      ++stretches_.back().last;
    } else {
      stretches_.push_back({j, j + 1});
    }
  }
  impulse_.assign(line_.links.size(), 0.0);
  impulse_last_.assign(line_.links.size(), 0.0);
  connect_links();
}

LineCharacteristic::Port LineCharacteristic::make_port(std::size_t j) const {
  Port p;
  p.node = j;
  p.mass = line_.point_mass[j];
  auto add = [&](std::size_t bond, std::size_t neighbour) {
    const Bond& b = line_.bonds[bond];
    if (b.kind != BondKind::element) return;
    Side& s = p.side[static_cast<std::size_t>(p.sides++)];
    s.neighbour = neighbour;
    s.stiffness = b.stiffness;
    s.impedance = std::sqrt(b.stiffness * b.mass);  // (E A / h)(rho A h) = (A sqrt(E rho))^2
    p.impedance += s.impedance;
  };
  if (j > 0) add(j - 1, j - 1);
  if (j + 1 < line_.nodes()) add(j, j + 1);
  const End* e = j == line_.near.node ? &line_.near : j == line_.far.node ? &line_.far : nullptr;
  p.near = e == &line_.near;
  if (e != nullptr) {
    if (e->kind == EndKind::force) p.hold = Hold::forced;
    if (e->kind == EndKind::clamped) p.hold = Hold::clamped;
    if (e->kind == EndKind::velocity) p.hold = Hold::driven;
  }
  const bool held = p.hold == Hold::clamped || p.hold == Hold::driven;
  p.response = held ? 0.0 : dt_ / (2.0 * p.mass + p.impedance * dt_);  // (C3): d u^{n+1} / d J
  return p;
}

void LineCharacteristic::connect_links() {
  for (std::size_t i = 0; i < line_.links.size(); ++i) {
    const Link& l = line_.links[i];
    for (auto [face, sign] : {std::pair{l.a, -1.0}, std::pair{l.b, 1.0}}) {
      if (face == Link::ground) continue;
      Port& p = ports_[port_of_[face]];  // a link's faces end their bodies: always ports
      const std::size_t k = p.links[0] == none ? 0 : 1;
      p.links[k] = i;
      p.link_sign[k] = sign;
      coupled_ = coupled_ || k == 1;
    }
  }
}

double LineCharacteristic::step_integral(bool near, double t) const {
  // Simpson's rule over [t, t + dt]: exact for a force or velocity cubic in t.
  auto g = [&](double s) { return near ? near_value(s) : far_value(s); };
  return dt_ / 6.0 * (g(t) + 4.0 * g(t + 0.5 * dt_) + g(t + dt_));
}

void LineCharacteristic::arrive(Port& p, const double* u, bool first) {
  double drive = 0.0;
  for (int k = 0; k < p.sides; ++k) {
    Side& s = p.side[static_cast<std::size_t>(k)];
    if (first) {
      // d'Alembert from u0 split evenly at the port: the wave arriving at
      // t = dt is at the neighbour at t = 0, u0_nbr / 2 + (1 / 2c) int v0 over
      // the element (the trapezoid, exact for the P1 interpolant; dx / c = dt).
      s.in_next = 0.5 * u0_[s.neighbour] + 0.25 * dt_ * (v0_[p.node] + v0_[s.neighbour]);
    } else {
      s.in_next = u[s.neighbour] - s.out[0];  // (C1)
    }
    drive += 2.0 * s.impedance * (s.in_next - s.in);
  }
  p.drive = drive;
}

void LineCharacteristic::free_update(Port& p, const double* u, double* up, double t) {
  const std::size_t j = p.node;
  p.impulse[0] = p.impulse[1];
  switch (p.hold) {
    case Hold::clamped:
      up[j] = 0.0;
      return;
    case Hold::driven:
      up[j] = u[j] + step_integral(p.near, t);
      return;
    case Hold::forced:
      p.impulse[1] = step_integral(p.near, t);
      break;
    case Hold::free:
      break;
  }
  // (C3) solved for u^{n+1}: (m + Z dt / 2) du = m v dt + (dt / 2)(dq + J).
  const double load = p.drive + (p.hold == Hold::forced ? p.impulse[1] : 0.0);
  up[j] = u[j] + (dt_ * p.mass * p.velocity[1] + 0.5 * dt_ * load) / (p.mass + 0.5 * p.impedance * dt_);
}

void LineCharacteristic::settle_links(double* up) {
  std::fill(impulse_.begin(), impulse_.end(), 0.0);
  auto response = [&](std::size_t j) { return j == Link::ground ? 0.0 : ports_[port_of_[j]].response; };
  double scale = 0.0;
  for (int sweep = 0; sweep < 10000; ++sweep) {
    double moved = 0.0;
    for (std::size_t i = 0; i < line_.links.size(); ++i) {
      const Link& l = line_.links[i];
      const double wa = response(l.a), wb = response(l.b);
      if (wa + wb == 0.0) continue;  // both faces held or on the ground
      const double y = line_.opening(i, up);
      if (sweep == 0) scale = std::max(scale, std::abs(y));
      const double total = std::max(0.0, impulse_[i] - y / (wa + wb));  // I >= 0 closes y to 0
      const double d = total - impulse_[i];
      if (d == 0.0) continue;
      impulse_[i] = total;
      if (l.a != Link::ground) up[l.a] -= d * wa;
      if (l.b != Link::ground) up[l.b] += d * wb;
      moved = std::max(moved, std::abs(d) * (wa + wb));
    }
    if (!coupled_ || moved <= 1e-14 * scale) break;  // one pass is exact for links sharing no node
  }
}

double LineCharacteristic::link_impulse_on(const Port& p) const {
  double s = 0.0;
  for (std::size_t k = 0; k < 2; ++k)
    if (p.links[k] != none) s += p.link_sign[k] * impulse_[p.links[k]];
  return s;
}

void LineCharacteristic::depart(Port& p, const double* u, const double* up, double t) {
  const std::size_t j = p.node;
  const double du = up[j] - u[j];
  for (int k = 0; k < p.sides; ++k) {
    Side& s = p.side[static_cast<std::size_t>(k)];
    s.out = {s.out[1], up[j] - s.in_next};
    s.in = s.in_next;
  }
  const double before = p.velocity[1];
  double after = 0.0;
  if (p.hold == Hold::driven)
    after = p.near ? near_value(t + dt_) : far_value(t + dt_);
  else if (p.hold != Hold::clamped && p.mass > 0.0)
    after = 2.0 * du / dt_ - before;  // the trapezoidal rule of (C3)
  p.velocity = {before, after};
  // A held node's support: what (C3) lacks, m dv + Z du - dq minus the links' share.
  if (p.hold == Hold::clamped || p.hold == Hold::driven)
    p.impulse[1] = p.mass * (after - before) + p.impedance * du - p.drive - link_impulse_on(p);
}

void LineCharacteristic::uniform_rows(const double* __restrict um, const double* __restrict u,
                                      double* __restrict up) const {
  for (const Stretch& s : stretches_)
    for (std::size_t j = s.first; j < s.last; ++j) up[j] = u[j + 1] + u[j - 1] - um[j];
}

void LineCharacteristic::start_rows(double* up) const {
  // d'Alembert at t = dt for the P1 interpolants of u0 and v0 (c dt = h):
  // u(x_j, dt) = (u0_{j-1} + u0_{j+1}) / 2 + (1 / 2c) int_{x_{j-1}}^{x_{j+1}} v0.
  for (const Stretch& s : stretches_)
    for (std::size_t j = s.first; j < s.last; ++j)
      up[j] = 0.5 * (u0_[j - 1] + u0_[j + 1]) + 0.25 * dt_ * (v0_[j - 1] + 2.0 * v0_[j] + v0_[j + 1]);
}

void LineCharacteristic::start() {
  prev_ = levels_[2].data();
  cur_ = levels_[0].data();
  next_ = levels_[1].data();
  n_ = 0;
  std::copy(u0_.begin(), u0_.end(), prev_);
  std::copy(u0_.begin(), u0_.end(), cur_);
  for (Port& p : ports_) {
    const std::size_t j = p.node;
    for (Side& s : p.side) s.in = s.out[0] = s.out[1] = 0.5 * u0_[j];  // any split will do: take half each
    p.velocity = {v0_[j], v0_[j]};
    p.impulse = {0.0, 0.0};
  }
  std::fill(impulse_.begin(), impulse_.end(), 0.0);
  start_rows(next_);
  for (Port& p : ports_) arrive(p, cur_, true);
  for (Port& p : ports_) free_update(p, cur_, next_, 0.0);
  settle_links(next_);
  for (Port& p : ports_) depart(p, cur_, next_, 0.0);
  std::fill(impulse_last_.begin(), impulse_last_.end(), 0.0);
  report_forces(true);
  book_first_half_step();
}

void LineCharacteristic::advance() {
  const long long m = n_ + 1;
  const double t = static_cast<double>(m) * dt_;
  const double* um = cur_;
  const double* u = next_;
  double* up = prev_;
  for (Port& p : ports_) arrive(p, u, false);
  uniform_rows(um, u, up);
  for (Port& p : ports_) free_update(p, u, up, t);
  std::copy(impulse_.begin(), impulse_.end(), impulse_last_.begin());
  settle_links(up);
  for (Port& p : ports_) depart(p, u, up, t);
  prev_ = cur_;
  cur_ = next_;
  next_ = up;
  n_ = m;
  report_forces(false);
  double dw = 0.0, dc = 0.0;
  book_budget(dw, dc);
  budget_.book(dw, 0.0, dc);
}

double LineCharacteristic::support(const Port& p) const {
  const std::size_t j = p.node;
  double r = m_[j] * (next_[j] - 2.0 * cur_[j] + prev_[j]) / (dt_ * dt_);
  for (int k = 0; k < p.sides; ++k) {
    const Side& s = p.side[static_cast<std::size_t>(k)];
    r -= s.stiffness * (cur_[s.neighbour] - cur_[j]);
  }
  for (std::size_t k = 0; k < 2; ++k)
    if (p.links[k] != none) r -= p.link_sign[k] * force_[p.links[k]];
  return r;
}

void LineCharacteristic::report_forces(bool first) {
  for (std::size_t i = 0; i < force_.size(); ++i) force_[i] = (impulse_last_[i] + impulse_[i]) / (2.0 * dt_);
  const double t = time();
  near_force_ = line_.near.kind == EndKind::force ? near_value(t) : 0.0;
  far_force_ = line_.far.kind == EndKind::force ? -far_value(t) : 0.0;
  for (Port& p : ports_) {
    if (p.hold != Hold::clamped && p.hold != Hold::driven) continue;
    // At t = 0 the mean force of the first step; later the node's equation.
    p.support = first ? p.impulse[1] / dt_ : support(p);
    (p.near ? near_force_ : far_force_) = p.near ? p.support : -p.support;
  }
  if (!line_.links.empty() && line_.links.front().name == "near_end") near_force_ = force_.front();
  if (!line_.links.empty() && line_.links.back().name == "far_end") far_force_ = force_.back();
}

// The first half step's share: each impulse of (0, dt) over dt, against the
// mean of the rate at t = 0 and the rate over (0, dt).
void LineCharacteristic::book_first_half_step() {
  double power = 0.0, contact = 0.0;
  for (const Port& p : ports_) {
    if (p.hold == Hold::free) continue;
    const std::size_t j = p.node;
    power += p.impulse[1] / dt_ * 0.5 * (v0_[j] + (next_[j] - cur_[j]) / dt_);
  }
  for (std::size_t i = 0; i < line_.links.size(); ++i) {
    const double rate = line_.links[i].gap - line_.opening(i, v0_.data());  // dc/dt at t = 0
    const double over = (line_.opening(i, cur_) - line_.opening(i, next_)) / dt_;
    contact += impulse_[i] / dt_ * 0.5 * (rate + over);
  }
  budget_.start(dt_, power, 0.0, contact);
}

// Level n's increments: each external force at t_n, (J^{n-1} + J^n) / (2 dt)
// or the support's, tested with (u^{n+1} - u^{n-1}) / 2.
void LineCharacteristic::book_budget(double& dw, double& dc) const {
  for (const Port& p : ports_) {
    if (p.hold == Hold::free) continue;
    const std::size_t j = p.node;
    const double force = p.hold == Hold::forced ? (p.impulse[0] + p.impulse[1]) / (2.0 * dt_) : p.support;
    dw += force * 0.5 * (next_[j] - prev_[j]);
  }
  for (std::size_t i = 0; i < line_.links.size(); ++i)
    dc += force_[i] * 0.5 * (line_.opening(i, prev_) - line_.opening(i, next_));
}

double LineCharacteristic::velocity_at(std::size_t j) const {
  if (n_ == 0) return v0_[j];
  const std::size_t k = port_of_[j];
  if (k != none && ports_[k].mass > 0.0 && (ports_[k].hold == Hold::free || ports_[k].hold == Hold::forced))
    return ports_[k].velocity[0];
  return (next_[j] - prev_[j]) / (2.0 * dt_);
}

double LineCharacteristic::half_step(const double* a, const double* b, double& kinetic) const {
  kinetic = 0.0;
  for (std::size_t j = 0; j < line_.nodes(); ++j) {
    const double w = (b[j] - a[j]) / dt_;
    kinetic += 0.5 * m_[j] * w * w;
  }
  return 0.5 * line_.bond_form(BondKind::element, false, a, b);
}

Energies LineCharacteristic::energies() const {
  Energies e;
  if (n_ == 0) {
    for (std::size_t j = 0; j < line_.nodes(); ++j) e.kinetic += 0.5 * m_[j] * v0_[j] * v0_[j];
    e.strain = 0.5 * line_.bond_form(BondKind::element, false, u0_.data(), u0_.data());
    return e;
  }
  double k1 = 0.0, k2 = 0.0;
  const double s1 = half_step(prev_, cur_, k1), s2 = half_step(cur_, next_, k2);
  e.kinetic = 0.5 * (k1 + k2);
  e.strain = 0.5 * (s1 + s2);
  e.work = budget_.work();
  e.contact = budget_.contact();
  return e;
}

bool LineCharacteristic::finite() const {
  const std::size_t last = line_.nodes() - 1;
  return std::isfinite(cur_[0]) && std::isfinite(cur_[last]) && std::isfinite(next_[0]) && std::isfinite(next_[last]) &&
         std::isfinite(budget_.work_half) && std::isfinite(budget_.contact_half);
}

namespace {

// A bar body's element transit time h / c = sqrt(m_j / k_j) (its elements alike).
struct BarTransit {
  std::size_t body;
  double transit;
};

std::vector<BarTransit> transits(const Line& line) {
  std::vector<BarTransit> out;
  for (std::size_t i = 0; i < line.bodies.size(); ++i) {
    const BodyRange& r = line.bodies[i];
    if (r.is_mass || r.last == r.first) continue;
    const Bond& b = line.bonds[r.first];
    out.push_back({i, std::sqrt(b.mass / b.stiffness)});
  }
  return out;
}

bool same_step(double a, double b) {
  return std::abs(a - b) <= 1e-9 * b;
}

std::optional<SchemeMisfit> refuse(std::string rule) {
  return SchemeMisfit{"scheme", std::move(rule)};
}

constexpr const char* scheme = "= \"characteristic\"";

// What the characteristic relations cannot carry exactly: a body force or
// gravity (the invariants then change along the characteristics), viscosity
// (dispersion), springs and penalty laws (no transit time: a stiff ODE).
std::optional<SchemeMisfit> law_misfit(const Line& line) {
  if (!Expression(line.body_force).is_zero() || line.gravity != 0.0)
    return refuse(
        fmt::format("{} cannot run a body force or gravity (load.body_force = \"{}\", load.gravity = {}); "
                    "schemes that can: central-difference, newmark, moreau-jean, paoli-schatzman, "
                    "mass-redistribution",
                    scheme, line.body_force, line.gravity));
  for (const Bond& b : line.bonds) {
    if (b.kind == BondKind::element && b.viscosity > 0.0)
      return refuse(
          fmt::format("{} cannot run the viscous body \"{}\" (elastic bars only); schemes that can: "
                      "central-difference, newmark, moreau-jean, paoli-schatzman",
                      scheme, line.bodies[b.body].name));
    if (b.kind == BondKind::spring)
      return refuse(
          fmt::format("{} cannot run the spring joint between \"{}\" and \"{}\"; schemes that can: "
                      "central-difference, newmark, moreau-jean, paoli-schatzman, mass-redistribution",
                      scheme, line.bodies[b.body - 1].name, line.bodies[b.body].name));
  }
  for (const Link& l : line.links)
    if (!l.law.rigid())
      return refuse(
          fmt::format("{} cannot run the {} link \"{}\" (rigid links only); schemes that can: "
                      "central-difference, newmark, paoli-schatzman",
                      scheme, to_string(l.law.kind), l.name));
  return std::nullopt;
}

std::optional<SchemeMisfit> transit_misfit(const Case& c, const Line& line) {
  const auto bars = transits(line);
  if (bars.empty())
    return refuse(fmt::format("{} needs a bar: its step is the bars' element transit time h/c", scheme));
  const double dt = bars.front().transit;
  const std::string& first = line.bodies[bars.front().body].name;
  for (const auto& b : bars) {
    if (same_step(b.transit, dt)) continue;
    const BodyRange& r = line.bodies[b.body];
    const double fit = static_cast<double>(r.last - r.first) * b.transit / dt;  // elements giving h/c = dt
    const std::string hint =
        std::abs(fit - std::round(fit)) <= 1e-6 * fit
            ? fmt::format("give \"{}\" {} elements", r.name, std::round(fit))
            : fmt::format("no whole number of elements of \"{}\" does: L / (c dt) = {:.6g}", r.name, fit);
    return refuse(
        fmt::format("{} steps every element in one transit, so every bar's h/c must be equal: body \"{}\" "
                    "has {:.6g}, body \"{}\" {:.6g} ({})",
                    scheme, r.name, b.transit, first, dt, hint));
  }
  if (!same_step(c.time.step, dt))
    return SchemeMisfit{"step", fmt::format("= {} is not the line's element transit time h/c = {} (characteristic "
                                            "takes one transit per step; give that value)",
                                            c.time.step, dt)};
  return std::nullopt;
}

}  // namespace

std::optional<double> line_characteristic_step(const Line& line) {
  const auto bars = transits(line);
  if (bars.empty()) return std::nullopt;
  for (const auto& b : bars)
    if (!same_step(b.transit, bars.front().transit)) return std::nullopt;
  return bars.front().transit;
}

std::optional<SchemeMisfit> characteristic_line_misfit(const Case& c, const Line& line) {
  if (auto m = law_misfit(line)) return m;
  return transit_misfit(c, line);
}

}  // namespace barimpact
