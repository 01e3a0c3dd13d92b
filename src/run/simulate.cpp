#include "barimpact/run/simulate.hpp"

#include "barimpact/case/line_builder.hpp"
#include "barimpact/exact/lines.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <vector>

#include <cmath>
#include "barimpact/exact/exact.hpp"
#include "barimpact/run/health.hpp"
#include "barimpact/schemes/paper_scheme.hpp"
#include "barimpact/schemes/registry.hpp"

namespace barimpact {

LoopResult simulate(Scheme& scheme, long long steps, std::span<Observer* const> observers,
                    const std::atomic<bool>* interrupt) {
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
      const std::string why = scheme.failure();
      result.message = why.empty() ? fmt::format("the state became non-finite at step {} (t = {})", n, scheme.time())
                                   : fmt::format("{} at step {} (t = {})", why, n, scheme.time());
      return result;
    }
    result.steps_done = n;
    if (!notify()) {
      result.status = RunStatus::stopped;
      result.message = fmt::format("stopped by an observer at step {} (t = {})", n, scheme.time());
      return result;
    }
    if (interrupt != nullptr && interrupt->load(std::memory_order_relaxed) && n < steps) {
      result.status = RunStatus::interrupted;
      result.message = fmt::format("interrupted at step {} (t = {})", n, scheme.time());
      return result;
    }
  }
  return result;
}

namespace {

RunResult run_scheme(const Case& c, Scheme& scheme, long long steps, const RunOptions& options,
                     bool finite_rows = true);

// The observers of one run and the summary they add up to.
// What the near-end contact monitor watches: the obstacle of a single bar,
// or the near end's unilateral law on a line (none for free, held or loaded ends).
ObstacleData near_obstacle(const Case& c) {
  if (c.single_bar) return c.obstacle;
  ObstacleData o;
  const JointLaw law = c.near_end.law;
  o.kind = law == JointLaw::rigid                                                           ? ObstacleKind::rigid
           : law == JointLaw::elastic || law == JointLaw::cushion || law == JointLaw::smith ? ObstacleKind::elastic
           : law == JointLaw::viscoelastic                                                  ? ObstacleKind::viscoelastic
                                                                                            : ObstacleKind::none;
  o.stiffness = c.near_end.stiffness;
  o.gap = c.near_end.gap;
  o.viscosity = c.near_end.viscosity;
  return o;
}

struct Recorders {
  std::optional<Line> own;  // built only for a scheme that holds no line (the fused one-bar paper scheme)
  const Line& line;
  Probes probes;
  HistoryRecorder history;
  FieldRecorder fields;
  ContactMonitor contact;
  LinkMonitor links;
  PlasticMonitor plastic;
  std::optional<BlowMonitor> blow;
  Recorders(const Case& c, const Scheme& scheme)
      : own(scheme.line() ? std::nullopt : std::optional<Line>(build_line(c))),
        line(scheme.line() ? *scheme.line() : *own),
        probes(c, line),
        history(c.output.every, &probes),
        fields(c, line, c.output.fields_at),
        contact(near_obstacle(c)),
        links(line),
        plastic(line, c.output.every) {
    if (reports_blow(c, line)) blow.emplace(c, line);
    observers = {&history, &fields, &contact, &links, &plastic};
    if (blow) observers.push_back(&*blow);
  }
  Recorders(const Recorders&) = delete;  // blow watches `line`, observers point into it
  const std::vector<Observer*>& all() const { return observers; }
  std::vector<Observer*> observers;
};

RunResult collect(const Case& c, LoopResult loop, long long steps, Recorders& rec,
                  std::chrono::steady_clock::time_point started, bool finite_rows = true);

}  // namespace

RunResult run(const Case& c, const RunOptions& options) {
  auto scheme = make_scheme(c);
  return run_scheme(c, *scheme, c.step_count(), options);
}

