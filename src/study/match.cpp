// Signal matching's fit: the unknowns (shaft resistances, toe, quakes,
// dampings) scaled to order one, bounded, and found by Levenberg-Marquardt
// (Ceres Solver's, in the fitting module: least_squares.hpp) on the force
// difference over the window, from the Case method's estimate and further
// starts; forward differences for the Jacobian, its columns' runs spread
// over the cores a start has.
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <thread>

#include "barimpact/model/input_error.hpp"
#include "barimpact/study/executor.hpp"
#include "barimpact/study/match.hpp"

#include "least_squares.hpp"

namespace barimpact {

namespace {

constexpr double quake_lo = 0.0005, quake_hi = 0.015;  // m
constexpr double damping_hi = 2.5;                     // s/m

// The fit's variables: the unknowns a match fits, in MatchSettings' order,
// scaled (resistances by `scale` N, quakes in mm, dampings in s/m); the
// others keep the start's values.
class Unknowns {
 public:
  Unknowns(const MatchSettings& m, std::size_t segments, double scale) : segments_(segments), scale_(scale) {
    shaft_ = m.fits("shaft");
    toe_ = m.fits("toe");
    sq_ = m.fits("shaft_quake");
    tq_ = m.fits("toe_quake");
    sd_ = m.fits("shaft_damping");
    td_ = m.fits("toe_damping");
  }
  [[nodiscard]] std::size_t size() const { return (shaft_ ? segments_ : 0) + toe_ + sq_ + tq_ + sd_ + td_; }
  // Calls f(value&, scale, lo, hi) on each variable's soil value in order.
  template <class F>
  void each(MatchSoil& s, F&& f) const {
    if (shaft_)
      for (auto& r : s.shaft) f(r, scale_, 0.0, HUGE_VAL);
    if (toe_) f(s.toe, scale_, 0.0, HUGE_VAL);
    if (sq_) f(s.shaft_quake, 1e-3, quake_lo, quake_hi);
    if (tq_) f(s.toe_quake, 1e-3, quake_lo, quake_hi);
    if (sd_) f(s.shaft_damping, 1.0, 0.0, damping_hi);
    if (td_) f(s.toe_damping, 1.0, 0.0, damping_hi);
  }
  void to_x(MatchSoil s, double* x) const {
    std::size_t k = 0;
    each(s, [&](double& v, double sc, double, double) { x[k++] = v / sc; });
  }
  [[nodiscard]] MatchSoil from_x(MatchSoil s, const double* x) const {
    std::size_t k = 0;
    each(s, [&](double& v, double sc, double lo, double hi) { v = std::clamp(x[k++] * sc, lo, hi); });
    return s;
  }
  // Each variable's bounds, scaled: {lower, upper}.
  [[nodiscard]] std::vector<std::pair<double, double>> limits() const {
    std::vector<std::pair<double, double>> out;
    MatchSoil s;
    s.shaft.assign(shaft_ ? segments_ : 0, 0.0);
    each(s, [&](double&, double sc, double lo, double hi) { out.emplace_back(lo / sc, hi / sc); });
    return out;
  }
  void bounds(detail::LeastSquaresProblem& p) const {
    for (const auto& [lo, hi] : limits()) {
      p.lower.push_back(lo);
      p.upper.push_back(hi);
    }
  }

 private:
  std::size_t segments_;
  double scale_;
  bool shaft_, toe_, sq_, tq_, sd_, td_;
};

// The residuals r_k = (F_computed - F_measured) / F_max at the window's
// samples, and their forward-difference Jacobian (columns on `threads`).
class ForceMisfit final : public detail::ResidualBlock {
 public:
  ForceMisfit(const MatchModel& model, const Unknowns& unknowns, const MatchSoil& base,
              const std::vector<double>& measured, std::size_t first, double scale, int threads,
              std::atomic<long long>& evaluations)
      : model_(model),
        unknowns_(unknowns),
        base_(base),
        measured_(measured),
        first_(first),
        inv_scale_(1.0 / scale),
        threads_(threads),
        evaluations_(evaluations),
        limits_(unknowns.limits()) {}

  [[nodiscard]] std::size_t residuals() const override { return measured_.size(); }

