#include "barimpact/schemes/line_central_difference.hpp"

#include "barimpact/model/setup_polling.hpp"

#include <cmath>

namespace barimpact {

LineCentralDifference::LineCentralDifference(const Case& c, Line line)
    : LineScheme(c, std::move(line)), plastic_(line_) {
  const std::size_t n = line_.nodes();
  for (const auto& b : line_.bonds) {
    k_.push_back(b.stiffness);
    c_.push_back(b.viscosity);
    viscous_ = viscous_ || b.viscosity > 0.0;
  }
  poll_setup();  // each phase is line-sized: a study's case polls its interrupt between them
  m_ = line_.lumped_mass();
  inv_m_.resize(n);
  for (std::size_t j = 0; j < n; ++j) inv_m_[j] = line_.fixed(j) ? 0.0 : 1.0 / m_[j];
  r_.assign(n, 0.0);
  rigid_.assign(line_.links.size(), 0.0);
  for (std::size_t i = 0; i < line_.links.size(); ++i)
    if (line_.links[i].law.rigid()) rigid_links_.push_back(i);
  near_held_ = line_.near.kind == EndKind::clamped || line_.near.kind == EndKind::velocity;
  far_held_ = line_.far.kind == EndKind::clamped || line_.far.kind == EndKind::velocity;
  held_ends_ = near_held_ || far_held_;
  poll_setup();
  for (auto& l : levels_) l.assign(n, 0.0);
  // Uniform interior nodes: both bonds the same element of one body, no point mass, not held.
  auto uniform = [&](std::size_t j) {
    if (j == 0 || j + 1 >= n || line_.fixed(j) || line_.point_mass[j] != 0.0) return false;
    const Bond &a = line_.bonds[j - 1], &b = line_.bonds[j];
    return a.kind == BondKind::element && b.kind == BondKind::element && a.stiffness == b.stiffness &&
           a.viscosity == b.viscosity && a.mass == b.mass && a.body == b.body;
  };
  auto plastic = [&](const Bond& b) { return b.body < line_.plasticity.size() && line_.plasticity[b.body]; };
  const Shaft& shaft = line_.shaft;
  auto soil = [&](std::size_t j) {
    if (shaft.empty() || shaft.ultimate[j] == 0.0) return Soil::none;
    return shaft.viscous[j] > 0.0 ? Soil::viscous : Soil::smith;
  };
  for (std::size_t j = 0; j < n; ++j) {
    if (!uniform(j)) {
      special_.push_back(j);
      if (soil(j) != Soil::none) special_soil_.push_back(j);
      continue;
    }
    const Bond& b = line_.bonds[j];
    if (!stretches_.empty() && stretches_.back().last == j && stretches_.back().k == b.stiffness &&
        stretches_.back().c == b.viscosity && stretches_.back().inv_m == inv_m_[j] &&
        stretches_.back().plastic == plastic(b) && stretches_.back().soil == soil(j))
      ++stretches_.back().last;
    else
      stretches_.push_back({j, j + 1, b.stiffness, b.viscosity, inv_m_[j], b.axial, plastic(b), soil(j)});
  }
  if (!shaft.empty()) {
    slip_.assign(n, 0.0);
    soil_damping_.assign(n, 0.0);
  }
}

inline double LineCentralDifference::shaft_force(std::size_t j, const double* um, const double* u) {
  const Shaft& s = line_.shaft;
  const double w = -u[j];
  const double slip = smith_slip(slip_[j], w, s.quake[j]);
  slip_work_ += s.ultimate[j] * std::abs(slip - slip_[j]);
  slip_[j] = slip;
  const double rs = s.stiffness[j] * (w - slip);
  const double rd = (s.smith[j] * std::abs(rs) + s.viscous[j]) * (um[j] - u[j]) * inv_dt_;
  soil_damping_[j] = rd;
  return rs + rd;
}

inline double LineCentralDifference::row_force(const double* um, const double* u, std::size_t j) const {
  const std::size_t n = line_.nodes();
  const double inv_dt = inv_dt_;
  double r = load_zero_ ? 0.0 : load_[j];
  const double* p = plastic_.active() ? plastic_.next() : nullptr;  // level n's, read before it moves on
  auto tension = [&](std::size_t b) {
    double t = k_[b] * (u[b + 1] - u[b]);
    if (viscous_) t += c_[b] * ((u[b + 1] - u[b]) - (um[b + 1] - um[b])) * inv_dt;
    if (p != nullptr) t -= line_.bonds[b].axial * p[b];
    return t;
  };
  if (j + 1 < n) r += tension(j);
  if (j > 0) r -= tension(j - 1);
  return r;
}

template <bool viscous, bool loaded>
void LineCentralDifference::uniform_rows(const double* um, const double* u, double* up) {
  const bool yielded = !plastic_.pristine();  // before the first yield every p is 0: the elastic stencil
  for (const Stretch& s : stretches_) {
    const bool p = s.plastic && yielded;
    switch (s.soil) {
      case Soil::none:
        p ? stretch_rows<viscous, loaded, true, Soil::none>(s, um, u, up)
          : stretch_rows<viscous, loaded, false, Soil::none>(s, um, u, up);
        break;
      case Soil::smith:
        p ? stretch_rows<viscous, loaded, true, Soil::smith>(s, um, u, up)
          : stretch_rows<viscous, loaded, false, Soil::smith>(s, um, u, up);
        break;
      case Soil::viscous:
        p ? stretch_rows<viscous, loaded, true, Soil::viscous>(s, um, u, up)
          : stretch_rows<viscous, loaded, false, Soil::viscous>(s, um, u, up);
        break;
    }
  }
}

template <bool viscous, bool loaded, bool plastic, LineCentralDifference::Soil soil_law>
void LineCentralDifference::stretch_rows(const Stretch& s, const double* __restrict um, const double* __restrict u,
                                         double* __restrict up) {
  const double dt2 = dt_ * dt_, inv_dt = inv_dt_;
  const double* __restrict f = load_.data();
  const double* __restrict p = plastic ? plastic_.next() : nullptr;
  const double k = s.k, c = s.c * inv_dt, scale = dt2 * s.inv_m, axial = s.axial;
  constexpr bool soil = soil_law != Soil::none;
  // Smith's shaft, as shaft_force() (fused: the node's u^{n+1} is final here).
  double* __restrict slip = soil ? slip_.data() : nullptr;
  const double* __restrict quake = soil ? line_.shaft.quake.data() : nullptr;
  const double* __restrict ru = soil ? line_.shaft.ultimate.data() : nullptr;
  const double* __restrict ks = soil ? line_.shaft.stiffness.data() : nullptr;
  const double* __restrict js = soil ? line_.shaft.smith.data() : nullptr;
  const double* __restrict jv = soil ? line_.shaft.viscous.data() : nullptr;
  double slip_work = 0.0, damping_work = 0.0;
  for (std::size_t j = s.first; j < s.last; ++j) {
    double r = -k * (2.0 * u[j] - u[j - 1] - u[j + 1]);
    if constexpr (loaded) r += f[j];
    if constexpr (viscous) r -= c * (2.0 * (u[j] - um[j]) - (u[j - 1] - um[j - 1]) - (u[j + 1] - um[j + 1]));
    if constexpr (plastic) r += axial * (p[j - 1] - p[j]);
    double rd = 0.0;
    if constexpr (soil) {
      const double w = -u[j];
      const double sj = smith_slip(slip[j], w, quake[j]);
      slip_work += ru[j] * std::abs(sj - slip[j]);
      slip[j] = sj;
      const double rs = ks[j] * (w - sj);
      // J |R_s| or J R_u (the other is 0 on the node: shaft_force's sum, the same bits)
      rd = (soil_law == Soil::smith ? js[j] * std::abs(rs) : jv[j]) * (um[j] - u[j]) * inv_dt;
      r += rs + rd;
    }
    up[j] = 2.0 * u[j] - um[j] + scale * r;
    if constexpr (soil) damping_work += rd * 0.5 * (um[j] - up[j]);  // R_d^n (w^{n+1} - w^{n-1}) / 2
  }
  if constexpr (soil) {
    slip_work_ += slip_work;
    soil_damping_work_ += damping_work;
  }
}

inline void LineCentralDifference::advance_levels(const double* um, const double* u, double* up, double t) {
  load_at(t);
  for (std::size_t j : special_) r_[j] = row_force(um, u, j);
  for (std::size_t j : special_soil_) r_[j] += shaft_force(j, um, u);
  soil_damping_work_ = 0.0;                            // the stretches' share of this level, added as they go
  if (has_penalty_) penalty_forces(u, um, r_.data());  // links join special nodes only
  if (line_.near.kind == EndKind::force) r_[line_.near.node] += near_value(t);
  if (line_.far.kind == EndKind::force) r_[line_.far.node] += far_value(t);
  const double dt2 = dt_ * dt_;
  for (std::size_t j : special_) up[j] = 2.0 * u[j] - um[j] + dt2 * r_[j] * inv_m_[j];
  if (viscous_)
    load_zero_ ? uniform_rows<true, false>(um, u, up) : uniform_rows<true, true>(um, u, up);
  else
    load_zero_ ? uniform_rows<false, false>(um, u, up) : uniform_rows<false, true>(um, u, up);
}

void LineCentralDifference::predict(const double* um, const double* u, double* up, double t, bool taylor) {
  const std::size_t n = line_.nodes();
  load_at(t);
  double* __restrict r = r_.data();
  for (std::size_t j = 0; j < n; ++j) r[j] = load_zero_ ? 0.0 : load_[j];
  const double inv_dt = 1.0 / dt_;
  const double* p = plastic_.active() ? plastic_.next() : nullptr;
  for (std::size_t j = 0; j + 1 < n; ++j) {
    double tension = k_[j] * (u[j + 1] - u[j]);
    if (viscous_) tension += c_[j] * ((u[j + 1] - u[j]) - (um[j + 1] - um[j])) * inv_dt;
    if (p != nullptr) tension -= line_.bonds[j].axial * p[j];
    r[j] += tension;
    r[j + 1] -= tension;
  }
  if (has_penalty_) penalty_forces(u, um, r);
  for (std::size_t j : line_.shaft.nodes) r[j] += shaft_force(j, um, u);
  if (line_.near.kind == EndKind::force) r[line_.near.node] += near_value(t);
  if (line_.far.kind == EndKind::force) r[line_.far.node] += far_value(t);
  const double dt2 = dt_ * dt_;
  const double* __restrict inv_m = inv_m_.data();
  if (taylor) {
    for (std::size_t j = 0; j < n; ++j) up[j] = u[j] + dt_ * v0_[j] + 0.5 * dt2 * r[j] * inv_m[j];
  } else {
    for (std::size_t j = 0; j < n; ++j) up[j] = 2.0 * u[j] - um[j] + dt2 * r[j] * inv_m[j];
  }
}

void LineCentralDifference::hold_ends(const double* u, double* up, double t) const {
  if (!held_ends_) return;
  for (const End* e : {&line_.near, &line_.far}) {
    if (e->kind == EndKind::clamped) up[e->node] = 0.0;
    if (e->kind == EndKind::velocity)
      up[e->node] = u[e->node] + dt_ * (e == &line_.near ? near_value(t + 0.5 * dt_) : far_value(t + 0.5 * dt_));
  }
}

inline void LineCentralDifference::project(double* up, double force_scale) {
  if (!has_rigid_) return;
  for (std::size_t i : rigid_links_) rigid_[i] = 0.0;  // the others' stay 0 (not std::fill: a call to memset)
  const double scale = inv_dt2_;
  for (int sweep = 0; sweep < 1000; ++sweep) {
    double moved = 0.0;
    for (std::size_t i : rigid_links_) {
      const Link& l = line_.links[i];
      const double wa = l.a == Link::ground ? 0.0 : inv_m_[l.a];
      const double wb = l.b == Link::ground ? 0.0 : inv_m_[l.b];
      if (wa + wb == 0.0) continue;
      const double y = line_.opening(i, up);
      // No impulse yet and open: lambda is max(0, -y / w) = 0 (no division:
      // the common case of a link apart costs a few ns less).
      if (rigid_[i] == 0.0 && !(y < 0.0)) continue;
      const double lambda = std::max(0.0, rigid_[i] - y / (wa + wb));  // accumulated impulse, kept >= 0
      const double d = lambda - rigid_[i];
      if (d == 0.0) continue;
      rigid_[i] = lambda;
      if (l.a != Link::ground) up[l.a] -= d * wa;
      if (l.b != Link::ground) up[l.b] += d * wb;
      moved = std::max(moved, std::abs(d) * (wa + wb));
    }
    if (moved <= 1e-15 * (1.0 + std::abs(up[0]))) break;
  }
  for (std::size_t i : rigid_links_) force_[i] = rigid_[i] = rigid_[i] * scale * force_scale;
}

inline void LineCentralDifference::end_forces(const double* um, const double* u, const double* up, double t,
                                              double scale) {
  const double inv_dt2 = inv_dt2_;
  auto support = [&](const End& e) {
    const std::size_t j = e.node;
    return scale * m_[j] * (up[j] - 2.0 * u[j] + um[j]) * inv_dt2 - r_[j];
  };
  near_support_ = near_held_ ? support(line_.near) : 0.0;
  far_support_ = far_held_ ? support(line_.far) : 0.0;
  near_force_ = near_link_ ? force_.front() : line_.near.kind == EndKind::force ? near_value(t) : near_support_;
  far_force_ = far_link_ ? force_.back() : line_.far.kind == EndKind::force ? -far_value(t) : -far_support_;
}

void LineCentralDifference::start() {
  const std::size_t n = line_.nodes();
  prev_ = levels_[2].data();
  cur_ = levels_[0].data();
  next_ = levels_[1].data();
  n_ = 0;
  std::fill(c_max_.begin(), c_max_.end(), 0.0);
  std::fill(slip_.begin(), slip_.end(), 0.0);
  slip_work_ = soil_damping_work_ = 0.0;
  if (resume_) {  // the previous blow's rest: its displacements, slips and locked-in forces
    u0_ = resume_->u;
    if (!slip_.empty()) slip_ = resume_->shaft_slip;
    c_max_ = resume_->c_max;
  }
  // u^1 = u^0 + dt v^0 + dt^2/2 a^0 (second order, exact for a rigid motion);
  // rates at t = 0 from v^0 through a level u^0 - dt v^0.
  std::vector<double> before(n);
  for (std::size_t j = 0; j < n; ++j) {
    cur_[j] = prev_[j] = u0_[j];
    before[j] = u0_[j] - dt_ * v0_[j];
  }
  if (plastic_.active()) plastic_.start(cur_);
  predict(before.data(), cur_, next_, 0.0, true);
  hold_ends(cur_, next_, 0.0);
  // The Taylor step moves by dt^2/2 a^0: a correction's force is twice a full step's.
  project(next_, 2.0);
  end_forces(before.data(), cur_, next_, 0.0, 2.0);
  if (plastic_.active()) plastic_.advance(cur_, next_, true);
  // The first half step's share of the budget, dt/2 times the rates at t = 0.
  double power = 0.0, viscous = 0.0, contact = 0.0;
  for (std::size_t j = 0; j < n; ++j) power += (load_zero_ ? 0.0 : load_[j]) * v0_[j];
  power += near_support_ * v0_[line_.near.node] + far_support_ * v0_[line_.far.node];
  if (line_.near.kind == EndKind::force) power += near_value(0.0) * v0_[line_.near.node];
  if (line_.far.kind == EndKind::force) power += far_value(0.0) * v0_[line_.far.node];
  for (std::size_t j = 0; j + 1 < n; ++j) viscous += c_[j] * (v0_[j + 1] - v0_[j]) * (v0_[j + 1] - v0_[j]);
  for (std::size_t i = 0; i < line_.links.size(); ++i) {
    const Link& l = line_.links[i];
    const double rate = -line_.opening(i, v0_.data()) + l.gap;  // dc/dt
    // A rigid link's impulse against the mean of the rates at t = 0 and over
    // (0, dt): the Taylor step's own identity (twice the half step's share).
    if (l.law.rigid()) contact += 0.5 * force_[i] * (rate + (line_.opening(i, cur_) - line_.opening(i, next_)) / dt_);
    book_link_damping(i, -line_.opening(i, cur_), rate, power, viscous, contact);
  }
  for (std::size_t j : line_.shaft.nodes) contact -= soil_damping_[j] * v0_[j];  // R_d dw/dt, w = -u
  budget_.start(dt_, power, viscous, contact);
}

// Level m's increments, each force at t_m tested with (u^{m+1} - u^{m-1}) / 2.
inline void LineCentralDifference::book_budget(const double* um, const double* u, const double* up) {
  // Booked here, the sums kept in registers: handed back through memory they
  // cost a failed store forwarding (two 8-byte stores, one 16-byte load).
  double dw = 0.0, dd = 0.0, dc = soil_damping_work_;
  const std::size_t n = line_.nodes();
  if (!load_zero_)
    for (std::size_t j = 0; j < n; ++j) dw += load_[j] * 0.5 * (up[j] - um[j]);
  const double t = time();
  auto moved = [&](std::size_t j) { return 0.5 * (up[j] - um[j]); };
  dw += near_support_ * moved(line_.near.node) + far_support_ * moved(line_.far.node);
  if (line_.near.kind == EndKind::force) dw += near_value(t) * moved(line_.near.node);
  if (line_.far.kind == EndKind::force) dw += far_value(t) * moved(line_.far.node);
  if (viscous_) {
    const double inv_dt = inv_dt_;
    for (std::size_t j = 0; j + 1 < n; ++j)
      dd += c_[j] * ((u[j + 1] - u[j]) - (um[j + 1] - um[j])) * inv_dt * 0.5 *
            ((up[j + 1] - up[j]) - (um[j + 1] - um[j]));
  }
  book_link_work(um, u, up, dw, dd, dc);
  for (std::size_t j : special_soil_) dc += soil_damping_[j] * 0.5 * (um[j] - up[j]);
  budget_.book(dw, dd, dc);
}

void LineCentralDifference::advance() {
  const long long m = n_ + 1;
  const double t = static_cast<double>(m) * dt_;
  const double* um = cur_;
  const double* u = next_;
  double* up = prev_;
  advance_levels(um, u, up, t);
  if (held_ends_) hold_ends(u, up, t);  // the tests here: a short line's step is a few dozen ns
  if (has_rigid_) project(up, 1.0);
  end_forces(um, u, up, t, 1.0);
  if (plastic_.active()) plastic_.advance(u, up);
  prev_ = cur_;
  cur_ = next_;
  next_ = up;
  n_ = m;
  book_budget(prev_, cur_, next_);
}

double LineCentralDifference::half_step(const double* a, const double* b, BondKind kind, double& kinetic) const {
  kinetic = 0.0;
  for (std::size_t j = 0; j < line_.nodes(); ++j) {
    const double w = (b[j] - a[j]) / dt_;
    kinetic += 0.5 * m_[j] * w * w;
  }
  return 0.5 * line_.bond_form(kind, false, a, b);
}

Energies LineCentralDifference::energies() const {
  Energies e;
  e.obstacle = link_energy(cur_);
  for (std::size_t j : line_.shaft.nodes) {  // Smith's shaft springs at u^n and s^n
    const double e_j = -cur_[j] - slip_[j];
    e.obstacle += 0.5 * line_.shaft.stiffness[j] * e_j * e_j;
  }
  if (n_ == 0) {
    e.contact = slip_work_;  // what level 0 slipped (the soil penetrated past its quake at t = 0)
    for (std::size_t j = 0; j < line_.nodes(); ++j) e.kinetic += 0.5 * m_[j] * v0_[j] * v0_[j];
    e.strain = 0.5 * line_.bond_form(BondKind::element, false, u0_.data(), u0_.data());
    if (plastic_.active()) e.strain += plastic_.strain_energy(u0_.data());
    e.obstacle += 0.5 * line_.bond_form(BondKind::spring, false, u0_.data(), u0_.data());
    return e;
  }
  double k1 = 0, k2 = 0;
  const double s1 = half_step(prev_, cur_, BondKind::element, k1), s2 = half_step(cur_, next_, BondKind::element, k2);
  e.kinetic = 0.5 * (k1 + k2);
  e.strain = 0.5 * (s1 + s2);
  if (plastic_.active()) {
    e.strain += plastic_.strain_energy(prev_, cur_, next_);
    e.plastic = plastic_.work();
  }
  e.obstacle += 0.25 * (line_.bond_form(BondKind::spring, false, prev_, cur_) +
                        line_.bond_form(BondKind::spring, false, cur_, next_));
  e.work = budget_.work();
  e.dissipation = budget_.dissipation();
  e.contact = budget_.contact() + link_hysteresis() + slip_work_;
  return e;
}

LineScheme::SoilRest LineCentralDifference::soil_rest() const {
  SoilRest r;
  r.u.assign(cur_, cur_ + line_.nodes());
  r.shaft_slip = slip_.empty() ? std::vector<double>(line_.nodes(), 0.0) : slip_;
  r.c_max = c_max_;
  return r;
}

double LineCentralDifference::soil_slip_work() const {
  double d = slip_work_;
  for (std::size_t i = 0; i < line_.links.size(); ++i)
    if (line_.links[i].law.kind == LawKind::smith) d += line_.links[i].law.hysteresis(c_max_[i]);
  return d;
}

bool LineCentralDifference::finite() const {
  const std::size_t last = line_.nodes() - 1;
  return std::isfinite(cur_[0]) && std::isfinite(cur_[last]) && std::isfinite(next_[0]) && std::isfinite(next_[last]) &&
         std::isfinite(budget_.work_half) && std::isfinite(budget_.dissipation_half);
}

}  // namespace barimpact