std::vector<RunResult> run_batch(const std::vector<const Case*>& cases, const std::atomic<bool>* interrupt) {
  const auto started = std::chrono::steady_clock::now();
  PaperBatch batch(cases);
  const long long steps = cases.front()->step_count();
  std::vector<std::unique_ptr<Recorders>> rec;
  std::vector<LoopResult> loops(cases.size());
  std::vector<bool> live(cases.size(), true);
  for (std::size_t l = 0; l < cases.size(); ++l) {
    rec.push_back(std::make_unique<Recorders>(*cases[l], batch.lane(l)));
    for (auto* o : rec[l]->all()) o->begin(batch.lane(l), steps);
  }
  batch.start();
  // The loop of simulate(), lane by lane: a lane that turns non-finite stops
  // being observed (its numbers keep being computed, and are ignored).
  auto observe = [&](std::size_t l) {
    Scheme& s = batch.lane(l);
    if (!s.finite()) {
      live[l] = false;
      loops[l].status = RunStatus::non_finite;
      loops[l].message = s.step() == 0
                             ? std::string("the initial state is not finite")
                             : fmt::format("the state became non-finite at step {} (t = {})", s.step(), s.time());
      return;
    }
    loops[l].steps_done = s.step();
    for (auto* o : rec[l]->all()) o->observe(s);
  };
  for (std::size_t l = 0; l < cases.size(); ++l) observe(l);
  for (long long n = 1; n <= steps && std::find(live.begin(), live.end(), true) != live.end(); ++n) {
    batch.advance();
    for (std::size_t l = 0; l < cases.size(); ++l)
      if (live[l]) observe(l);
    if (interrupt != nullptr && interrupt->load(std::memory_order_relaxed) && n < steps) {
      for (std::size_t l = 0; l < cases.size(); ++l)
        if (live[l]) {
          loops[l].status = RunStatus::interrupted;
          loops[l].message = fmt::format("interrupted at step {} (t = {})", n, batch.lane(l).time());
        }
      break;
    }
  }
  std::vector<RunResult> out;
  for (std::size_t l = 0; l < cases.size(); ++l) {
    out.push_back(collect(*cases[l], loops[l], steps, *rec[l], started));
    out.back().summary.run_seconds /= static_cast<double>(cases.size());  // each lane's share of the batch
  }
  return out;
}

namespace {
// An exact solution tabulated as a run, up to where it is known (the
// case's end, or the solution's horizon: then said in a warning).
RunResult run_known(const Case& c, Scheme& scheme, double known, const std::string& name, const RunOptions& options) {
  long long steps = c.step_count();
  if (std::isfinite(known)) steps = std::min(steps, static_cast<long long>(std::floor(known / c.time.step)));
  RunResult r = run_scheme(c, scheme, steps, options, false);
  r.summary.method = "exact";
  r.summary.message = name;
  if (steps < c.step_count())
    r.summary.warnings.push_back(
        fmt::format("exact-horizon: the exact solution is known up to t = {:.6g} only; tabulated to t = {:.6g}, not to "
                    "time.end = {:.6g}",
                    known, static_cast<double>(steps) * c.time.step, c.time.end));
  return r;
}

RunResult run_exact_line(const Case& c, const RunOptions& options) {
  std::shared_ptr<const exact::LineSolution> solution = exact::for_line_case(c);
  if (!solution)
    throw InputError(
        "exact: this line admits no exact solution barimpact knows (two free bars of one material through a rigid "
        "joint; a mass on a rigid joint striking a bar clamped at x = 0; two welded bars under a constant force at x "
        "= 0; each at rest or in uniform motion, without viscosity, body force or gravity; or von Karman's "
        "elastic-plastic bar, E_t > 0, driven at a constant velocity at x = 0 or moving onto a rigid wall)");
  auto scheme = exact::as_line_scheme(c, solution);
  return run_known(c, *scheme, solution->valid_until(), solution->name(), options);
}
}  // namespace

RunResult run_exact(const Case& c, const RunOptions& options) {
  if (!c.single_bar) return run_exact_line(c, options);
  std::shared_ptr<const exact::Solution> solution = exact::for_case(c);
  if (!solution)
    throw InputError(
        "exact: this case admits no exact solution barimpact knows (uniform elastic bar, u0 = 0 and uniform v0 < 0 "
        "against a rigid obstacle with gap, or with a constant load, or against an elastic obstacle; or the clamped "
        "bar released from u0 = kappa (L - x) onto a rigid obstacle)");
  auto scheme = exact::as_scheme(c, solution);  // energies are NaN where u(x, t) is not known
  return run_known(c, *scheme, solution->valid_until(), solution->name(), options);
}

