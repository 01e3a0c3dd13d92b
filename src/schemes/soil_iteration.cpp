#include "barimpact/schemes/soil_iteration.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace barimpact {

SoilIteration::SoilIteration(const Line& line, const Tridiagonal& a, const std::vector<std::size_t>& held, double c,
                             double r)
    : held_(held), c_(c), r_(r) {
  double capacity = 0.0;
  for (std::size_t i = 0; i < line.links.size(); ++i) {
    const Link& l = line.links[i];
    if (l.law.kind != LawKind::smith) continue;  // a near-end law (case.cpp): a = ground, b = node 0
    const SoilSpring& s = l.law.soil;
    const bool smith = s.damping_law == DampingLaw::smith;
    points_.push_back({l.b, true, s.ultimate, s.quake, s.stiffness(), smith ? s.damping : 0.0,
                       smith ? 0.0 : s.damping * s.ultimate, l.gap});
    toe_link_ = i;
    capacity += s.ultimate;
  }
  const Shaft& shaft = line.shaft;
  for (std::size_t j : shaft.nodes) {
    points_.push_back(
        {j, false, shaft.ultimate[j], shaft.quake[j], shaft.stiffness[j], shaft.smith[j], shaft.viscous[j], 0.0});
    capacity += shaft.ultimate[j];
  }
  tolerance_ = 1e-10 * capacity;
  for (auto* x : {&state_, &force_, &damping_, &iterate_, &trial_, &trial_damping_, &trial_state_, &tangent_, &spring_,
                  &spring_old_, &dashpot_, &state_reported_, &trial_spring_, &trial_dashpot_})
    x->assign(points_.size(), 0.0);
  if (points_.empty()) return;  // no soil: its matrix and solve (line-sized) are never used
  a_ = a;
  for (auto* x : {&diag_, &du_, &toe_du_}) x->assign(a.size(), 0.0);
  off_.assign(a.off.size(), 0.0);
}

// The penetration w into the soil is -u (the toe's compression -(u + gap)),
// its rate -v. A side spring slips both ways, s' = clamp(s, w - q, w + q),
// and pushes back k (w - s'); the toe keeps c_max (slip (c_max - q)^+) and
// never pulls (contact_law.hpp). The tangent is -d force / d u with
// dv / du = r: the spring's k while elastic, and the damping's
// d/du (J |R_s| dw/dt) = J sign(R_s) k_el dw/dt + r J |R_s| (Smith's) or
// r J R_u (viscous); a clipped toe has none.
void SoilIteration::use_levels(Levels w) {
  levels_ = true;
  weights_ = w;
}

SoilIteration::Resistance SoilIteration::law_at(std::size_t i, double u, double v) const {
  const Point& p = points_[i];
  Resistance out;
  const double w = p.toe ? -(u + p.gap) : -u, rate = -v;
  double r = 0.0, k_el = 0.0;
  bool in_soil = true;  // the toe below its slipped position (a side spring always)
  if (p.toe) {
    out.state = std::max(state_[i], w);
    const double slip = std::max(0.0, out.state - p.quake);
    in_soil = w > slip;
    if (in_soil) {
      r = std::min(p.ultimate, p.stiffness * (w - slip));
      k_el = w < state_[i] || w <= p.quake ? p.stiffness : 0.0;  // below c_max, or not yet yielded
    }
  } else {
    out.state = smith_slip(state_[i], w, p.quake);
    r = p.stiffness * (w - out.state);
    k_el = out.state == state_[i] ? p.stiffness : 0.0;
  }
  const double eta = p.smith > 0.0 ? p.smith * std::abs(r) : p.viscous;  // the dashpot J |R_s| or J R_u
  double d = eta * rate, dd_dw = p.smith > 0.0 ? p.smith * (r < 0.0 ? -k_el : k_el) * rate : 0.0;
  if (!in_soil) d = dd_dw = 0.0;  // above its slipped position: no damping
  out.spring = r;
  out.dashpot = in_soil ? eta : 0.0;
  out.stiffness = k_el;
  out.force = r + d;
  out.damping = d;
  out.tangent = std::max(0.0, k_el + dd_dw + r_ * eta);
  if (p.toe && out.force < 0.0) {  // the toe never pulls
    out.force = 0.0;
    out.damping = -r;
    out.tangent = 0.0;
  }
  return out;
}

