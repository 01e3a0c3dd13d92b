#include "barimpact/study/convergence.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <time.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>

#include "barimpact/exact/exact.hpp"
#include "barimpact/exact/lines.hpp"
#include "barimpact/model/setup_polling.hpp"
#include "barimpact/run/health.hpp"
#include "barimpact/run/output.hpp"
#include "barimpact/run/output_directory.hpp"
#include "barimpact/run/simulate.hpp"
#include "barimpact/schemes/registry.hpp"
#include "barimpact/study/executor.hpp"
#include "range_point.hpp"

namespace barimpact {

namespace fs = std::filesystem;

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const auto at = s.find(sep, start);
    out.push_back(s.substr(start, at - start));
    if (at == std::string::npos) return out;
    start = at + 1;
  }
}

double number(const std::string& text, const std::string& where) {
  try {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size() && std::isfinite(v)) return v;
  } catch (const std::exception&) {
  }
  throw InputError(fmt::format("{}: \"{}\" is not a number", where, text));
}

struct Task {
  std::string id;  // runs/<id>
  std::string scheme;
  int level = 0;
  double scale = 1.0;  // 1/h growth factor, or the varied value
  std::string value;
  std::optional<Case> c;
  RunResult result;
  std::string status, message;
  double cpu = 0.0;
};

// One run of the study: read back from its directory when a previous
// (interrupted) study left it there for this very case, else run and kept.
void run_task(Task& t, const StudyOptions& o, OutputStop& stop) {
  if (!t.c) return;
  const bool keep = !o.runs.empty();
  const std::string case_toml = keep ? t.c->to_toml() : std::string();
  if (keep) {
    if (auto done = read_run_directory(o.runs / t.id, case_toml);
        done && done->summary.status != RunStatus::interrupted) {
      t.result = std::move(*done);
      t.status = std::string(to_string(t.result.summary.status));
      t.message = t.result.summary.message;
      t.cpu = t.result.summary.run_seconds;  // a timing column: the earlier run's wall time
      return;
    }
  }
  if ((o.interrupt != nullptr && o.interrupt->load()) || stop.stopped()) {
    t.status = "interrupted";
    t.message = "interrupted before it began";
    return;
  }
  const double start = thread_cpu_seconds();
  try {
    RunOptions options;
    options.interrupt = o.interrupt;
    t.result = run(*t.c, options);
    t.status = std::string(to_string(t.result.summary.status));
    t.message = t.result.summary.message;
    t.cpu = thread_cpu_seconds() - start;
    if (keep && t.result.summary.status != RunStatus::interrupted) {
      RunDirectory dir(o.runs / t.id, false, "converge", false);  // runs/ is cleaned once, in converge()
      dir.commit(*t.c, t.result);
    }
  } catch (const OutputError& e) {
    stop.record(e);  // a full disk ends the study (converge rethrows it)
    t.status = "refused";
    t.message = e.what();
  } catch (const std::exception& e) {
    t.status = "refused";
    t.message = e.what();
  }
}

// Linear interpolation of a history column at t (rows sorted by t).
double interpolate(const std::vector<HistoryRow>& rows, double HistoryRow::*column, double t) {
  auto it = std::lower_bound(rows.begin(), rows.end(), t, [](const HistoryRow& r, double x) { return r.t < x; });
  if (it == rows.end()) return nan;
  if (it->t == t || it == rows.begin()) return (*it).*column;
  const auto& b = *it;
  const auto& a = *(it - 1);
  return a.*column + (b.*column - a.*column) * (t - a.t) / (b.t - a.t);
}

// The exact reaction's mean over [t - dt/2, t + dt/2] (nothing before t = 0):
// what a scheme's R^n, an impulse over its step divided by the step, is to
// be compared with, also where R jumps (or is impulsive) at a step time.
double mean_reaction(const exact::Solution& s, double t, double dt) {
  constexpr int samples = 16;
  double sum = 0.0;
  for (int i = 0; i < samples; ++i) {
    const double x = t - 0.5 * dt + (i + 0.5) * dt / samples;
    if (x >= 0.0) sum += s.R(x);
  }
  return sum / samples;
}