  bool evaluate(const double* x, double* residuals, double* jacobian) const override {
    const std::size_t n = unknowns_.size(), m = measured_.size();
    if (!residuals_at(x, residuals)) return false;
    if (jacobian == nullptr) return true;
    std::atomic<bool> ok{true};
    auto column = [&](std::size_t i) {
      std::vector<double> xi(x, x + n), ri(m);
      // A step of 1e-4 of the variable (1e-4 of its scale near 0), inward at an upper bound.
      double h = 1e-4 * std::max(std::abs(x[i]), 1.0);
      if (x[i] + h > limits_[i].second) h = -h;
      xi[i] += h;
      if (!residuals_at(xi.data(), ri.data())) {
        ok = false;
        return;
      }
      for (std::size_t k = 0; k < m; ++k) jacobian[k * n + i] = (ri[k] - residuals[k]) / h;
    };
    if (threads_ <= 1)
      for (std::size_t i = 0; i < n; ++i) column(i);
    else
      run_parallel(n, threads_, column);
    return ok;
  }

 private:
  bool residuals_at(const double* x, double* r) const {
    const MatchSoil s = unknowns_.from_x(base_, x);
    ++evaluations_;
    if (!model_.head_force(s, first_, std::span<double>(r, measured_.size()))) return false;
    for (std::size_t k = 0; k < measured_.size(); ++k) r[k] = (r[k] - measured_[k]) * inv_scale_;
    return true;
  }

  const MatchModel& model_;
  const Unknowns& unknowns_;
  const MatchSoil& base_;
  const std::vector<double>& measured_;
  std::size_t first_;
  double inv_scale_;
  int threads_;
  std::atomic<long long>& evaluations_;
  std::vector<std::pair<double, double>> limits_;  // each variable's bounds (scaled)
};

// Tikhonov's penalty on the shaft's curvature: w (R_{i-1} - 2 R_i + R_{i+1})
// / F_max for each inner segment (the first `segments` variables, scaled by
// `scale`); zero on any linear distribution.
class ShaftSmoothing final : public detail::ResidualBlock {
 public:
  ShaftSmoothing(std::size_t segments, std::size_t size, double weight)
      : segments_(segments), size_(size), weight_(weight) {}
  [[nodiscard]] std::size_t residuals() const override { return segments_ - 2; }
  bool evaluate(const double* x, double* residuals, double* jacobian) const override {
    for (std::size_t i = 1; i + 1 < segments_; ++i) {
      residuals[i - 1] = weight_ * (x[i - 1] - 2.0 * x[i] + x[i + 1]);
      if (jacobian != nullptr) {
        double* row = jacobian + (i - 1) * size_;
        std::fill(row, row + size_, 0.0);
        row[i - 1] = weight_;
        row[i] = -2.0 * weight_;
        row[i + 1] = weight_;
      }
    }
    return true;
  }

