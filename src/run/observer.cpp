#include "barimpact/run/observer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace barimpact {

void HistoryRecorder::begin(const Scheme& /*scheme*/, long long steps) {
  last_ = steps;
  rows_.clear();
  rows_.reserve(static_cast<std::size_t>(steps / every_ + 2));
  extra_.clear();
  if (probes_ != nullptr) extra_.reserve(rows_.capacity() * probes_->size());
  pending_ = false;
}

// A row's energies as the scheme completes them, at the step after it.
void HistoryRecorder::complete(const Scheme& s) {
  s.finish_energies(energies_);
  rows_.back().E_kin = energies_.kinetic;
  rows_.back().E_strain = energies_.strain;
  pending_ = false;
}

void HistoryRecorder::end(const Scheme& s) {
  if (pending_) complete(s);
}

bool HistoryRecorder::observe(const Scheme& s) {
  if (pending_) complete(s);
  const long long n = s.step();
  if (n % every_ != 0 && n != last_) return true;
  // The last row whole: no step follows to complete it.
  pending_ = n == last_ ? (energies_ = s.energies(), false) : !s.begin_energies(energies_);
  const Energies& e = energies_;
  rows_.push_back({s.time(), s.end_displacement(), s.end_velocity(), s.reaction(), e.kinetic, e.strain, e.obstacle,
                   e.work, e.dissipation, e.contact, e.plastic});
  if (probes_ != nullptr && probes_->size() > 0) {
    extra_.resize(extra_.size() + probes_->size());  // within the reserve: no allocation
    probes_->read(s, extra_.data() + extra_.size() - probes_->size());
  }
  return true;
}

FieldRecorder::FieldRecorder(const Case& c, const Line& line, std::vector<double> times, FieldSink* sink)
    : dt_(c.time.step), line_(&line), times_(std::move(times)), sink_(sink) {
  if (times_.empty()) return;  // no snapshots: no rows to describe (and no memory per node)
  fields_.x.reserve(line.nodes());
  fields_.node.reserve(line.nodes());
  fields_.body.reserve(line.nodes());
  for (std::size_t b = 0; b < line.bodies.size(); ++b) {
    const BodyRange& r = line.bodies[b];
    if (r.is_mass) continue;
    fields_.body_names.push_back(r.name);
    for (std::size_t j = r.first; j <= r.last; ++j) {
      fields_.x.push_back(line.x[j]);
      fields_.node.push_back(j);
      fields_.body.push_back(fields_.body_names.size() - 1);
    }
  }
}

void FieldRecorder::begin(const Scheme& /*scheme*/, long long steps) {
  steps_.clear();
  for (double t : times_) steps_.push_back(std::clamp(std::llround(t / dt_), 0LL, steps));
  std::sort(steps_.begin(), steps_.end());
  steps_.erase(std::unique(steps_.begin(), steps_.end()), steps_.end());
  const std::size_t n = fields_.nodes(),
                    held = sink_ != nullptr ? std::min<std::size_t>(steps_.size(), 1) : steps_.size();
  fields_.t.assign(held, 0.0);
  fields_.u.assign(held * n, 0.0);
  fields_.v.assign(held * n, 0.0);
  fields_.sigma.assign(held * n, 0.0);
  fields_.eps_p.assign(held * n, 0.0);
  taken_ = 0;
}

bool FieldRecorder::observe(const Scheme& s) {
  if (taken_ == steps_.size() || s.step() != steps_[taken_]) return true;
  const std::size_t slot = sink_ != nullptr ? 0 : taken_, n = fields_.nodes(), at = slot * n;
  fields_.t[slot] = s.time();
  ++taken_;
  double* u = fields_.u.data() + at;
  double* v = fields_.v.data() + at;
  double* sigma = fields_.sigma.data() + at;
  double* eps_p = fields_.eps_p.data() + at;
  for (std::size_t r = 0; r < n; ++r) {
    u[r] = s.displacement_at(fields_.node[r]);
    v[r] = s.velocity_at(fields_.node[r]);
  }
  // sigma per element, constant; a row takes the mean of its body's elements
  // beside it (one at the body's ends).
  double left = 0.0, left_ep = 0.0;
  for (std::size_t r = 0; r < n; ++r) {
    const bool last = r + 1 == n || fields_.body[r + 1] != fields_.body[r];
    const bool first = r == 0 || fields_.body[r - 1] != fields_.body[r];
    if (last) {
      sigma[r] = left;
      eps_p[r] = left_ep;
      continue;
    }
    const Bond& b = line_->bonds[fields_.node[r]];
    const double ep = s.plastic_strain(fields_.node[r]);
    double sig = (b.axial * (u[r + 1] - u[r]) + b.damping * (v[r + 1] - v[r])) / b.h - b.axial * ep;
    if (b.area != 1.0) sig /= b.area;
    sigma[r] = first ? sig : 0.5 * (left + sig);
    eps_p[r] = first ? ep : 0.5 * (left_ep + ep);
    left = sig;
    left_ep = ep;
  }
  return sink_ == nullptr || sink_->write(fields_);
}