// The characteristic scheme's step dt = h/c for a level whose variation
// (bar.elements, bar.length, ...) may change h or c: the level's case finds
// it, as it does without a given step; `fallback` if that case is refused
// (it is then refused again, with its own message, when the level is built).
double varied_courant_step(const std::string& base_toml, std::vector<Case::Override> sets, double fallback) {
  sets.push_back({"time.step=\"auto\""});
  try {
    return fit_scheme(Case::from_string(base_toml, sets, "study", false)).c.time.step;
  } catch (const InputError&) {
    return fallback;
  }
}

}  // namespace

Variation Variation::parse(const std::string& text) {
  const auto where = fmt::format("--vary {}", text);
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || text.find('.') > eq)
    throw InputError(
        fmt::format("{}: expected section.key=v1,v2,... or section.key=a:b:n or section.key=log:a:b:n", where));
  Variation v{text.substr(0, eq), {}};
  const std::string spec = text.substr(eq + 1);
  const auto parts = split(spec, ':');
  if (parts.size() == 3 || (parts.size() == 4 && parts[0] == "log")) {
    const bool log = parts.size() == 4;
    const double a = number(parts[log ? 1 : 0], where), b = number(parts[log ? 2 : 1], where);
    const double n = number(parts[log ? 3 : 2], where);
    if (n < 2 || n != std::floor(n) || n > 1000)
      throw InputError(fmt::format("{}: the count must be 2 .. 1000", where));
    if (log && (a <= 0 || b <= 0)) throw InputError(fmt::format("{}: a logarithmic range needs a, b > 0", where));
    for (int i = 0; i < static_cast<int>(n); ++i) {
      const double s = i / (n - 1.0);
      const double x = detail::range_point(a, b, s, log);
      v.values.push_back(fmt::format("{}", x));
    }
  } else {
    v.values = split(spec, ',');
    for (const auto& x : v.values)
      if (x.empty()) throw InputError(fmt::format("{}: an empty value in the list", where));
    if (v.values.size() < 2) throw InputError(fmt::format("{}: give at least two values", where));
  }
  return v;
}

double observed_order(double e_prev, double e, double s_prev, double s) {
  if (!(e_prev > 0) || !(e > 0) || !std::isfinite(e_prev) || !std::isfinite(e) || s_prev <= 0 || s <= 0 || s == s_prev)
    return nan;
  return std::log(e_prev / e) / std::log(s / s_prev);
}

StudyOptions study_options(const StudyArguments& a) {
  StudyOptions o;
  o.levels = a.levels;
  o.ratio = a.ratio;
  o.jobs = a.jobs;
  if (a.refine) {
    const std::string& r = *a.refine;
    if (r != "both" && r != "h" && r != "dt" && r != "none")
      throw InputError(fmt::format("--refine: must be both, h, dt or none (got \"{}\")", r));
    o.refine = r == "h" ? Refine::h : r == "dt" ? Refine::dt : r == "none" ? Refine::none : Refine::both;
  }
  if (a.vary) {
    o.vary = Variation::parse(*a.vary);
    if (!a.refine) o.refine = Refine::none;  // a variation alone changes only its key
  }
  const auto& known = scheme_names;
  for (const auto& s : a.schemes) {
    if (std::find(known.begin(), known.end(), s) == known.end())
      throw InputError(fmt::format("--schemes: unknown scheme \"{}\" (known: {})", s, fmt::join(known, ", ")));
    o.schemes.push_back(s);
  }
  if (a.reference != "auto" && a.reference != "rigid" && a.reference != "finest")
    throw InputError(fmt::format("--reference: must be auto, rigid or finest (got \"{}\")", a.reference));
  o.reference = a.reference == "rigid"    ? Reference::rigid
                : a.reference == "finest" ? Reference::finest
                                          : Reference::automatic;
  return o;
}