// The three-level form's Phi^m at u^{m+1} = u, v = (u^{m+1} - u^{m-1}) / (2 dt):
// the spring's R(u) and state as the law's, level m's dashpot fixed.
SoilIteration::Resistance SoilIteration::level_at(std::size_t i, double u, double v) const {
  Resistance out = law_at(i, u, 0.0);  // at rest: the spring alone, its tangent, state and dashpot
  const double k_el = out.stiffness;
  const double spring = weights_.new_level * out.spring + weights_.current * spring_[i] + weights_.old * spring_old_[i];
  out.damping = dashpot_[i] * -v;
  out.force = spring + out.damping;
  out.tangent = weights_.new_level * k_el + r_ * dashpot_[i];
  if (points_[i].toe && out.force < 0.0) {  // the toe never pulls
    out.force = 0.0;
    out.damping = -spring;
    out.tangent = 0.0;
  }
  return out;
}

void SoilIteration::start(const double* u0, const double* v0) {
  std::fill(state_.begin(), state_.end(), 0.0);
  slip_work_ = damping_work_ = 0.0;
  toe_force_ = 0.0;
  slip_last_ = damping_last_ = 0.0;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const Resistance s = law_at(i, u0[points_[i].node], v0[points_[i].node]);
    if (!points_[i].toe) slip_work_ += points_[i].ultimate * std::abs(s.state);
    state_[i] = state_reported_[i] = s.state;
    force_[i] = s.force;
    damping_[i] = s.damping;
    spring_[i] = s.spring;
    if (points_[i].toe) toe_force_ = s.force;
  }
  begin_step();
}

void SoilIteration::start_levels(const double* u1, const double* v0, double dt) {
  double half_step = 0.0;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const Point& p = points_[i];
    half_step += damping_[i] * -v0[p.node];
    const Resistance s = law_at(i, u1[p.node], 0.0);  // level 1's spring from level 0's state
    if (!p.toe) slip_work_ += p.ultimate * std::abs(s.state - state_[i]);
    state_[i] = s.state;
    spring_old_[i] = spring_[i];
    spring_[i] = s.spring;
    dashpot_[i] = s.dashpot;
  }
  // Level 0's share, its forward half step as the scheme books W_ext, which
  // t = 0 does not report yet (damping_work() = sum - last / 2 = 0 there).
  damping_work_ = 0.5 * dt * half_step;
  damping_last_ = 2.0 * damping_work_;
  slip_last_ = 0.0;
  for (std::size_t i = 0; i < points_.size(); ++i)
    if (!points_[i].toe) slip_last_ += points_[i].ultimate * std::abs(state_[i] - state_reported_[i]);
}

void SoilIteration::add_start_forces(double* f) const {
  for (std::size_t i = 0; i < points_.size(); ++i)
    if (!points_[i].toe) f[points_[i].node] += force_[i];
}

void SoilIteration::begin_step() {
  std::copy(force_.begin(), force_.end(), iterate_.begin());
}

void SoilIteration::add_load(double* f) const {
  for (std::size_t i = 0; i < points_.size(); ++i) f[points_[i].node] += iterate_[i];
}

double SoilIteration::load_on(std::size_t node) const {
  double f = 0.0;
  for (std::size_t i = 0; i < points_.size(); ++i)
    if (points_[i].node == node) f += iterate_[i];
  return f;
}

bool SoilIteration::settled(const double* u, const double* v) {
  double worst = 0.0;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const Resistance s = at(i, u[points_[i].node], v[points_[i].node]);
    trial_[i] = s.force;
    trial_damping_[i] = s.damping;
    trial_state_[i] = s.state;
    trial_spring_[i] = s.spring;
    trial_dashpot_[i] = s.dashpot;
    tangent_[i] = s.tangent;
    if (points_[i].toe && on_face(i, u[points_[i].node], v[points_[i].node])) continue;
    const double d = std::abs(s.force - iterate_[i]);
    if (!(d <= worst)) worst = d;  // a NaN stays: the iteration then fails, it does not settle
  }
  misfit_ = worst / tolerance_;
  if (worst <= tolerance_) return true;
  newton(u, v);
  return false;
}

// A viscous toe's law jumps where the toe reaches its slipped position
// (from 0 to J R_u dc/dt): there it holds with any force between the two,
// c = s (the viscoelastic face of penalty_links.hpp).
bool SoilIteration::on_face(std::size_t i, double u, double v) const {
  if (levels_) return false;  // Phi is continuous: level m's dashpot is fixed
  const Point& p = points_[i];
  const double w = -(u + p.gap), slip = std::max(0.0, std::max(state_[i], w) - p.quake);
  const double upper = std::max(0.0, -p.viscous * v);
  return std::abs(w - slip) <= 1e-9 * p.quake && iterate_[i] >= -tolerance_ && iterate_[i] <= upper + tolerance_;
}

