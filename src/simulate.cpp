#include "barimpact/simulate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <vector>

#include <cmath>
#include "barimpact/exact.hpp"

namespace barimpact {

LoopResult simulate(Scheme& scheme, long long steps, std::span<Observer* const> observers) {
  LoopResult result;
  for (auto* o : observers) o->begin(scheme, steps);
  scheme.start();
  auto notify = [&] {
    bool go_on = true;
    for (auto* o : observers) go_on = o->observe(scheme) && go_on;
    return go_on;
  };
  if (!scheme.finite()) {
    result.status = RunStatus::non_finite;
    result.message = "the initial state is not finite";
    return result;
  }
  if (!notify()) {
    result.status = RunStatus::stopped;
    return result;
  }
  for (long long n = 1; n <= steps; ++n) {
    scheme.advance();
    if (!scheme.finite()) {
      result.status = RunStatus::non_finite;
      result.message = fmt::format("the state became non-finite at step {} (t = {})", n, scheme.time());
      return result;
    }
    result.steps_done = n;
    if (!notify()) {
      result.status = RunStatus::stopped;
      result.message = fmt::format("stopped by an observer at step {} (t = {})", n, scheme.time());
      return result;
    }
  }
  return result;
}

namespace {

RunResult run_scheme(const Case& c, Scheme& scheme, long long steps, const RunOptions& options);

}  // namespace

RunResult run(const Case& c, const RunOptions& options) {
  auto scheme = make_scheme(c);
  return run_scheme(c, *scheme, c.step_count(), options);
}

RunResult run_exact(const Case& c) {
  std::shared_ptr<const exact::Solution> solution = exact::for_case(c);
  if (!solution)
    throw InputError(
        "exact: this case admits no exact solution barimpact knows (uniform elastic bar, u0 = 0 and uniform v0 < 0 "
        "against a rigid obstacle with gap, or with a constant load, or against an elastic obstacle; or the clamped "
        "bar released from u0 = kappa (L - x) onto a rigid obstacle)");
  auto scheme = exact::as_scheme(c, solution);
  const double known = solution->valid_until();
  long long steps = c.step_count();
  if (std::isfinite(known)) steps = std::min(steps, static_cast<long long>(std::floor(known / c.time.step)));
  RunResult r = run_scheme(c, *scheme, steps, {});
  r.summary.method = "exact";
  r.summary.message = solution->name();
  return r;
}

namespace {

RunResult run_scheme(const Case& c, Scheme& scheme_ref, long long steps, const RunOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  Scheme* scheme = &scheme_ref;
  HistoryRecorder history(c.output.every);
  FieldRecorder fields(c, c.output.fields_at);
  ContactMonitor contact(c.obstacle);
  ProgressMonitor progress(options.progress, static_cast<double>(steps) * c.time.step, options.progress_interval,
                           options.progress_delay);
  std::vector<Observer*> observers{&history, &fields, &contact};
  if (options.progress) observers.push_back(&progress);
  const LoopResult loop = simulate(*scheme, steps, observers);

  RunResult r;
  Summary& s = r.summary;
  s.method = c.time.scheme;
  s.status = loop.status;
  s.complete = loop.status == RunStatus::complete;
  s.message = loop.message;
  s.steps = steps;
  s.steps_done = loop.steps_done;
  s.t_end = static_cast<double>(loop.steps_done) * c.time.step;
  s.contacts = contact.intervals();
  s.max_penetration = contact.max_penetration();
  s.max_reaction = contact.max_reaction();
  r.history = history.rows();
  if (!r.history.empty()) {
    auto total = [](const HistoryRow& h) { return h.E_kin + h.E_strain + h.E_obstacle - h.W_ext + h.D_visc; };
    s.energy_initial = total(r.history.front());
    s.energy_final = total(r.history.back());
    for (const auto& h : r.history)
      s.energy_error_max = std::max(s.energy_error_max, std::abs(total(h) - s.energy_initial));
  }
  r.fields = fields.take();
  s.run_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return r;
}

}  // namespace

std::string_view to_string(RunStatus status) {
  switch (status) {
    case RunStatus::complete:
      return "complete";
    case RunStatus::non_finite:
      return "non-finite";
    case RunStatus::stopped:
      return "stopped";
  }
  return "?";
}

}  // namespace barimpact