void check_study(const Case& base, const StudyOptions& o) {
  if (o.ratio < 2 || o.ratio > 16) throw InputError(fmt::format("--ratio: must be 2 .. 16 (got {})", o.ratio));
  if (o.levels < 2 || o.levels > 12) throw InputError(fmt::format("--levels: must be 2 .. 12 (got {})", o.levels));
  check_jobs(o.jobs);
  if (!o.vary && o.refine == Refine::none)
    throw InputError("--refine none: without --vary there is nothing to change between levels");
  if (o.vary) {
    const std::string& key = o.vary->key;
    if (o.vary->values.size() < 2 || o.vary->values.size() > 12)
      throw InputError(
          fmt::format("--vary {}: must give 2 .. 12 values, one per level (got {})", key, o.vary->values.size()));
    // The study sets the step and the bars' elements itself: a varied one
    // wins over that, unless --refine refines it too.
    const bool step = key == "time.step";
    const bool elements = key == "bar.elements" || (key.starts_with("body.") && key.ends_with(".elements"));
    const bool refine_h = o.refine == Refine::both || o.refine == Refine::h;
    const bool refine_dt = o.refine == Refine::both || o.refine == Refine::dt;
    const char* refine = o.refine == Refine::both ? "both" : o.refine == Refine::h ? "h" : "dt";
    if (step && refine_dt)
      throw InputError(
          fmt::format("--vary {}: --refine {} refines the step too; vary it with --refine h or none", key, refine));
    if (elements && refine_h)
      throw InputError(fmt::format(
          "--vary {}: --refine {} refines the elements too; vary them with --refine dt or none", key, refine));
    const auto& schemes = o.schemes.empty() ? std::vector<std::string>{base.time.scheme} : o.schemes;
    for (const auto& name : schemes)
      if (step && scheme_info(name).step == StepRule::transit)
        throw InputError(
            fmt::format("--vary {}: the {} scheme sets dt = h/c itself; vary bar.elements "
                        "instead, or leave it out of --schemes",
                        key, name));
    try {  // an unknown key is the option's error, not a run's (as in a sweep file)
      (void)Case::from_string(base.to_toml(), {{key + "=" + o.vary->values.front()}}, "study", false);
    } catch (const InputError& e) {
      const std::string what = e.what();
      if (what.find("unknown") != std::string::npos || what.find("expected section.key") != std::string::npos)
        throw InputError(fmt::format("--vary {}: {}", key, what));
    }
  }
  if (o.reference == Reference::rigid) {
    if (!base.one_bar()) throw InputError("--reference rigid: applies to a single bar's obstacle, not to a line");
    Case rigid = base;
    rigid.near_end.law = JointLaw::rigid;
    if (!exact::for_case(rigid))
      throw InputError("--reference rigid: the case with a rigid obstacle admits no exact solution");
  }
}