// (A + c K) du = c (G^ - g^k) over the shaft by the Thomas algorithm (held
// rows the identity), then g^{k+1} = G(u + du, v + r du). The toe is solved
// apart, exactly on the step's line through it: its penetration answers its
// force p by -c (A + c K)^{-1}_00 p, its law F decreases along that line, so
// p - F(p) increases (with upward jumps at the face) and bisection finds
// where it changes sign, the face included.
void SoilIteration::newton(const double* u, const double* v) {
  std::copy(a_.diag.begin(), a_.diag.end(), diag_.begin());
  std::copy(a_.off.begin(), a_.off.end(), off_.begin());
  std::fill(du_.begin(), du_.end(), 0.0);
  std::fill(toe_du_.begin(), toe_du_.end(), 0.0);
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const std::size_t j = points_[i].node;
    if (points_[i].toe) {
      toe_du_[j] = c_;
      continue;
    }
    diag_[j] += c_ * tangent_[i];
    du_[j] += c_ * (trial_[i] - iterate_[i]);
  }
  solve_tangent(diag_, off_, held_, du_, toe_du_);
  for (std::size_t i = 0; i < points_.size(); ++i)
    if (points_[i].toe) solve_toe(i, u, v);
  for (std::size_t i = 0; i < points_.size(); ++i) {
    if (points_[i].toe) continue;
    const std::size_t j = points_[i].node;
    iterate_[i] = at(i, u[j] + du_[j], v[j] + r_ * du_[j]).force;
  }
}

// The toe's force p on the step's line through it, du + toe_du (p - g^k):
// bisection on p - F(p), <= 0 at 0 and >= 0 at F(0), where F is largest.
void SoilIteration::solve_toe(std::size_t i, const double* u, const double* v) {
  const std::size_t j = points_[i].node;
  const double g = iterate_[i];
  auto law = [&](double p) {
    const double du = du_[j] + toe_du_[j] * (p - g);
    return at(i, u[j] + du, v[j] + r_ * du).force;
  };
  double lo = 0.0, hi = law(0.0);
  for (int k = 0; k < 200 && hi - lo > 1e-15 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (mid - law(mid) < 0.0 ? lo : hi) = mid;
  }
  iterate_[i] = hi;
  for (std::size_t m = 0; m < du_.size(); ++m) du_[m] += toe_du_[m] * (hi - g);
}

void SoilIteration::accept(const double* u_old, const double* u) {
  if (levels_) {
    accept_level(u_old, u);
    return;
  }
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const Point& p = points_[i];
    const double dw = -(u[p.node] - u_old[p.node]);
    // The damping the step applied: its force less the static part (on a
    // viscous toe's face anything between 0 and J R_u v, else G^'s to the tolerance).
    const double applied = iterate_[i] - (trial_[i] - trial_damping_[i]);
    damping_work_ += 0.5 * (damping_[i] + applied) * dw;
    if (!p.toe) slip_work_ += p.ultimate * std::abs(trial_state_[i] - state_[i]);
    state_[i] = trial_state_[i];
    force_[i] = iterate_[i];
    damping_[i] = applied;
    if (p.toe) toe_force_ = force_[i];
  }
}

// Level m's damping tested as the scheme tests its forces, with
// (w^{m+1} - w^{m-1}) / 2; level m + 1's slips and springs, its dashpots.
void SoilIteration::accept_level(const double* u_old, const double* u) {
  double damping = 0.0, slip = 0.0;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const Point& p = points_[i];
    const double applied = iterate_[i] - (trial_[i] - trial_damping_[i]);  // Phi^m less its springs
    damping += applied * -0.5 * (u[p.node] - u_old[p.node]);
    if (!p.toe) slip += p.ultimate * std::abs(trial_state_[i] - state_[i]);
    state_reported_[i] = state_[i];
    state_[i] = trial_state_[i];
    spring_old_[i] = spring_[i];
    spring_[i] = trial_spring_[i];
    dashpot_[i] = trial_dashpot_[i];
    force_[i] = iterate_[i];
    damping_[i] = applied;
    if (p.toe) toe_force_ = force_[i];
  }
  damping_work_ += damping;
  damping_last_ = damping;
  slip_work_ += slip;
  slip_last_ = slip;
}

std::string SoilIteration::failure() const {
  return fmt::format(
      "Smith's soil did not settle in {} steps (its forces still move by {:.3g} times the tolerance 1e-10 of its "
      "capacity)",
      most_iterations, misfit_);
}

double SoilIteration::shaft_energy(const double* u_kept, double scale) const {
  const std::vector<double>& state = levels_ ? state_reported_ : state_;
  double e = 0.0;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const Point& p = points_[i];
    if (p.toe) continue;
    const double x = -scale * u_kept[p.node] - state[i];
    e += 0.5 * p.stiffness * x * x;
  }
  return e;
}

}  // namespace barimpact
