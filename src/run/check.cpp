#include "barimpact/run/check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <string>

#include <sys/resource.h>

#include "barimpact/case/line_builder.hpp"
#include "barimpact/model/input_error.hpp"
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

// The memory model (bytes a run adds to the process at its peak):
//   per node: the line, the scheme with its factors and the observers'
//     per-node arrays, measured scheme by scheme (the scheme table's
//     bytes_per_node: a bar alone, a line of bodies, an elastic-plastic bar);
//   per history row: its values, held twice at the end (the recorder's
//     and the result's);
//   field snapshots: one (u, v, sigma, eps_p of every node) while they
//     stream to the run directory, all of them where the caller holds them;
//   results.h5: written as the run goes; HDF5 holds a few chunks of each
//     of the four fields (its chunk caches, 1 MiB each at most).
double bytes_per_node(const Case& c) {
  const NodeBytes& b = scheme_info(c.time.scheme).bytes_per_node;
  const bool plastic = std::any_of(c.bodies.begin(), c.bodies.end(), [](const BodyData& body) {
    return body.kind == BodyKind::bar && body.material.kind == MaterialKind::plastic;
  });
  if (plastic) return b.plastic;
  return c.one_bar() ? b.one_bar : b.line;
}

// Bytes of a history value and of a fields.csv row as written (shortest
// round-trip doubles): measured on Example 1 at 10^5 elements, dt = 10^-5
// (a field still at rest writes shorter rows).
constexpr double csv_value_bytes = 12.0;
constexpr double fields_row_bytes = 92.0;
// HDF5's default chunk cache of a dataset.
constexpr double h5_chunk_cache_bytes = 1024.0 * 1024.0;

// The history's columns: the budget's and the probes' (probe.cpp).
std::size_t history_columns(const Case& c) {
  std::size_t n = budget_columns.size() + 2 * c.joints.size() + 3 * c.gauges.size();
  if (c.far_end.law != JointLaw::free) n += 2;
  for (const auto& b : c.bodies)
    if (b.kind == BodyKind::mass) n += 2;
  return n;
}

// The snapshots' distinct steps, as FieldRecorder takes them (before the
// step is fitted, "auto": each time its own).
std::size_t snapshot_count(const Case& c) {
  if (c.time.step_auto) return c.output.fields_at.size();
  std::vector<long long> steps;
  for (double t : c.output.fields_at) steps.push_back(std::clamp(std::llround(t / c.time.step), 0LL, c.step_count()));
  std::sort(steps.begin(), steps.end());
  return static_cast<std::size_t>(std::unique(steps.begin(), steps.end()) - steps.begin());
}

// A value of /proc's "Key:   N kB" lines, in bytes; infinity when absent.
double proc_kilobytes(const char* file, std::string_view key) {
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);)
    if (line.starts_with(key) && line.size() > key.size() && line[key.size()] == ':')
      return 1024.0 * std::stod(line.substr(key.size() + 1));
  return std::numeric_limits<double>::infinity();
}

std::string gigabytes(double bytes) {
  return bytes >= 1e9 ? fmt::format("{:.3g} GB", bytes / 1e9) : fmt::format("{:.3g} MB", bytes / 1e6);
}

// The key that sets the most elements: bar.elements for one bar, else the
// largest body's.
std::string elements_key(const Case& c) {
  if (c.one_bar() && c.bodies.size() == 1) return "bar.elements";
  const auto largest = std::max_element(c.bodies.begin(), c.bodies.end(), [](const BodyData& a, const BodyData& b) {
    return (a.kind == BodyKind::bar ? a.elements : 0) < (b.kind == BodyKind::bar ? b.elements : 0);
  });
  return "body." + largest->name + ".elements";
}

}  // namespace

ResourceEstimate estimate_resources(const Case& c, bool streamed_fields) {
  ResourceEstimate e;
  for (const auto& b : c.bodies) e.nodes += b.kind == BodyKind::bar ? static_cast<std::size_t>(b.elements) + 1 : 1;
  e.history_rows = c.time.step_auto ? 0 : c.step_count() / c.output.every + 2;  // "auto": not known yet
  e.snapshots = snapshot_count(c);
  const auto nodes = static_cast<double>(e.nodes), rows = static_cast<double>(e.history_rows);
  const auto snapshots = static_cast<double>(e.snapshots);
  const double columns = static_cast<double>(history_columns(c));
  const bool h5 = c.output.format == OutputFormat::hdf5;
  e.output_bytes = h5 ? 8.0 * (rows * columns + 4.0 * nodes * snapshots + nodes)
                      : rows * columns * csv_value_bytes + nodes * snapshots * fields_row_bytes;
  // A snapshot's rows (x, node, body) and its values (u, v, sigma, eps_p).
  const double held = streamed_fields ? std::min(snapshots, 1.0) : snapshots;
  const double fields = e.snapshots > 0 ? 24.0 * nodes + 32.0 * nodes * held : 0.0;
  e.memory_bytes = bytes_per_node(c) * nodes + 2.0 * 8.0 * rows * columns + fields;
  if (h5) e.memory_bytes += 4.0 * h5_chunk_cache_bytes;
  return e;
}

double available_memory() {
  double available = proc_kilobytes("/proc/meminfo", "MemAvailable");
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    const double used = proc_kilobytes("/proc/self/status", "VmSize");
    const double left = static_cast<double>(limit.rlim_cur) - (std::isfinite(used) ? used : 0.0);
    available = std::min(available, std::max(left, 0.0));
  }
  return available;
}

void refuse_beyond_memory(const Case& c, const ResourceEstimate& e, double available) {
  if (!(e.memory_bytes > available)) return;
  throw MemoryRefusal(fmt::format(
      "the run needs about {} of memory ({} nodes, {} field snapshots, {} history rows) and {} is available: "
      "lower {}, output.fields_at (fewer snapshots), or the history rows (raise output.every, or time.end / "
      "time.step)",
      gigabytes(e.memory_bytes), e.nodes, e.snapshots, e.history_rows, gigabytes(available), elements_key(c)));
}

std::string output_size_warning(const Case& c, const ResourceEstimate& e) {
  if (!(e.output_bytes > large_output_bytes)) return {};
  return fmt::format(
      "output-size: the results will take about {} on disk ({} field snapshots of {} nodes, {} history rows): "
      "fewer output.fields_at or {}, or a larger output.every, make them smaller",
      gigabytes(e.output_bytes), e.snapshots, e.nodes, e.history_rows, elements_key(c));
}

std::string check_resources(const Case& c, bool streamed_fields) {
  const ResourceEstimate e = estimate_resources(c, streamed_fields);
  refuse_beyond_memory(c, e, available_memory());
  return output_size_warning(c, e);
}

CaseCheck check_case(const Case& c, double timing_budget) {
  CaseCheck k;
  k.resources = estimate_resources(c, true);  // as `barimpact run` writes them
  refuse_beyond_memory(c, k.resources, available_memory());
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
  out += fmt::format("memory: about {} ({} nodes, {} field snapshots, {} history rows)\n",
                     gigabytes(k.resources.memory_bytes), k.resources.nodes, k.resources.snapshots,
                     k.resources.history_rows);
  out += fmt::format("outputs: about {}\n", gigabytes(k.resources.output_bytes));
  if (!k.trouble.empty()) out += fmt::format("trouble: {}\n", k.trouble);
  return out;
}

}  // namespace barimpact