namespace {

// The runs' directory made, and what a killed study left in it removed.
void prepare_runs(const StudyOptions& o) {
  if (o.runs.empty()) return;
  std::error_code ec;
  if (!fs::create_directories(o.runs, ec) && ec)
    throw OutputError(fmt::format("--out: cannot create {} ({})", o.runs.string(), ec.message()), o.runs, ec.message());
  remove_stale_staging(o.runs, "");
  remove_stale_staging(o.runs.parent_path(), "");
}

// Level i of `scheme`: its case (h and dt refined by ratio^i, or the varied
// key's value), its scale for the observed orders, or its refusal.
Task make_task(const Case& base, const std::string& base_toml, const StudyOptions& o, const std::string& scheme,
               int i) {
  Task t;
  t.id = fmt::format("{}-{:02}", scheme, i);
  t.scheme = scheme;
  t.level = i;
  const auto one = base.one_bar();
  const bool varies_step = o.vary && o.vary->key == "time.step";
  const long long f = static_cast<long long>(std::llround(std::pow(o.ratio, i)));
  const bool refine_h = o.refine == Refine::both || o.refine == Refine::h;
  const bool refine_dt = o.refine == Refine::both || o.refine == Refine::dt;
  const long long elements = base.bar_elements() * (refine_h ? f : 1);
  double step = base.time.step / static_cast<double>(refine_dt ? f : 1);
  std::vector<Case::Override> sets{{"time.scheme=\"" + scheme + "\""}, {"output.every=1"}, {"output.fields_at=[]"}};
  if (one)
    sets.push_back({fmt::format("bar.elements={}", elements)});
  else  // every bar of the line refined alike
    for (const auto& b : base.bodies)
      if (b.kind == BodyKind::bar)
        sets.push_back({fmt::format("body.{}.elements={}", b.name, b.elements * (refine_h ? f : 1))});
  if (o.vary) {
    t.value = o.vary->values[static_cast<std::size_t>(i)];
    sets.push_back({o.vary->key + "=" + t.value});
  }
  // Courant 1 (a line refines every bar alike: its common h/c falls with the step).
  if (scheme_info(scheme).step == StepRule::transit && one) {
    step = one->bar.length / static_cast<double>(elements) / std::sqrt(one->bar.stiffness / one->bar.density);
    if (o.vary) step = varied_courant_step(base_toml, sets, step);
  }
  // A varied step wins (check_study refuses it where the study refines the step).
  if (!varies_step) sets.push_back({fmt::format("time.step={}", step)});
  t.scale = (o.refine != Refine::none) ? static_cast<double>(f) : nan;
  if (o.refine == Refine::none && o.vary) {
    try {
      t.scale = number(t.value, "--vary");
      if (varies_step) t.scale = 1.0 / t.scale;  // as 1/h: the orders of a falling step come out positive
    } catch (const InputError&) {
      t.scale = nan;
    }
  }
  try {
    t.c = fit_scheme(Case::from_string(base_toml, sets, "study", false)).c;
  } catch (const InputError& e) {
    t.status = "refused";
    t.message = e.what();
  }
  return t;
}

// The exact solution a run is measured against (none: the finest run).
std::unique_ptr<exact::Solution> reference_solution(const Case& c, const StudyOptions& o) {
  if (o.reference == Reference::rigid) {
    Case rigid = c;
    rigid.near_end.law = JointLaw::rigid;
    auto solution = exact::for_case(rigid);
    if (!solution) throw InputError("--reference rigid: the case with a rigid obstacle admits no exact solution");
    return solution;
  }
  if (o.reference == Reference::finest) return nullptr;
  return c.one_bar() ? exact::for_case(c) : exact::line_end(c);
}

// The largest error in U and the L1 error in R of `h` against `U(t)`,
// `R(t)` (NaN past where the reference is known).
template <class Known>
void measure_errors(const std::vector<HistoryRow>& h, double dt, StudyRun& r, Known reference) {
  double eu = 0, er = 0;
  for (const auto& x : h) {
    const auto [U, R] = reference(x.t);
    if (std::isnan(U)) break;
    eu = std::max(eu, std::abs(x.U - U));
    er += std::abs(x.R - R) * dt;
  }
  r.error_U_max = eu;
  r.error_R_l1 = er;
}

// One row of the study: the run's status, mesh and contact, its energy
// error, and its errors against the exact solution or its scheme's finest run.
StudyRun measure(const Task& t, const StudyOptions& o, const std::map<std::string, const Task*>& finest, int levels,
                 std::map<std::string, std::string>& references) {
  StudyRun r;
  r.id = t.id;
  r.scheme = t.scheme;
  r.level = t.level;
  r.value = t.value;
  r.status = t.status;
  r.message = t.message;
  r.warnings = t.result.summary.warnings;
  r.cpu_seconds = t.cpu;
  r.error_U_max = r.error_R_l1 = r.energy_error_end = r.first_contact = r.lift_off = nan;
  r.order_U = r.order_R = nan;
  if (t.c) {
    r.elements = static_cast<int>(t.c->bar_elements());
    r.h = t.c->bar_length() / static_cast<double>(t.c->bar_elements());
    r.step = t.c->time.step;
  }
  const auto& h = t.result.history;
  if (!t.c || h.empty() || t.status != "complete") return r;  // no error is measured on a run cut short
  const auto& s = t.result.summary;
  r.contact_episodes = static_cast<int>(s.contacts.size());
  if (!s.contacts.empty()) r.first_contact = s.contacts.front().start;
  if (const ContactInterval* left = departure(s.contacts)) r.lift_off = left->end;
  r.energy_error_end = std::abs(h.back().total() - h.front().total()) / std::abs(h.front().total());
  const double dt = t.c->time.step;
  const auto finest_run = finest.find(t.scheme);
  if (const auto solution = reference_solution(*t.c, o)) {
    references[fmt::format("exact solution: {}", solution->name())] = "";
    measure_errors(h, dt, r, [&](double time) {
      return time > solution->valid_until() ? std::pair{nan, nan}
                                            : std::pair{solution->U(time), mean_reaction(*solution, time, dt)};
    });
  } else if (finest_run != finest.end() && finest_run->second != &t) {
    references[fmt::format("the finest run of each scheme (level {})", levels - 1)] = "";
    const auto& ref = finest_run->second->result.history;
    measure_errors(h, dt, r, [&](double time) {
      return std::pair{interpolate(ref, &HistoryRow::U, time), interpolate(ref, &HistoryRow::R, time)};
    });
  } else if (finest_run != finest.end()) {
    r.status = "reference";
  }
  return r;
}

}  // namespace

