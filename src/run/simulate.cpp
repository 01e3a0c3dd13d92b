#include "barimpact/run/simulate.hpp"

#include "barimpact/case/line_builder.hpp"
#include "barimpact/model/setup_polling.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <vector>

#include <cmath>
#include "barimpact/run/check.hpp"
#include "barimpact/run/health.hpp"
#include "barimpact/run/residual.hpp"
#include "barimpact/schemes/paper_scheme.hpp"
#include "barimpact/schemes/registry.hpp"

namespace barimpact {

namespace {

// One scheme as the loop's only lane.
class OneLane final : public LaneStepper {
 public:
  explicit OneLane(Scheme& s) : s_(s) {}
  [[nodiscard]] std::size_t lanes() const override { return 1; }
  [[nodiscard]] Scheme& lane(std::size_t /*i*/) override { return s_; }
  void start() override { s_.start(); }
  void advance() override { s_.advance(); }

 private:
  Scheme& s_;
};

// Whether a lane goes on after its step `n` (0: the start): its state
// finite and every observer content. Else its result says why.
bool observe(Scheme& s, long long n, std::span<Observer* const> observers, LoopResult& result) {
  if (!s.finite()) {
    result.status = RunStatus::non_finite;
    const std::string why = s.failure();
    result.message = n == 0        ? std::string("the initial state is not finite")
                     : why.empty() ? fmt::format("the state became non-finite at step {} (t = {})", n, s.time())
                                   : fmt::format("{} at step {} (t = {})", why, n, s.time());
    return false;
  }
  result.steps_done = n;
  bool go_on = true;
  for (auto* o : observers) go_on = o->observe(s) && go_on;
  if (!go_on) {
    result.status = RunStatus::stopped;
    if (n > 0) result.message = fmt::format("stopped by an observer at step {} (t = {})", n, s.time());
  }
  return go_on;
}

}  // namespace

std::vector<LoopResult> simulate(LaneStepper& lanes, long long steps, std::span<const std::vector<Observer*>> observers,
                                 const std::atomic<bool>* interrupt) {
  const std::size_t count = lanes.lanes();
  std::vector<LoopResult> results(count);
  std::vector<char> live(count, 1);
  std::size_t left = count;
  for (std::size_t l = 0; l < count; ++l)
    for (auto* o : observers[l]) o->begin(lanes.lane(l), steps);
  lanes.start();
  for (long long n = 0; n <= steps && left > 0; ++n) {
    if (n > 0) lanes.advance();
    for (std::size_t l = 0; l < count; ++l)
      if (live[l] && !observe(lanes.lane(l), n, observers[l], results[l])) {
        live[l] = 0;
        --left;
      }
    if (interrupt != nullptr && interrupt->load(std::memory_order_relaxed) && n > 0 && n < steps) {
      for (std::size_t l = 0; l < count; ++l)
        if (live[l]) {
          results[l].status = RunStatus::interrupted;
          results[l].message = fmt::format("interrupted at step {} (t = {})", n, lanes.lane(l).time());
        }
      break;
    }
  }
  for (std::size_t l = 0; l < count; ++l)
    for (auto* o : observers[l]) o->end(lanes.lane(l));
  return results;
}

LoopResult simulate(Scheme& scheme, long long steps, std::span<Observer* const> observers,
                    const std::atomic<bool>* interrupt) {
  OneLane one(scheme);
  const std::vector<std::vector<Observer*>> lane{{observers.begin(), observers.end()}};
  return simulate(one, steps, lane, interrupt).front();
}

RunRecorder::RunRecorder(const Case& c, const Scheme& scheme, FieldSink* fields)
    : case_(c),
      own_(scheme.line() ? std::nullopt : std::optional<Line>(build_line(c))),
      line_(scheme.line() ? *scheme.line() : *own_),
      probes_(c, line_),
      history_(c.output.every, &probes_),
      fields_(c, line_, c.output.fields_at, fields),
      contact_(line_, c.time.step),
      links_(line_),
      plastic_(line_, c.output.every) {
  if (reports_blow(c, line_)) blow_.emplace(c, line_);
  observers_ = {&history_, &fields_, &contact_, &links_, &plastic_};
  if (blow_) observers_.push_back(&*blow_);
}

namespace {

// A run whose set-up its interrupt ended: no step taken.
RunResult interrupted_setup(const Case& c, const Interrupted& e) {
  RunResult r;
  r.summary.method = c.time.scheme;
  r.summary.complete = false;
  r.summary.status = RunStatus::interrupted;
  r.summary.message = e.what();
  r.summary.steps = c.step_count();
  return r;
}

}  // namespace

RunResult run(const Case& c, const RunOptions& options) {
  (void)check_resources(c, options.fields != nullptr);  // before fitting builds the line
  const SetupPolling polling(options.interrupt);        // a study's case: its set-up polls too
  try {
    return run(fit_scheme(c), options);
  } catch (const Interrupted& e) {
    return interrupted_setup(c, e);
  }
}

namespace {

RunResult run_one(FittedCase fitted, const RunOptions& options) {
  auto scheme = make_scheme(fitted);
  return run_scheme(fitted.c, *scheme, fitted.c.step_count(), options);
}

bool within_percent(double a, double b) {
  return std::abs(a - b) <= 0.01 * std::abs(b);
}

// A diesel hammer's blows at one soil (issue 32's stroke iteration): the
// first from the case's stroke (its max_stroke unless given), each next
// from the previous blow's rebound capped at max_stroke, until both set and
// stroke change by less than 1% from one blow to the next (at most 20). The
// last blow is the result; its summary gives the stroke, the first blow's
// set and the blows run.
RunResult run_diesel(const FittedCase& fitted, const RunOptions& options) {
  constexpr int most = 20;
  const DieselData& d = fitted.c.hammer->diesel;
  double stroke = fitted.c.hammer->stroke, first_set = 0.0, set = 0.0;
  RunResult r;
  RunOptions held = options;
  held.fields = nullptr;  // each blow's snapshots held: only the last's are the result's
  std::string stopped;    // why the iteration ended before it converged
  int blows = 1;
  for (;; ++blows) {
    Case c = fitted.c;
    start_ram(c, stroke);
    r = run_one(fit_scheme(std::move(c)), held);
    if (r.summary.status != RunStatus::complete || !r.summary.blow) return r;
    const BlowSummary& b = *r.summary.blow;
    if (blows == 1) first_set = b.set;
    const double next = std::min(b.next_stroke, d.max_stroke);
    if (blows > 1 && within_percent(b.set, set) && within_percent(next, stroke)) break;
    if (!(next > d.compression_length)) {
      stopped = std::isnan(b.next_stroke)
                    ? "the ram did not rise back past the ports by time.end (raise it)"
                    : fmt::format("the ram rose {:.4g} m, not past the ports: the hammer stalls", b.next_stroke);
      break;
    }
    if (blows == most) {
      stopped = fmt::format("set and stroke still changed by 1% or more after {} blows", most);
      break;
    }
    set = b.set;
    stroke = next;
  }
  BlowSummary& b = *r.summary.blow;
  // A diesel hammer's energy is its rated one, m g H (the gas works on the
  // ram before impact and on the anvil after): ENTHRU's share of it is the
  // transfer ratio analysers report.
  for (const auto& body : fitted.c.bodies)
    if (body.name == fitted.c.hammer->ram) b.hammer_energy = body.mass * drive_gravity(fitted.c.load.gravity) * stroke;
  b.stroke = stroke;
  b.first_set = first_set;
  b.blows_run = blows;
  if (!stopped.empty())
    r.summary.warnings.push_back(
        fmt::format("diesel-stroke: after {} blows from {:.4g} m: {}", blows, fitted.c.hammer->stroke, stopped));
  return r;
}

}  // namespace

bool repeats_blows(const Case& c) {
  return (c.drive && c.drive->blows > 1) || (c.hammer && c.hammer->kind == HammerKind::diesel);
}

RunResult run(FittedCase fitted, const RunOptions& options) {
  if (fitted.c.drive && fitted.c.drive->blows > 1) return run_residual(fitted, options);
  if (fitted.c.hammer && fitted.c.hammer->kind == HammerKind::diesel) return run_diesel(fitted, options);
  return run_one(std::move(fitted), options);
}

RunResult run_scheme(const Case& c, Scheme& scheme_ref, long long steps, const RunOptions& options, bool finite_rows) {
  const auto started = std::chrono::steady_clock::now();
  // A pile under gravity starts at rest on its soil (issue 33: else its own
  // weight is a load that moves the set).
  const bool unsettled = c.load.gravity > 0.0 && c.smith_soil() && !start_at_rest(c, scheme_ref);
  ProgressMonitor progress(options.progress, static_cast<double>(steps) * c.time.step, options.progress_interval,
                           options.progress_delay);
  RunRecorder rec(c, scheme_ref, options.fields);
  std::vector<Observer*> observers = rec.observers();
  if (options.progress) observers.push_back(&progress);
  poll_setup();
  if (options.loop_begins) options.loop_begins();
  const SetupPolling set_up(nullptr);  // the loop polls its own way: what it ran is the result
  const LoopResult loop = simulate(scheme_ref, steps, observers, options.interrupt);
  RunResult r = rec.finish(loop, steps, started, finite_rows);
  if (unsettled)
    r.summary.warnings.push_back(fmt::format(
        "gravity-start: time.scheme = \"{}\" starts the pile where the case puts it, not at rest on its soil under "
        "gravity (central-difference does): its own weight loads the soil during the blow",
        c.time.scheme));
  return r;
}

namespace {

// The state can stay finite while what is read off it overflows (a
// blowing-up run squares (u^{n+1} - u^n)/dt in its energies first): the
// first row that is not finite ends a complete run there, as a non-finite
// state would.
void cut_at_non_finite_row(RunResult& r, LoopResult& loop, double dt) {
  const auto bad = std::find_if(r.history.begin(), r.history.end(), [](const HistoryRow& h) {
    return !(std::isfinite(h.t) && std::isfinite(h.U) && std::isfinite(h.V) && std::isfinite(h.R) &&
             std::isfinite(h.E_kin) && std::isfinite(h.E_strain) && std::isfinite(h.E_obstacle) &&
             std::isfinite(h.W_ext) && std::isfinite(h.D_visc) && std::isfinite(h.D_contact) &&
             std::isfinite(h.D_plastic));
  });
  if (bad == r.history.end()) return;
  r.extra.resize(static_cast<std::size_t>(bad - r.history.begin()) * r.columns.size());
  const long long step = std::llround(bad->t / dt);
  loop.status = RunStatus::non_finite;
  loop.message = fmt::format("the history became non-finite at step {} (t = {})", step, bad->t);
  loop.steps_done = std::max(0LL, step - 1);
  r.history.erase(bad, r.history.end());
}

// E_total at the first and last rows and its largest departure.
void book_energy(const std::vector<HistoryRow>& history, Summary& s) {
  if (history.empty()) return;
  s.energy_initial = history.front().total();
  s.energy_final = history.back().total();
  for (const auto& h : history)
    s.energy_error_max = std::max(s.energy_error_max, std::abs(h.total() - s.energy_initial));
}

}  // namespace

namespace {

// A tension the stress wave cannot yet have brought (BlowSummary::precursor)
// that is a tenth of the reported max_tension or more: the scheme's
// oscillation behind a steep front, passed off as a driving stress.
void check_precursor(const Case& c, const BlowSummary& b, std::vector<std::string>& warnings) {
  const StressPeak& p = b.precursor;
  if (!(p.value > 0.1 * b.max_tension.value && p.value > 1e-3 * b.max_compression.value)) return;
  warnings.push_back(fmt::format(
      "spurious-oscillation: {} puts {:.4g} of tension at x = {:.4g}, t = {:.4g}, before the stress wave can "
      "reach it (max_tension {:.4g}): its driving stresses oscillate behind the steep front; central-difference at "
      "its stable step (time.step = \"auto\") gives them",
      c.time.scheme, p.value, p.x, p.t, b.max_tension.value));
}

}  // namespace

RunResult RunRecorder::finish(LoopResult loop, long long steps, std::chrono::steady_clock::time_point started,
                              bool finite_rows) {
  const Case& c = case_;
  RunResult r;
  r.history = history_.rows();
  r.columns = probes_.names();
  r.extra = history_.extra();
  if (finite_rows && loop.status == RunStatus::complete) cut_at_non_finite_row(r, loop, c.time.step);
  Summary& s = r.summary;
  s.method = c.time.scheme;
  s.status = loop.status;
  s.complete = loop.status == RunStatus::complete;
  s.message = loop.message;
  s.steps = steps;
  s.steps_done = loop.steps_done;
  s.t_end = static_cast<double>(loop.steps_done) * c.time.step;
  s.contacts = contact_.intervals();
  s.link_names = links_.names();
  s.link_episodes = links_.episodes();
  s.max_penetration = contact_.max_penetration();
  s.max_reaction = contact_.max_reaction();
  s.max_impact_impulse = contact_.max_impact_impulse();
  if (plastic_.any()) s.plastic = plastic_summary();
  book_energy(r.history, s);
  r.fields = fields_.take();
  s.warnings = check_health(c, line_, s, r.history);
  if (blow_) {
    s.blow = blow_->summary();
    if (!s.blow->impact && s.complete)
      s.warnings.push_back(fmt::format(
          "blow-no-impact: the ram \"{}\" never struck the pile by t = {:.6g}: no set, no blow counts (check the "
          "ram's velocity, towards the pile, and [blow] ram)",
          s.blow->ram, s.t_end));
    else if (!s.blow->finished && s.complete)
      s.warnings.push_back(fmt::format(
          "blow-unfinished: the pile had not come to rest by t = {:.6g} (every node below 1% of the impact velocity "
          "{:.4g} after the soil's last slip): the set and blow counts may still change; raise time.end",
          s.t_end, std::abs(s.blow->impact_velocity)));
    check_precursor(c, *s.blow, s.warnings);
  }
  s.run_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return r;
}

PlasticSummary RunRecorder::plastic_summary() const {
  PlasticSummary p;
  p.largest_strain = plastic_.largest();
  const std::size_t j = plastic_.bond();
  p.body = line_.bodies[line_.bonds[j].body].name;
  p.x = 0.5 * (line_.x[j] + line_.x[j + 1]);
  p.t = plastic_.time();
  for (std::size_t b = 0; b < line_.bodies.size(); ++b)
    if (line_.plasticity[b]) p.work.emplace_back(line_.bodies[b].name, plastic_.work()[b]);
  return p;
}

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
