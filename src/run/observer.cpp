#include "barimpact/run/observer.hpp"

#include <algorithm>
#include <cmath>

namespace barimpact {

void HistoryRecorder::begin(const Scheme& /*scheme*/, long long steps) {
  last_ = steps;
  rows_.clear();
  rows_.reserve(static_cast<std::size_t>(steps / every_ + 2));
}

bool HistoryRecorder::observe(const Scheme& s) {
  const long long n = s.step();
  if (n % every_ != 0 && n != last_) return true;
  const Energies e = s.energies();
  rows_.push_back({s.time(), s.end_displacement(), s.end_velocity(), s.reaction(), e.kinetic, e.strain, e.obstacle,
                   e.work, e.dissipation});
  return true;
}

FieldRecorder::FieldRecorder(const Case& c, std::vector<double> times)
    : dt_(c.time.step),
      h_(c.bar.length / c.bar.elements),
      a_(c.bar.stiffness),
      b_(c.bar.viscosity),
      times_(std::move(times)) {
  const std::size_t n = static_cast<std::size_t>(c.bar.elements) + 1;
  fields_.x.resize(n);
  for (std::size_t j = 0; j < n; ++j) fields_.x[j] = static_cast<double>(j) * h_;
}

void FieldRecorder::begin(const Scheme& /*scheme*/, long long steps) {
  steps_.clear();
  for (double t : times_) steps_.push_back(std::clamp(std::llround(t / dt_), 0LL, steps));
  std::sort(steps_.begin(), steps_.end());
  steps_.erase(std::unique(steps_.begin(), steps_.end()), steps_.end());
  const std::size_t n = fields_.nodes();
  fields_.t.assign(steps_.size(), 0.0);
  fields_.u.assign(steps_.size() * n, 0.0);
  fields_.v.assign(steps_.size() * n, 0.0);
  fields_.sigma.assign(steps_.size() * n, 0.0);
  taken_ = 0;
}

bool FieldRecorder::observe(const Scheme& s) {
  if (taken_ == steps_.size() || s.step() != steps_[taken_]) return true;
  const std::size_t n = fields_.nodes(), at = taken_ * n;
  fields_.t[taken_++] = s.time();
  const std::span<double> u(fields_.u.data() + at, n), v(fields_.v.data() + at, n), sigma(fields_.sigma.data() + at, n);
  s.displacement(u);
  s.velocity(v);
  // sigma = a u_x + b v_x, constant per element; nodes take the mean of
  // their elements (one element at the ends).
  double left = 0.0;
  for (std::size_t e = 0; e + 1 < n; ++e) {
    const double sig = (a_ * (u[e + 1] - u[e]) + b_ * (v[e + 1] - v[e])) / h_;
    sigma[e] = e == 0 ? sig : 0.5 * (left + sig);
    left = sig;
  }
  sigma[n - 1] = left;
  return true;
}

Fields FieldRecorder::take() {
  const std::size_t n = fields_.nodes();
  fields_.t.resize(taken_);
  fields_.u.resize(taken_ * n);
  fields_.v.resize(taken_ * n);
  fields_.sigma.resize(taken_ * n);
  return std::move(fields_);
}

void ContactMonitor::begin(const Scheme& scheme, long long steps) {
  velocity_.assign(scheme.nodes(), 0.0);
  intervals_.clear();
  // An episode needs a step in contact after one out of it: at most
  // steps / 2 + 1 of them, all reserved up to 65536 (3 MB), so that the time
  // loop never allocates unless a run chatters more often than that.
  intervals_.reserve(static_cast<std::size_t>(std::min<long long>(steps / 2 + 1, 65536)));
  in_contact_ = have_previous_ = false;
  max_penetration_ = max_reaction_ = 0.0;
}

bool ContactMonitor::observe(const Scheme& s) {
  const double t = s.time();
  const double d = s.end_displacement() + law_.gap();  // < 0 in contact
  const double R = s.reaction();
  // On the obstacle: penetrating (penalty), or held by a reaction (rigid: U + g = 0).
  const bool contact = law_.kind() != ObstacleKind::none && (d < 0.0 || R > 0.0);
  // The crossing of U + g = 0, linear between the last two steps. A rigid
  // end can be held by a reaction one step before it reaches the face (R^n
  // is the force that puts u^{n+1} on it), so an episode's start may lie up
  // to a step ahead of the step that opened it; it never lies before the
  // previous step, and an episode never ends before it starts.
  auto crossing = [&](double latest) {
    if (!have_previous_ || previous_d_ == d) return t;  // a rigid end sits at d = 0
    return std::clamp(previous_t_ + (t - previous_t_) * previous_d_ / (previous_d_ - d), previous_t_, latest);
  };
  if (contact && !in_contact_) {
    intervals_.push_back({crossing(t + (t - previous_t_)), t, false, 0.0, 0.0});
  } else if (!contact && in_contact_) {
    auto& last = intervals_.back();
    last.end = std::max(crossing(t), last.start);
    last.closed = true;
    last.exit_velocity = s.end_velocity();
    // Mean velocity: the consistent P1 mass gives momentum rho h sum (v_j + v_{j+1}) / 2.
    s.velocity(velocity_);
    double sum = 0.0;
    for (std::size_t j = 0; j + 1 < velocity_.size(); ++j) sum += 0.5 * (velocity_[j] + velocity_[j + 1]);
    last.rebound_velocity = sum / static_cast<double>(velocity_.size() - 1);
  }
  if (contact) {
    auto& last = intervals_.back();
    last.end = std::max(t, last.start);
    last.max_reaction = std::max(last.max_reaction, R);
    max_penetration_ = std::max(max_penetration_, -d);
    max_reaction_ = std::max(max_reaction_, R);
  }
  in_contact_ = contact;
  have_previous_ = true;
  previous_t_ = t;
  previous_d_ = d;
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

}  // namespace barimpact