 private:
  std::size_t segments_, size_;
  double weight_;
};

// The Case method's estimate: the total RMX (or half the largest force if
// RMX is not positive); the shaft from the wave up's rise along the pile
// (a resistance R at depth x returns R / 2 up at t1 + 2x/c), over 1 + J_c
// for its damping, kept within 10% and 90% of the total; the rest at the toe.
MatchSoil case_estimate(const CaseMethodResult& pda, const MatchModel& model, const MatchSettings& m) {
  const auto& rec = pda.record;
  MatchSoil s;
  s.law = m.damping_law;
  const double total = pda.rmx > 0.0 ? pda.rmx : 0.5 * pda.fmx;
  s.shaft.assign(model.segments(), 0.0);
  double rise = 0.0;
  for (std::size_t i = 0; i < model.segments(); ++i) {
    const double up = pda.waves.up_at(pda.t1 + rec.two_way_time(model.segment_bottom(i))) -
                      pda.waves.up_at(pda.t1 + rec.two_way_time(model.segment_top(i)));
    s.shaft[i] = std::max(up, 0.0);
    rise += s.shaft[i];
  }
  const double shaft = std::clamp(2.0 * rise / (1.0 + rec.damping), 0.1 * total, 0.9 * total);
  for (auto& r : s.shaft) r = rise > 0.0 ? r * shaft / rise : shaft / static_cast<double>(model.segments());
  s.toe = total - shaft;
  s.shaft_quake = m.shaft_quake;
  s.toe_quake = m.toe_quake;
  // J_c Z v is the whole pile's damping force; spread over the capacity.
  const double j = std::clamp(rec.damping * rec.impedance() / total, 0.0, damping_hi);
  s.shaft_damping = m.shaft_damping.value_or(j);
  s.toe_damping = m.toe_damping.value_or(j);
  return s;
}

// Start k + 1 (k >= 1): the estimate's total times 1, 1.25, 0.8, 1.1, 0.9
// (and 5% more each further round of five), a uniform shaft carrying 50%,
// 80%, 20%, 35%, 65% of it, quakes and dampings varied; what the fit does
// not change stays as the estimate has it.
MatchSoil other_start(const MatchSoil& estimate, const MatchSettings& m, int k) {
  static const double total_factor[] = {1.0, 1.25, 0.8, 1.1, 0.9};
  static const double shaft_part[] = {0.5, 0.8, 0.2, 0.35, 0.65};
  static const double quake_factor[] = {1.0, 1.6, 0.6, 1.3, 0.8};
  static const double damping_factor[] = {1.0, 0.5, 1.8, 0.75, 1.3};
  const int i = (k - 1) % 5;
  MatchSoil s = estimate;
  const double total = estimate.capacity() * total_factor[i] * (1.0 + 0.05 * ((k - 1) / 5));
  // A resistance left out of the unknowns keeps the estimate's, in every start.
  const double shaft = m.fits("shaft") ? shaft_part[i] * total : estimate.shaft_total();
  if (m.fits("shaft"))
    for (auto& r : s.shaft) r = shaft / static_cast<double>(s.shaft.size());
  if (m.fits("toe")) s.toe = std::max(total - shaft, 0.05 * total);
  if (m.fits("shaft_quake")) s.shaft_quake = std::clamp(estimate.shaft_quake * quake_factor[i], quake_lo, quake_hi);
  if (m.fits("toe_quake")) s.toe_quake = std::clamp(estimate.toe_quake * quake_factor[(i + 2) % 5], quake_lo, quake_hi);
  if (m.fits("shaft_damping"))
    s.shaft_damping = std::clamp(estimate.shaft_damping * damping_factor[i], 0.01, damping_hi);
  if (m.fits("toe_damping"))
    s.toe_damping = std::clamp(estimate.toe_damping * damping_factor[(i + 3) % 5], 0.01, damping_hi);
  return s;
}

double rms_quality(const std::vector<double>& computed, const std::vector<double>& measured, double scale) {
  double sum = 0.0;
  for (std::size_t k = 0; k < measured.size(); ++k) sum += (computed[k] - measured[k]) * (computed[k] - measured[k]);
  return std::sqrt(sum / static_cast<double>(measured.size())) / scale;
}

struct Window {
  std::size_t first = 0, count = 0;
  double after_t2 = 0.0;
};

// The samples matched: from the foot to t2 + window (or the record's end).
Window match_window(const CaseMethodResult& pda) {
  const auto& t = pda.signals.t;
  Window w;
  w.after_t2 = std::min(pda.record.match.window.value_or(0.020), t.back() - pda.t2);
  w.first = pda.signals.foot;
  std::size_t last = w.first;
  while (last + 1 < t.size() && t[last + 1] <= pda.t2 + w.after_t2 * (1 + 1e-12)) ++last;
  w.count = last - w.first + 1;
  return w;
}

// What every start's fit shares: the model, the settings, the measured
// force over the window from sample `first`, its largest value, the
// resistances' scale, the threads a start has and the interrupt.
struct FitInputs {
  const MatchModel& model;
  const MatchSettings& m;
  const std::vector<double>& measured;
  std::size_t first;
  double fmax, scale;
  int threads;
  const std::atomic<bool>* interrupt;
};

// One start's fit: Levenberg-Marquardt within the bounds, ended early by the interrupt.
MatchStart fit_from(const FitInputs& in, const MatchSoil& start) {
  const auto& [model, m, measured, first, force_scale, scale, threads, interrupt] = in;
  MatchStart out;
  out.start = start;
  const Unknowns unknowns(m, model.segments(), scale);
  std::vector<double> x(unknowns.size());
  unknowns.to_x(start, x.data());
  std::atomic<long long> evaluations{0};
  const ForceMisfit misfit(model, unknowns, start, measured, first, force_scale, threads, evaluations);
  const ShaftSmoothing smoothing(model.segments(), unknowns.size(), m.smoothing * scale / force_scale);
  detail::LeastSquaresProblem problem;
  problem.parameters = unknowns.size();
  problem.blocks.push_back(&misfit);
  if (m.smoothing > 0.0 && m.fits("shaft") && model.segments() > 2) problem.blocks.push_back(&smoothing);
  unknowns.bounds(problem);
  problem.interrupt = interrupt;
  const detail::LeastSquaresSummary summary = detail::solve_least_squares(problem, x.data());
  out.soil = unknowns.from_x(start, x.data());
  out.iterations = static_cast<int>(summary.iterations) - 1;
  out.evaluations = evaluations.load();
  out.converged = summary.converged;
  out.message = summary.message;
  out.objective = 2.0 * summary.final_cost / static_cast<double>(measured.size());
  out.computed.assign(measured.size(), 0.0);
  out.quality = model.head_force(out.soil, first, out.computed) ? rms_quality(out.computed, measured, force_scale)
                                                                : std::numeric_limits<double>::infinity();
  return out;
}

}  // namespace

double MatchResult::spread() const {
  double lo = soil.capacity(), hi = lo;
  for (const auto& s : starts) {
    lo = std::min(lo, s.soil.capacity());
    hi = std::max(hi, s.soil.capacity());
  }
  return hi - lo;
}

bool MatchResult::converged() const {
  return std::any_of(starts.begin(), starts.end(), [](const MatchStart& s) { return s.converged; });
}

std::vector<std::string> MatchResult::warnings() const {
  std::vector<std::string> out;
  if (!pda.signals.filter_note.empty()) out.push_back("match-unfiltered: " + pda.signals.filter_note);
  if (!starts.empty() && !converged())
    out.push_back(
        fmt::format("match-not-converged: no start converged within its iterations (the best: {}); the "
                    "match may not be a minimum: see start_results in summary.json",
                    starts[best].message));
  return out;
}

MatchResult match_pile(const PileRecord& record, int jobs, const std::atomic<bool>* interrupt) {
  const auto clock = std::chrono::steady_clock::now();
  MatchResult r;
  r.pda = analyse_pda(record, read_pile_signals(record, record.match.low_pass));
  const auto& sig = r.pda.signals;
  const Window w = match_window(r.pda);
  r.window = w.after_t2;
  r.first = w.first;
  // The run starts at rest one rise time before the foot (the record's first sample at the latest).
  const double rise = r.pda.t1 - r.pda.t_foot;
  const double t_start = std::max(sig.t.front(), r.pda.t_foot - rise);
  const MatchModel model(record, sig, t_start, sig.t[w.first + w.count - 1]);
  r.embedded = record.match.embedded.value_or(record.length());
  for (std::size_t i = 0; i < model.segments(); ++i) {
    r.segment_top.push_back(model.segment_top(i));
    r.segment_bottom.push_back(model.segment_bottom(i));
  }
  const std::vector<double> measured(sig.force.begin() + static_cast<std::ptrdiff_t>(w.first),
                                     sig.force.begin() + static_cast<std::ptrdiff_t>(w.first + w.count));
  double fmax = 0.0;
  for (double f : measured) fmax = std::max(fmax, std::abs(f));
  const MatchSoil estimate = case_estimate(r.pda, model, record.match);
  const double scale = std::max(estimate.capacity(), 1e-6 * fmax) / static_cast<double>(model.segments() + 1);
  const int cores = jobs > 0 ? jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int starts = record.match.starts;
  const FitInputs in{model, record.match, measured, w.first, fmax, scale, std::max(1, cores / starts), interrupt};
  r.starts.resize(static_cast<std::size_t>(starts));
  detail::load_least_squares();  // here: a start's thread must not throw
  run_parallel(static_cast<std::size_t>(starts), std::min(cores, starts), [&](std::size_t k) {
    if (interrupt != nullptr && interrupt->load()) return;
    const MatchSoil start = k == 0 ? estimate : other_start(estimate, record.match, static_cast<int>(k));
    r.starts[k] = fit_from(in, start);
  });
  if (interrupt != nullptr && interrupt->load()) {
    r.interrupted = true;
    return r;
  }
  for (std::size_t k = 0; k < r.starts.size(); ++k) {
    r.evaluations += r.starts[k].evaluations;
    r.iterations += r.starts[k].iterations;
    if (r.starts[k].objective < r.starts[r.best].objective) r.best = k;
  }
  const MatchStart& best = r.starts[r.best];
  if (!std::isfinite(best.quality))
    throw InputError(fmt::format("{}: the matched pile's blow did not stay finite", record.origin.string()));
  r.soil = best.soil;
  r.computed = best.computed;
  r.quality = best.quality;
  r.static_test = static_load_test(model, r.soil);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock).count();
  return r;
}

}  // namespace barimpact