Fields FieldRecorder::take() {
  const std::size_t n = fields_.nodes();
  if (sink_ != nullptr) taken_ = 0;  // the snapshots went to the sink
  fields_.t.resize(taken_);
  fields_.u.resize(taken_ * n);
  fields_.v.resize(taken_ * n);
  fields_.sigma.resize(taken_ * n);
  fields_.eps_p.resize(taken_ * n);
  return std::move(fields_);
}

const ContactInterval* departure(const std::vector<ContactInterval>& episodes) {
  return !episodes.empty() && episodes.back().closed ? &episodes.back() : nullptr;
}

ContactMonitor::ContactMonitor(const Line& line, double dt) : line_(&line), dt_(dt) {
  if (!line.links.empty() && line.links.front().is_end && line.links.front().a == Link::ground) {
    present_ = true;
    rigid_ = line.links.front().law.rigid();
    gap_ = line.links.front().gap;
  }
}

// Momentum over mass, node by node (the consistent mass's momentum is the
// lumped mass's: its rows sum to the lumped masses). Once an episode: no
// copy of the velocities is kept.
double ContactMonitor::mean_velocity(const Scheme& s) const {
  const Line& line = *line_;
  double momentum = 0.0, mass = 0.0;
  for (std::size_t j = 0; j < line.nodes(); ++j) {
    const double m = line.node_mass(j);
    momentum += m * s.velocity_at(j);
    mass += m;
  }
  return momentum / mass;
}

void ContactMonitor::begin(const Scheme& /*scheme*/, long long steps) {
  intervals_.clear();
  // An episode needs a step in contact after one out of it: at most
  // steps / 2 + 1 of them, all reserved up to 65536 (3 MB), so that the time
  // loop never allocates unless a run chatters more often than that.
  intervals_.reserve(static_cast<std::size_t>(std::min<long long>(steps / 2 + 1, 65536)));
  in_contact_ = have_previous_ = false;
  max_penetration_ = max_reaction_ = max_impulse_ = 0.0;
}

bool ContactMonitor::observe(const Scheme& s) {
  const double t = s.time();
  const double d = s.end_displacement() + gap_;  // < 0 in contact
  const double R = s.reaction();
  // On the obstacle: penetrating (penalty), or held by a reaction (rigid: U + g = 0).
  const bool contact = present_ && (d < 0.0 || R > 0.0);
  // The crossing of U + g = 0, linear between the last two steps. A rigid
  // end can be held by a reaction one step before it reaches the face (R^n
  // is the force that puts u^{n+1} on it), so an episode's start may lie up
  // to a step ahead of the step that opened it; it never lies before the
  // previous step, and an episode never ends before it starts.
  auto crossing = [&](double latest) {
    if (!have_previous_ || previous_d_ == d) return t;  // a rigid end sits at d = 0
    return std::clamp(previous_t_ + (t - previous_t_) * previous_d_ / (previous_d_ - d), previous_t_, latest);
  };
  const bool opened = contact && !in_contact_;
  if (opened) {
    intervals_.push_back({crossing(t + (t - previous_t_)), t, false, 0.0, 0.0});
  } else if (!contact && in_contact_) {
    auto& last = intervals_.back();
    last.end = std::max(crossing(t), last.start);
    last.closed = true;
    last.exit_velocity = s.end_velocity();
    last.rebound_velocity = mean_velocity(s);
  }
  if (contact) {
    auto& last = intervals_.back();
    last.end = std::max(t, last.start);
    max_penetration_ = std::max(max_penetration_, -d);
    if (opened && rigid_) {  // the impact step: an impulse
      last.impact_impulse = R * (dt_ > 0.0 ? dt_ : have_previous_ ? t - previous_t_ : 0.0);
      max_impulse_ = std::max(max_impulse_, last.impact_impulse);
    } else {
      last.max_reaction = std::max(last.max_reaction, R);
      max_reaction_ = std::max(max_reaction_, R);
    }
  }
  in_contact_ = contact;
  have_previous_ = true;
  previous_t_ = t;
  previous_d_ = d;
  return true;
}