Study converge(const Case& base, const StudyOptions& o) {
  check_study(base, o);
  const int levels = o.vary ? static_cast<int>(o.vary->values.size()) : o.levels;
  prepare_runs(o);
  const auto schemes = o.schemes.empty() ? std::vector<std::string>{base.time.scheme} : o.schemes;
  const std::string base_toml = base.to_toml();
  std::vector<Task> tasks;
  {
    const SetupPolling polling(o.interrupt);  // fitting a level builds its line
    for (const auto& scheme : schemes)
      for (int i = 0; i < levels; ++i) tasks.push_back(make_task(base, base_toml, o, scheme, i));
  }

  OutputStop stop(o.runs.parent_path());
  run_parallel(tasks.size(), o.jobs, [&](std::size_t i) { run_task(tasks[i], o, stop); });
  stop.rethrow();

  Study study;
  study.abscissa = o.refine != Refine::none ? "h" : (o.vary ? o.vary->key : "h");
  std::map<std::string, std::string> references;
  std::map<std::string, const Task*> finest;
  for (const auto& t : tasks)
    if (t.level == levels - 1 && t.status == "complete") finest[t.scheme] = &t;
  for (const auto& t : tasks) study.runs.push_back(measure(t, o, finest, levels, references));
  for (std::size_t i = 0; i < study.runs.size(); ++i) {
    auto& r = study.runs[i];
    if (r.level == 0) continue;
    const auto& p = study.runs[i - 1];
    r.order_U = observed_order(p.error_U_max, r.error_U_max, tasks[i - 1].scale, tasks[i].scale);
    r.order_R = observed_order(p.error_R_l1, r.error_R_l1, tasks[i - 1].scale, tasks[i].scale);
  }
  for (const auto& [name, unused] : references) study.reference += (study.reference.empty() ? "" : "; ") + name;
  if (study.reference.empty()) study.reference = "none (no run completed)";
  return study;
}

namespace {
// A CSV cell: nan where the level defines no value (a reader's float()
// takes it).
std::string cell(double v, const char* spec = "{:.6g}") {
  return std::isfinite(v) ? fmt::format(fmt::runtime(spec), v) : std::string("nan");
}
// A Markdown table's cell to its digits; a value the level does not define
// (the first level's order, an error without a reference) is a dash.
std::string md_cell(double v, const char* spec) {
  return std::isfinite(v) ? fmt::format(fmt::runtime(spec), v) : std::string("-");
}
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char ch : s) out += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return out + "\"";
}
}  // namespace

