#include "barimpact/run/blow.hpp"

#include <algorithm>
#include <cmath>

#include "barimpact/run/probe.hpp"

namespace barimpact {

namespace {

std::size_t body_named(const Line& line, const std::string& name) {
  for (std::size_t b = 0; b < line.bodies.size(); ++b)
    if (line.bodies[b].name == name) return b;
  return line.bodies.size();
}

// The pile: [blow] pile, else the bar nearest x = 0.
std::size_t pile_of(const Case& c, const Line& line) {
  if (!c.blow.pile.empty()) return body_named(line, c.blow.pile);
  for (std::size_t b = 0; b < line.bodies.size(); ++b)
    if (!line.bodies[b].is_mass) return b;
  return 0;
}

}  // namespace

bool reports_blow(const Case& c, const Line& line) {
  const bool toe = !line.links.empty() && line.links.front().law.kind == LawKind::smith;
  return toe || !line.shaft.empty() || !c.blow.gauge.empty() || !c.blow.ram.empty() || !c.blow.pile.empty();
}

BlowMonitor::BlowMonitor(const Case& c, const Line& line) : line_(line), dt_(c.time.step) {
  const BodyRange& pile = line.bodies[pile_of(c, line)];
  out_.pile = pile.name;
  first_ = pile.first;
  last_ = pile.last;
  const std::size_t ram = c.blow.ram.empty() ? line.bodies.size() - 1 : body_named(line, c.blow.ram);
  out_.ram = line.bodies[ram].name;
  ram_first_ = line.bodies[ram].first;
  ram_last_ = line.bodies[ram].last;
  for (std::size_t i = 0; i < line.links.size(); ++i) {
    if (line.links[i].b == ram_first_ && !line.links[i].is_end) ram_link_ = i;
    if (!line.links[i].is_end && line.links[i].a >= last_ && line.links[i].b <= ram_first_) hammer_links_.push_back(i);
    if (line.links[i].name == "near_end" && line.links[i].law.kind == LawKind::smith) {
      toe_link_ = i;
      toe_quake_ = line.links[i].law.soil.quake;
    }
  }
  // ENTHRU's gauge: [blow] gauge, else the pile's gauge nearest its head.
  for (const auto& g : line.gauges) {
    const bool on_pile = g.node >= first_ && g.node < last_;
    if (c.blow.gauge.empty() ? on_pile && (!gauge_ || g.node >= gauge_->node) : g.name == c.blow.gauge) gauge_ = g;
  }
  if (gauge_) {
    out_.gauge = gauge_->name;
    const Bond& b = line.bonds[std::min(gauge_->node, line.bonds.size() - 1)];  // the gauged bar's
    out_.impedance = std::sqrt(b.axial * b.mass / b.h);                         // E A / c
  }
  if (ram_link_ != Link::ground && line.links[ram_link_].law.kind == LawKind::diesel) {
    const DieselGas& gas = line.links[ram_link_].law.gas;
    diesel_ = out_.diesel = true;
    out_.compression_work = gas.compression_work();
    out_.expansion_work = gas.expansion_work();
  }
  for (std::size_t j = first_; j < last_; ++j) out_.envelope.x.push_back(0.5 * (line.x[j] + line.x[j + 1]));
  out_.envelope.compression.assign(out_.envelope.x.size(), 0.0);
  out_.envelope.tension.assign(out_.envelope.x.size(), 0.0);
  out_.max_compression.body = out_.max_tension.body = out_.pile;
  out_.max_compression.x = out_.max_tension.x = line.x[first_];
  arrival_.assign(last_ - first_, 0.0);
  for (std::size_t j = last_; j-- > first_;) {  // from the head down: h / c per element, c = sqrt(E A h / (rho A h))
    const Bond& b = line.bonds[j];
    const double h_c = b.kind == BondKind::element ? b.h / std::sqrt(b.axial * b.h / b.mass) : 0.0;
    arrival_[j - first_] = transit_ - 1.5 * h_c;  // its middle's arrival, less two transits of margin
    transit_ += h_c;
  }
  out_.precursor.body = out_.pile;
  open_at_apex_.assign(hammer_links_.size(), 0);
  if (c.blow.rest_window) out_.rest_window = *c.blow.rest_window;
  start_ = out_;
  mass_ = line.lumped_mass();
  if (line.bodies[ram].is_mass)  // its own mass, not the half elements of a bar welded to it
    mass_[ram_first_] = line.point_mass[ram_first_];
}

void BlowMonitor::begin(const Scheme& /*scheme*/, long long /*steps*/) {
  out_ = start_;
  power_ = energy_ = 0.0;
  impacted_ = false;
  at_rest_ = rested_ = false;
  ram_rising_ = apex_ = restruck_ = false;
  slip_ = 0.0;
}

bool BlowMonitor::observe(const Scheme& s) {
  if (restruck_) return true;  // the first strike's blow is over: nothing after it counts
  watch_impact(s);
  if (!diesel_) watch_restrike(s);
  if (restruck_) return true;
  watch_stresses(s);
  if (gauge_) {  // ENTHRU: int N v dt by trapezoids, its largest value
    const double power = gauge_force(line_, s, *gauge_) * gauge_velocity(s, *gauge_);
    if (s.step() > 0) energy_ += 0.5 * (power_ + power) * dt_;
    power_ = power;
    out_.enthru = std::max(std::isnan(out_.enthru) ? 0.0 : out_.enthru, energy_);
  }
  if (toe_link_ != Link::ground)
    out_.toe_penetration = std::max(out_.toe_penetration, -s.link_opening(toe_link_));
  else
    out_.toe_penetration = std::max(out_.toe_penetration, -s.displacement_at(first_));
  watch_rest(s);
  if (diesel_) watch_rebound(s);
  return true;
}

// A diesel ram past the ports moving up after impact rises ballistically:
// its height above impact is y + v^2 / 2g at the first step it is there
// (the anvil at rest by then: v is the ram's own velocity).
void BlowMonitor::watch_rebound(const Scheme& s) {
  if (!impacted_ || !std::isnan(out_.next_stroke)) return;
  const double y = s.link_opening(ram_link_), v = s.velocity_at(ram_first_);
  if (y >= line_.links[ram_link_].law.gas.compression_length && v > 0.0)
    out_.next_stroke = y + v * v / (2.0 * line_.gravity);
}

// A re-strike: the ram, risen in free flight after impact (its link open,
// moving up faster than the rest rule's 1% of the impact velocity), turns
// two round trips or more after impact and falls back; the first step after
// that turn at which a joint of the hammer that was open then pushes again
// (the helmet landing on the pile, the ram on its capblock) is a second
// strike. It ends the blow if the blow is over by then (settled());
// otherwise the pile is still moving and it is part of the blow.
// (A diesel's ram, which its gas catches, is its stroke iteration's.)
void BlowMonitor::watch_restrike(const Scheme& s) {
  if (!impacted_ || ram_link_ == Link::ground) return;
  const double v = s.velocity_at(ram_first_);
  const bool free = s.link_force(ram_link_) <= 0.0;
  if (!apex_) {
    ram_rising_ = free && (ram_rising_ || v > 0.01 * std::abs(out_.impact_velocity));
    if (!ram_rising_ || v > 0.0 || s.time() < out_.impact_time + 4.0 * transit_) return;
    apex_ = true;
    for (std::size_t k = 0; k < hammer_links_.size(); ++k) open_at_apex_[k] = s.link_force(hammer_links_[k]) <= 0.0;
    return;
  }
  for (std::size_t k = 0; k < hammer_links_.size(); ++k)
    if (open_at_apex_[k] && s.link_force(hammer_links_[k]) > 0.0) {
      if (settled(s.time())) {
        restruck_ = true;
        out_.restrike_time = s.time();
      } else {
        ++out_.strikes;
        apex_ = ram_rising_ = false;
      }
      return;
    }
}

// Impact: the first step the link below the ram pushes (from t = 0 without
// one); the ram's kinetic energy and velocity are those of the step before.
void BlowMonitor::watch_impact(const Scheme& s) {
  if (impacted_) return;
  double energy = 0.0, momentum = 0.0, mass = 0.0;
  for (std::size_t j = ram_first_; j <= ram_last_; ++j) {
    const double v = s.velocity_at(j);
    energy += 0.5 * mass_[j] * v * v;
    momentum += mass_[j] * v;
    mass += mass_[j];
  }
  // A diesel cylinder pushes before impact (its gas): the ram strikes when its cushion first closes.
  const bool touching = ram_link_ == Link::ground ||
                        (diesel_ ? s.link_largest_compression(ram_link_) > 0.0 : s.link_force(ram_link_) > 0.0);
  if (touching) {
    impacted_ = true;
    const bool before = s.step() > 0 && ram_link_ != Link::ground;
    out_.impact_time = before ? s.time() - dt_ : s.time();
    out_.hammer_energy = before ? ram_energy_ : energy;
    out_.impact_velocity = before ? ram_velocity_ : momentum / mass;
  }
  ram_energy_ = energy;
  ram_velocity_ = momentum / mass;
}

// The pile's elements' stress (E A eps + eta A deps/dt - E A eps_p) / A.
void BlowMonitor::watch_stresses(const Scheme& s) {
  double* __restrict compression = out_.envelope.compression.data();
  double* __restrict tension = out_.envelope.tension.data();
  for (std::size_t j = first_; j < last_; ++j) {
    const double sigma = bond_tension(line_, s, j) / line_.bonds[j].area;
    compression[j - first_] = std::max(compression[j - first_], -sigma);
    tension[j - first_] = std::max(tension[j - first_], sigma);
    StressPeak& peak = sigma < 0.0 ? out_.max_compression : out_.max_tension;
    if (std::abs(sigma) > peak.value) {
      peak.value = std::abs(sigma);
      peak.x = 0.5 * (line_.x[j] + line_.x[j + 1]);
      peak.t = s.time();
    }
    if (impacted_ && sigma > out_.precursor.value && s.time() < out_.impact_time + arrival_[j - first_]) {
      out_.precursor.value = sigma;
      out_.precursor.x = 0.5 * (line_.x[j] + line_.x[j + 1]);
      out_.precursor.t = s.time();
    }
  }
}

// At rest: every node of the pile below 1% of the impact velocity, at a
// step after the soil's last slip and after the wave has reached the toe and
// moved it (before, the pile is still, not at rest).
void BlowMonitor::watch_rest(const Scheme& s) {
  const double slip = s.soil_slip_work();
  if (slip > slip_ && !rested_) {
    slip_ = slip;
    out_.last_slip_time = s.time();
    at_rest_ = false;
  }
  if (!impacted_ || rested_) return;
  if (s.time() < out_.impact_time + transit_ || !(out_.toe_penetration > 0.0)) return;
  const double limit = 0.01 * std::abs(out_.impact_velocity);
  for (std::size_t j = first_; j <= last_; ++j)
    if (!(std::abs(s.velocity_at(j)) < limit)) {
      at_rest_ = false;  // a node passing through zero while the pile rings is not rest
      return;
    }
  if (!at_rest_) out_.rest_time = s.time();
  at_rest_ = true;
  rested_ = out_.rest_window > 0 && s.time() - out_.rest_time >= out_.rest_window;
}

// The blow is over at time t: the pile at rest, or the soil not slipping
// for ten round trips (20 L/c; the ringing since is elastic), the wave
// having reached and moved the toe.
bool BlowMonitor::settled(double t) const {
  if (at_rest_ || rested_) return true;
  if (!(out_.toe_penetration > 0.0) || t < out_.impact_time + transit_) return false;
  const double since = std::isnan(out_.last_slip_time) ? out_.impact_time : out_.last_slip_time;
  return t - since >= 20.0 * transit_;
}

BlowSummary BlowMonitor::summary() const {
  BlowSummary b = out_;
  b.impact = impacted_;
  b.finished = at_rest_ || rested_ || restruck_;
  if (!(at_rest_ || rested_)) b.rest_time = std::numeric_limits<double>::quiet_NaN();
  b.set = std::max(0.0, b.toe_penetration - toe_quake_);
  if (toe_link_ == Link::ground && !line_.shaft.empty()) {  // no toe spring: the shaft's quake at the toe
    const std::size_t j = line_.shaft.nodes.front();
    b.set = std::max(0.0, b.toe_penetration - line_.shaft.quake[j]);
  }
  return b;
}

}  // namespace barimpact