LinkMonitor::LinkMonitor(const Line& line) {
  for (const auto& l : line.links) {
    names_.push_back(l.name);
    a_.push_back(l.a);
    b_.push_back(l.b);
  }
}

void LinkMonitor::begin(const Scheme& /*scheme*/, long long steps) {
  episodes_.assign(names_.size(), {});
  for (auto& e : episodes_) e.reserve(static_cast<std::size_t>(std::min<long long>(steps / 2 + 1, 4096)));
  in_contact_.assign(names_.size(), 0);
  largest_ = 0.0;
}

bool LinkMonitor::observe(const Scheme& s) {
  const double t = s.time();
  for (std::size_t i = 0; i < names_.size(); ++i) largest_ = std::max(largest_, s.link_force(i));
  for (std::size_t i = 0; i < names_.size(); ++i) {
    const double p = s.link_force(i);
    // In contact while pushing, above 1e-9 of the largest force any link
    // has carried: an explicit scheme's numerical precursor (forces of
    // 1e-200 ahead of the wave) is not a contact.
    const bool contact = p > 1e-9 * largest_;
    auto& list = episodes_[i];
    if (contact && !in_contact_[i]) list.push_back({t, t, false, 0.0, 0.0, 0.0});
    if (!contact && in_contact_[i]) {
      auto& last = list.back();
      last.closed = true;
      const double nan = std::numeric_limits<double>::quiet_NaN();
      last.velocity_lower = a_[i] == Link::ground ? nan : s.velocity_at(a_[i]);
      last.velocity_upper = b_[i] == Link::ground ? nan : s.velocity_at(b_[i]);
    }
    if (contact) {
      list.back().end = t;
      list.back().max_force = std::max(list.back().max_force, p);
    }
    in_contact_[i] = contact ? 1 : 0;
  }
  return true;
}

ProgressMonitor::ProgressMonitor(Report report, double t_end, double interval_seconds, double delay_seconds)
    : report_(std::move(report)), t_end_(t_end), interval_(interval_seconds), delay_(delay_seconds) {}

void ProgressMonitor::begin(const Scheme& /*scheme*/, long long steps) {
  steps_ = steps;
  stride_ = countdown_ = 1;
  started_ = last_read_ = Clock::now();
  last_report_ = started_ - std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(interval_));
}

bool ProgressMonitor::observe(const Scheme& s) {
  if (--countdown_ > 0) return true;
  const auto now = Clock::now();
  const double since_read = std::chrono::duration<double>(now - last_read_).count();
  if (since_read < interval_ / 16 && stride_ < (1LL << 30)) stride_ *= 2;
  countdown_ = stride_;
  last_read_ = now;
  const double elapsed = std::chrono::duration<double>(now - started_).count();
  if (elapsed < delay_ || std::chrono::duration<double>(now - last_report_).count() < interval_) return true;
  last_report_ = now;
  return report_(Progress{s.step(), steps_, s.time(), t_end_, elapsed});
}

PlasticMonitor::PlasticMonitor(const Line& line, long long every) : every_(every) {
  work_.assign(line.bodies.size(), 0.0);
  // An elastic line: no bond to watch, and none to look at (10^6 of them at start-up).
  if (std::none_of(line.plasticity.begin(), line.plasticity.end(), [](auto p) { return static_cast<bool>(p); })) return;
  for (std::size_t j = 0; j < line.bonds.size(); ++j) {
    const Bond& b = line.bonds[j];
    if (b.kind == BondKind::element && b.body < line.plasticity.size() && line.plasticity[b.body]) bonds_.push_back(j);
  }
}

void PlasticMonitor::begin(const Scheme& /*scheme*/, long long steps) {
  last_ = steps;
  largest_ = time_ = 0.0;
  bond_ = bonds_.empty() ? 0 : bonds_.front();
  std::fill(work_.begin(), work_.end(), 0.0);
}

bool PlasticMonitor::observe(const Scheme& s) {
  const long long n = s.step();
  if (bonds_.empty() || (n % every_ != 0 && n != last_)) return true;
  for (std::size_t b = 0; b < work_.size(); ++b) work_[b] = s.plastic_work(b);
  // Before anything flows, no plastic work is done and every eps_p is 0:
  // nothing to scan (the largest stays 0, as the scan would leave it).
  if (std::all_of(work_.begin(), work_.end(), [](double w) { return w == 0.0; })) return true;
  for (std::size_t j : bonds_) {
    const double p = s.plastic_strain(j);
    if (std::abs(p) > std::abs(largest_)) {
      largest_ = p;
      bond_ = j;
      time_ = s.time();
    }
  }
  return true;
}

}  // namespace barimpact