std::string study_csv(const Study& study) {
  std::string out =
      "scheme,level,value,elements,h,step,status,error_U_max,error_R_l1,energy_error_end,first_contact,lift_off,"
      "contact_episodes,cpu_seconds,order_U,order_R,message,warnings\n";
  for (const auto& r : study.runs) {
    const std::string warnings = join_warnings(r.warnings);
    out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", r.scheme, r.level, quoted(r.value),
                       r.elements, cell(r.h, "{}"), cell(r.step, "{}"), r.status, cell(r.error_U_max, "{}"),
                       cell(r.error_R_l1, "{}"), cell(r.energy_error_end, "{}"), cell(r.first_contact, "{}"),
                       cell(r.lift_off, "{}"), r.contact_episodes, cell(r.cpu_seconds, "{}"), cell(r.order_U, "{}"),
                       cell(r.order_R, "{}"), quoted(r.message), quoted(warnings));
  }
  return out;
}

std::string study_markdown(const Study& study, const std::string& command) {
  std::string out = fmt::format("    {}\n\nReference: {}.\n", command, study.reference);
  std::string current;
  for (const auto& r : study.runs) {
    if (r.scheme != current) {
      current = r.scheme;
      out += fmt::format(
          "\n**{}**\n\n| level | {} | M | dt | max err U | order | L1 err R | order | energy err | first contact | "
          "lift-off | episodes | CPU s | status "
          "|\n|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n",
          r.scheme, r.value.empty() ? "h" : "value");
    }
    const std::string abscissa = r.value.empty() ? md_cell(r.h, "{:.4g}") : r.value;
    out += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", r.level, abscissa,
                       r.elements, md_cell(r.step, "{:.4g}"), md_cell(r.error_U_max, "{:.3e}"),
                       md_cell(r.order_U, "{:.2f}"), md_cell(r.error_R_l1, "{:.3e}"), md_cell(r.order_R, "{:.2f}"),
                       md_cell(r.energy_error_end, "{:.2e}"), md_cell(r.first_contact, "{:.4f}"),
                       md_cell(r.lift_off, "{:.4f}"), r.contact_episodes, md_cell(r.cpu_seconds, "{:.3f}"), r.status);
  }
  return out;
}

const std::vector<std::string>& convergence_entries() {
  static const std::vector<std::string> entries{"runs",
                                                "convergence.csv",
                                                "convergence.md",
                                                "convergence.png",
                                                "convergence.svg",
                                                "work_precision.png",
                                                "work_precision.svg"};
  return entries;
}

namespace {
// Run directories in runs/ that barimpact wrote for an earlier, other study.
void remove_other_runs(const fs::path& runs, const Study& study) {
  for (const auto& name : directory_entries(runs)) {
    const bool ours = std::any_of(study.runs.begin(), study.runs.end(), [&](const auto& r) { return name == r.id; });
    std::error_code ec;
    // Only a study's own runs: a run of the user's kept in runs/ stays.
    if (!ours && output_command(runs / name) == "converge" && written_by_barimpact(runs / name))
      fs::remove_all(runs / name, ec);
  }
}
}  // namespace

Study write_convergence(const Case& base, StudyOptions options, const fs::path& dir, bool force,
                        const std::string& command) {
  check_study(base, options);  // a refusal writes nothing
  prepare_output_directory(dir, "converge", convergence_entries(), force, "--out", {{base.source}, {}});
  options.runs = dir / "runs";
  Study study = converge(base, options);
  remove_other_runs(options.runs, study);
  replace_text(dir / "convergence.csv", study_csv(study));
  replace_text(dir / "convergence.md", study_markdown(study, command));
  return study;
}

}  // namespace barimpact
