#include "barimpact/run/check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "barimpact/case/line_builder.hpp"
#include "barimpact/run/simulate.hpp"
#include "barimpact/schemes/line_scheme.hpp"
#include "barimpact/schemes/registry.hpp"

namespace barimpact {

namespace {

// The stable step and how it is decided, scheme by scheme (scheme.hpp,
// health.hpp): the explicit ones by a Gershgorin bound with the mass matrix
// they use, the implicit ones below the trapezoidal rule by omega_max.
void read_stability(const Case& c, CaseCheck& k) {
  const SchemeInfo& s = scheme_info(c.time.scheme);
  if (s.step == StepRule::limited) {
    const bool consistent = s.mass == MassMatrix::consistent;
    k.stable_step = line_stable_step(build_line(c), consistent);
    k.mass = consistent ? "consistent" : "lumped";
    k.stability = "explicit: steps above the stable step are refused";
  } else if (s.step == StepRule::transit) {
    k.stability = fmt::format("{}: dt = h/c, exact at the nodes", s.name);
  } else if ((k.stable_step = conditional_stable_step(c))) {
    k.mass = "consistent";
    k.stability = fmt::format("implicit, conditionally stable ({})", s.family(c).rule);
  } else {
    k.stability = "implicit, unconditionally stable";
  }
}

// Runs the first `steps` steps of `c` (no field snapshots) and returns
// their wall time; `trouble` says where the state became non-finite.
double time_steps(const Case& c, long long steps, std::string& trouble) {
  Case probe = c;
  probe.time.end = static_cast<double>(steps) * c.time.step;
  probe.output.fields_at.clear();
  const auto start = std::chrono::steady_clock::now();
  const RunResult r = run(probe);
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  if (!r.summary.complete) trouble = r.summary.message;
  return elapsed.count();
}

}  // namespace

CaseCheck check_case(const Case& c, double timing_budget) {
  CaseCheck k;
  k.steps = c.step_count();
  k.nodes = build_line(c).nodes();
  read_stability(c, k);
  k.penalties = penalty_time_constants(c);
  // Enough steps to time reliably (about timing_budget node-steps, a few
  // milliseconds), at least 20, never more than the run has.
  const auto budget = static_cast<long long>(timing_budget / static_cast<double>(k.nodes));
  k.timed_steps = std::min(k.steps, std::clamp(budget, 20LL, 100'000LL));
  k.timed_seconds = time_steps(c, k.timed_steps, k.trouble);
  k.estimate_seconds = k.timed_seconds * static_cast<double>(k.steps) / static_cast<double>(k.timed_steps);
  return k;
}

std::string check_text(const Case& c, const CaseCheck& k) {
  std::string out = fmt::format("scheme: {}\n", c.time.scheme);
  out += fmt::format("steps: {} (dt = {:.4g} to t = {:.4g}, {} nodes)\n", k.steps, c.time.step,
                     static_cast<double>(k.steps) * c.time.step, k.nodes);
  if (k.stable_step && std::isfinite(*k.stable_step))
    out += fmt::format("stable step: {:.4g} ({} mass); dt is {:.3g} of it\n", *k.stable_step, k.mass,
                       c.time.step / *k.stable_step);
  else if (k.stable_step)
    out += fmt::format("stable step: none (nothing stiff in the line, {} mass)\n", k.mass);
  out += fmt::format("stability: {}\n", k.stability);
  for (const auto& p : k.penalties)
    out += fmt::format("penalty: tau = {:.4g}, dt/tau = {:.3g}{} ({}, {})\n", p.tau, c.time.step / p.tau,
                       c.time.step > p.tau ? " not resolved" : "", p.link, p.basis);
  if (k.timed_steps == k.steps)
    out += fmt::format("time estimate: {:.2g} s (the whole run, timed)\n", k.estimate_seconds);
  else
    out += fmt::format("time estimate: {:.2g} s (from {} timed steps)\n", k.estimate_seconds, k.timed_steps);
  if (!k.trouble.empty()) out += fmt::format("trouble: {}\n", k.trouble);
  return out;
}

}  // namespace barimpact
