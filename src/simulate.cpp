#include "barimpact/simulate.hpp"

#include <fmt/format.h>

#include <vector>
#include <chrono>
#include <cmath>

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

RunResult run(const Case& c, const RunOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  auto scheme = make_scheme(c);
  HistoryRecorder history(c.output.every);
  FieldRecorder fields(c, c.output.fields_at);
  ContactMonitor contact(c.obstacle);
  const long long steps = c.step_count();
  ProgressMonitor progress(options.progress, static_cast<double>(steps) * c.time.step, options.progress_interval,
                           options.progress_delay);
  std::vector<Observer*> observers{&history, &fields, &contact};
  if (options.progress) observers.push_back(&progress);
  const LoopResult loop = simulate(*scheme, steps, observers);

  RunResult r;
  Summary& s = r.summary;
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