namespace {

RunResult run_scheme(const Case& c, Scheme& scheme_ref, long long steps, const RunOptions& options, bool finite_rows) {
  const auto started = std::chrono::steady_clock::now();
  ProgressMonitor progress(options.progress, static_cast<double>(steps) * c.time.step, options.progress_interval,
                           options.progress_delay);
  Recorders rec(c, scheme_ref);
  std::vector<Observer*> observers = rec.all();
  if (options.progress) observers.push_back(&progress);
  const LoopResult loop = simulate(scheme_ref, steps, observers, options.interrupt);
  return collect(c, loop, steps, rec, started, finite_rows);
}

RunResult collect(const Case& c, LoopResult loop, long long steps, Recorders& rec,
                  std::chrono::steady_clock::time_point started, bool finite_rows) {
  RunResult r;
  r.history = rec.history.rows();
  r.columns = rec.probes.names();
  r.extra = rec.history.extra();
  if (finite_rows && loop.status == RunStatus::complete) {
    // The state can stay finite while what is read off it overflows (a
    // blowing-up run squares (u^{n+1} - u^n)/dt in its energies first): the
    // first row that is not finite ends the run there, as a non-finite state would.
    const auto bad = std::find_if(r.history.begin(), r.history.end(), [](const HistoryRow& h) {
      return !(std::isfinite(h.t) && std::isfinite(h.U) && std::isfinite(h.V) && std::isfinite(h.R) &&
               std::isfinite(h.E_kin) && std::isfinite(h.E_strain) && std::isfinite(h.E_obstacle) &&
               std::isfinite(h.W_ext) && std::isfinite(h.D_visc) && std::isfinite(h.D_contact) &&
               std::isfinite(h.D_plastic));
    });
    if (bad != r.history.end()) {
      r.extra.resize(static_cast<std::size_t>(bad - r.history.begin()) * r.columns.size());
      const long long step = std::llround(bad->t / c.time.step);
      loop.status = RunStatus::non_finite;
      loop.message = fmt::format("the history became non-finite at step {} (t = {})", step, bad->t);
      loop.steps_done = std::max(0LL, step - 1);
      r.history.erase(bad, r.history.end());
    }
  }
  Summary& s = r.summary;
  s.method = c.time.scheme;
  s.status = loop.status;
  s.complete = loop.status == RunStatus::complete;
  s.message = loop.message;
  s.steps = steps;
  s.steps_done = loop.steps_done;
  s.t_end = static_cast<double>(loop.steps_done) * c.time.step;
  s.contacts = rec.contact.intervals();
  s.link_names = rec.links.names();
  s.link_episodes = rec.links.episodes();
  s.max_penetration = rec.contact.max_penetration();
  s.max_reaction = rec.contact.max_reaction();
  if (rec.plastic.any()) {
    PlasticSummary& p = s.plastic.emplace();
    p.largest_strain = rec.plastic.largest();
    const std::size_t j = rec.plastic.bond();
    p.body = rec.line.bodies[rec.line.bonds[j].body].name;
    p.x = 0.5 * (rec.line.x[j] + rec.line.x[j + 1]);
    p.t = rec.plastic.time();
    for (std::size_t b = 0; b < rec.line.bodies.size(); ++b)
      if (rec.line.plasticity[b]) p.work.emplace_back(rec.line.bodies[b].name, rec.plastic.work()[b]);
  }
  if (!r.history.empty()) {
    auto total = [](const HistoryRow& h) { return h.total(); };
    s.energy_initial = total(r.history.front());
    s.energy_final = total(r.history.back());
    for (const auto& h : r.history)
      s.energy_error_max = std::max(s.energy_error_max, std::abs(total(h) - s.energy_initial));
  }
  r.fields = rec.fields.take();
  s.warnings = check_health(c, rec.line, s, r.history);
  if (rec.blow) {
    s.blow = rec.blow->summary();
    if (!s.blow->finished && s.complete)
      s.warnings.push_back(fmt::format(
          "blow-unfinished: the pile had not come to rest by t = {:.6g} (every node below 1% of the impact velocity "
          "{:.4g} after the soil's last slip): the set and blow counts may still change; raise time.end",
          s.t_end, std::abs(s.blow->impact_velocity)));
  }
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
    case RunStatus::interrupted:
      return "interrupted";
  }
  return "?";
}

}  // namespace barimpact
