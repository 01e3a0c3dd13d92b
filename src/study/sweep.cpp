#include "barimpact/study/sweep.hpp"

#include "csv_cells.hpp"
#include "range_point.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "../case/toml_input.hpp"
#include "barimpact/run/health.hpp"
#include "barimpact/run/output.hpp"
#include "barimpact/run/output_directory.hpp"
#include "barimpact/run/simulate.hpp"
#include "barimpact/schemes/simd.hpp"
#include "barimpact/study/executor.hpp"
#include "barimpact/study/paper_batch.hpp"

namespace barimpact {

namespace fs = std::filesystem;

namespace {

std::string plain_text(const std::string& toml_value) {
  if (toml_value.size() >= 2 && (toml_value.front() == '\'' || toml_value.front() == '"'))
    return toml_value.substr(1, toml_value.size() - 2);
  return toml_value;
}

double nan_if(bool known, double v) {
  return known ? v : std::numeric_limits<double>::quiet_NaN();
}

SweepRow row_from_summary(const SweepPoint& p, const Summary& s) {
  SweepRow r;
  r.id = p.id;
  for (const auto& [k, v] : p.values) r.values.push_back(plain_text(v));
  r.status = std::string(to_string(s.status));
  r.message = s.message;
  r.steps_done = s.steps_done;
  r.t_end = s.t_end;
  r.contacts = static_cast<int>(s.contacts.size());
  r.first_contact = nan_if(!s.contacts.empty(), s.contacts.empty() ? 0 : s.contacts.front().start);
  const ContactInterval* left = departure(s.contacts);  // lift-off and rebound of one episode
  r.lift_off = nan_if(left != nullptr, left ? left->end : 0);
  r.rebound_velocity = nan_if(left != nullptr, left ? left->rebound_velocity : 0);
  r.max_penetration = s.max_penetration;
  r.max_reaction = s.max_reaction;
  r.energy_error_relative =
      s.energy_initial != 0 ? s.energy_error_max / std::abs(s.energy_initial) : s.energy_error_max;
  r.run_seconds = s.run_seconds;
  r.warnings = s.warnings;
  if (const auto& b = s.blow) {
    r.blow = true;
    r.set = b->set;
    r.blows_per_250mm = b->blows_per_250mm();
    r.blows_per_m = b->blows_per_m();
    r.max_compression = b->max_compression.value;
    r.max_tension = b->max_tension.value;
    r.enthru = b->enthru;
  }
  return r;
}

// [set]'s keys as --set overrides: section.key = value, and the named
// elements' body.<name>.key = value (a TOML dotted key makes nested tables).
void add_base_sets(const toml::table& keys, const std::string& prefix, std::vector<Case::Override>& out) {
  for (auto&& [key, value] : keys) {
    const std::string path = fmt::format("{}.{}", prefix, key.str());
    if (const auto* inner = value.as_table())
      add_base_sets(*inner, path, out);
    else
      out.push_back({fmt::format("{}={}", path, toml_value_text(value))});
  }
}

// Whether a case's refusal of an axis's first value is about the key, not
// the value: an unknown key, or a body, joint or gauge the case does not have.
bool names_no_key(const std::string& what) {
  for (const char* about_key : {"unknown", "no such case file", "expected section.key", "no body named",
                                "no joint named", "no gauge named", "is not a section"})
    if (what.find(about_key) != std::string::npos) return true;
  return false;
}

}  // namespace

SweepPlan SweepPlan::from_file(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw InputError(fmt::format("{}: no such sweep file", path.string()));
  SweepPlan plan = from_string(read_input_file(path, "sweep file"), path.string(), path.parent_path());
  plan.sweep_file_ = path;
  return plan;
}

CommandInputs SweepPlan::inputs() const {
  CommandInputs in;
  for (const auto& f : {sweep_file_, case_file_})
    if (!f.empty()) in.files.push_back(f);
  return in;
}

namespace {

std::string where_in(const std::string& source, const toml::node& n) {
  return fmt::format("{}:{}", source, n.source().begin.line);
}

// from, to, count and scale: `count` points, linearly or log-spaced.
std::vector<std::string> range_values(const toml::table& t, const std::string& at, const std::string& key) {
  const double bad = std::numeric_limits<double>::quiet_NaN();
  const double from = t["from"].value_or(bad), to = t["to"].value_or(bad);
  // An integer only: toml++ converts a float out of int64's range with undefined behaviour.
  const auto* counted = t.get_as<int64_t>("count");
  const int64_t count = counted != nullptr ? counted->get() : 0;
  const std::string scale = t["scale"].value_or(std::string("linear"));
  if (!std::isfinite(from) || !std::isfinite(to) || count < 2 || count > 100000)
    throw InputError(fmt::format("{}: axis {}: a range needs numbers from, to and count >= 2", at, key));
  if (scale != "linear" && scale != "log")
    throw InputError(fmt::format("{}: axis {}: scale must be linear or log", at, key));
  if (scale == "log" && (from <= 0 || to <= 0))
    throw InputError(fmt::format("{}: axis {}: a log range needs from, to > 0", at, key));
  std::vector<std::string> values;
  for (int64_t i = 0; i < count; ++i) {
    const double s = static_cast<double>(i) / static_cast<double>(count - 1);
    const double x = detail::range_point(from, to, s, scale == "log");
    values.push_back(fmt::format("{}", x));
  }
  return values;
}

// One [[axis]]: its key and values (a list, or a range).
SweepAxis read_axis(const toml::node& node, const std::string& source) {
  const std::string at = where_in(source, node);
  const auto* t = node.as_table();
  if (t == nullptr) throw InputError(fmt::format("{}: [[axis]] must be a table", at));
  SweepAxis a;
  for (auto&& [k, v] : *t)
    if (k != "key" && k != "values" && k != "from" && k != "to" && k != "count" && k != "scale")
      throw InputError(
          fmt::format("{}: unknown key {} in [[axis]] (known: key, values, from, to, count, scale; "
                      "zip belongs before the first [[axis]])",
                      where_in(source, v), k.str()));
  const auto* key = t->get_as<std::string>("key");
  if (key == nullptr) throw InputError(fmt::format("{}: axis.key = \"section.key\" is required", at));
  a.key = key->get();
  if (const auto* values = t->get_as<toml::array>("values")) {
    for (const auto& v : *values) a.values.push_back(toml_value_text(v));
  } else if (t->contains("from")) {
    a.values = range_values(*t, at, a.key);
  } else {
    throw InputError(fmt::format("{}: axis {}: give values = [...] or from, to, count", at, a.key));
  }
  if (a.values.empty()) throw InputError(fmt::format("{}: axis {} has no values", at, a.key));
  return a;
}

// The axes' groups: each zip moves its axes together; every other axis is
// its own group; in the axes' order.
std::vector<std::vector<std::size_t>> axis_groups(const toml::table& root, const std::vector<SweepAxis>& list,
                                                  const std::string& source) {
  std::vector<std::vector<std::size_t>> groups;
  std::vector<bool> grouped(list.size(), false);
  if (const auto* zips = root.get_as<toml::array>("zip")) {
    for (const auto& z : *zips) {
      const std::string at = where_in(source, z);
      const auto* names = z.as_array();
      if (names == nullptr || names->size() < 2)
        throw InputError(fmt::format("{}: zip takes lists of two or more axis keys", at));
      std::vector<std::size_t> g;
      for (const auto& n : *names) {
        const auto name = n.value<std::string>();
        std::size_t i = 0;
        while (i < list.size() && (!name || list[i].key != *name)) ++i;
        if (i == list.size())
          throw InputError(fmt::format("{}: zip names {}, which is no axis", at, toml_value_text(n)));
        if (grouped[i]) throw InputError(fmt::format("{}: axis {} is zipped twice", at, list[i].key));
        if (list[i].values.size() != list[g.empty() ? i : g.front()].values.size())
          throw InputError(fmt::format("{}: zipped axes must have as many values each", at));
        grouped[i] = true;
        g.push_back(i);
      }
      groups.push_back(g);
    }
  }
  for (std::size_t i = 0; i < list.size(); ++i)
    if (!grouped[i]) groups.push_back({i});
  std::sort(groups.begin(), groups.end(), [](const auto& a, const auto& b) { return a.front() < b.front(); });
  return groups;
}

// Every case of the product of the groups, the last axis varying fastest.
// The number of cases is refused before the product can wrap around: each
// case is a run directory and the plan holds every case's values, so past a
// million cases, or two million values over them, it is not a study but a
// machine stalled while building its list.
std::vector<SweepPoint> product(const std::vector<SweepAxis>& list, const std::vector<std::vector<std::size_t>>& groups,
                                const std::string& source) {
  constexpr std::size_t most = 1'000'000, most_values = 2'000'000;
  std::size_t total = 1;
  for (const auto& g : groups) {
    const std::size_t size = list[g.front()].values.size();
    if (total > most / size) throw InputError(fmt::format("{}: more than 1e6 cases", source));
    total *= size;
  }
  if (total * list.size() > most_values)
    throw InputError(
        fmt::format("{}: {} cases of {} axes each: more than 2e6 values in all", source, total, list.size()));
  const int width = std::max(4, static_cast<int>(std::to_string(total - 1).size()));
  std::vector<SweepPoint> points;
  for (std::size_t n = 0; n < total; ++n) {
    SweepPoint p;
    p.id = fmt::format("{:0{}}", n, width);
    std::vector<std::string> chosen(list.size());
    std::size_t rest = n;
    for (auto g = groups.rbegin(); g != groups.rend(); ++g) {
      const std::size_t size = list[g->front()].values.size(), k = rest % size;
      rest /= size;
      for (auto i : *g) chosen[i] = list[i].values[k];
    }
    for (std::size_t i = 0; i < list.size(); ++i) p.values.emplace_back(list[i].key, chosen[i]);
    points.push_back(std::move(p));
  }
  return points;
}

}  // namespace

SweepPlan SweepPlan::from_string(std::string_view text, std::string_view origin, const fs::path& dir) {
  const std::string source(origin);
  toml::table root = parse_toml(text, origin);
  for (auto&& [k, v] : root)
    if (k != "case" && k != "set" && k != "axis" && k != "zip")
      throw InputError(fmt::format("{}: unknown key {} (known: case, set, axis, zip)", where_in(source, v), k.str()));
  SweepPlan plan;
  const auto* c = root.get_as<std::string>("case");
  if (c == nullptr) throw InputError(fmt::format("{}: case = \"CASE.toml\" is required", source));
  plan.case_file_ = dir / c->get();
  refuse_blocking_input(plan.case_file_, "case file");  // before any point opens it
  if (const auto* set = root.get_as<toml::table>("set")) {
    for (auto&& [section, keys] : *set) {
      if (!keys.is_table())
        throw InputError(fmt::format("{}: [set] takes section.key = value", where_in(source, keys)));
      add_base_sets(*keys.as_table(), std::string(section.str()), plan.base_sets_);
    }
  }
  const auto* axes = root.get_as<toml::array>("axis");
  if (axes == nullptr || axes->empty()) throw InputError(fmt::format("{}: at least one [[axis]] is required", source));
  std::vector<SweepAxis> list;
  for (const auto& node : *axes) {
    SweepAxis a = read_axis(node, source);
    for (const auto& other : list)
      if (other.key == a.key) throw InputError(fmt::format("{}: axis {} given twice", where_in(source, node), a.key));
    // An unknown key is the sweep file's error, not a case's.
    try {
      std::vector<Case::Override> probe = plan.base_sets_;
      probe.push_back({a.key + "=" + a.values.front()});
      (void)Case::from_file(plan.case_file_, probe);
    } catch (const InputError& e) {
      const std::string what = e.what();
      if (names_no_key(what)) throw InputError(fmt::format("{}: axis {}: {}", where_in(source, node), a.key, what));
    }
    list.push_back(std::move(a));
  }
  const auto groups = axis_groups(root, list, source);
  for (const auto& a : list) plan.keys_.push_back(a.key);
  plan.points_ = product(list, groups, source);
  return plan;
}

Case SweepPlan::case_at(const SweepPoint& p) const {
  std::vector<Case::Override> sets = base_sets_;
  for (const auto& [k, v] : p.values) sets.push_back({k + "=" + v});
  return Case::from_file(case_file_, sets);
}

bool read_row(const SweepPlan& plan, const fs::path& dir, std::size_t point, SweepRow& row) {
  const auto& p = plan.points()[point];
  const fs::path run_dir = dir / "runs" / p.id;
  if (!fs::exists(run_dir / "summary.json")) return false;
  std::string case_toml;
  try {
    case_toml = plan.case_at(p).to_toml();
  } catch (const InputError&) {
    return false;  // a refused case has no run directory to resume
  }
  const auto run = read_run_directory(run_dir, case_toml);
  if (!run || run->summary.status == RunStatus::interrupted) return false;
  row = row_from_summary(p, run->summary);
  row.resumed = true;
  return true;
}

namespace {

// Groups of up to four cases that can share a SIMD batch (on a mesh small
// enough for a batch to pay); the rest alone. Refused cases (empty) in none.
std::vector<std::vector<std::size_t>> batch_groups(const std::vector<std::optional<Case>>& cases, bool batch) {
  std::vector<std::vector<std::size_t>> groups;
  std::vector<bool> taken(cases.size(), false);
  for (std::size_t i = 0; i < cases.size(); ++i) {
    if (!cases[i] || taken[i]) continue;
    std::vector<std::size_t> g{i};
    taken[i] = true;
    if (batch && cases[i]->bar_elements() <= PaperBatch::largest_mesh && batchable(*cases[i], *cases[i]))
      for (std::size_t k = i + 1; k < cases.size() && g.size() < PaperBatch::width; ++k)
        if (cases[k] && !taken[k] && batchable(*cases[i], *cases[k])) {
          g.push_back(k);
          taken[k] = true;
        }
    groups.push_back(std::move(g));
  }
  return groups;
}

// The row of a point that left no run: its status and why.
SweepRow failed_row(const SweepPoint& p, const std::string& why, const char* status) {
  SweepRow row;
  row.id = p.id;
  for (const auto& [k, v] : p.values) row.values.push_back(plain_text(v));
  row.status = status;
  row.message = why;
  row.t_end = row.first_contact = row.lift_off = row.rebound_velocity = row.max_penetration = row.max_reaction =
      row.energy_error_relative = row.run_seconds = std::numeric_limits<double>::quiet_NaN();
  return row;
}

// The points a sweep runs now and what became of each: its case (none when
// the case is refused) and its row, filled in as the runs end.
struct SweepWork {
  const SweepPlan& plan;
  const std::vector<std::size_t>& todo;
  std::vector<SweepRow> rows;
  std::vector<std::optional<Case>> cases;

  const SweepPoint& point(std::size_t i) const { return plan.points()[todo[i]]; }
  void refuse(std::size_t i, const std::string& why, const char* status = "refused") {
    rows[i] = failed_row(point(i), why, status);
  }
};

// Every point's case read before any run, so a refused one costs nothing
// and its row says why.
SweepWork read_cases(const SweepPlan& plan, const std::vector<std::size_t>& todo) {
  SweepWork work{plan, todo, std::vector<SweepRow>(todo.size()), std::vector<std::optional<Case>>(todo.size())};
  for (std::size_t i = 0; i < todo.size(); ++i) {
    try {
      work.cases[i] = plan.case_at(work.point(i));
    } catch (const InputError& e) {
      work.refuse(i, e.what());
    }
  }
  return work;
}

// One group's runs: a case alone, or several side by side in a SIMD batch.
std::vector<RunResult> run_group(const SweepWork& work, const std::vector<std::size_t>& g,
                                 const std::atomic<bool>* interrupt) {
  std::vector<RunResult> results;
  if (g.size() == 1) {
    RunOptions one;
    one.interrupt = interrupt;
    results.push_back(run(*work.cases[g.front()], one));
  } else {
    std::vector<const Case*> ptrs;
    for (auto i : g) ptrs.push_back(&*work.cases[i]);
    results = run_batch(ptrs, interrupt);
  }
  return results;
}

// Each finished run of a group written to runs/<id> and its row taken from
// its summary. A run cut short is not kept (a rerun runs it whole); one that
// cannot be written is refused, and a full disk stops the sweep.
void keep_runs(SweepWork& work, const std::vector<std::size_t>& g, const std::vector<RunResult>& results,
               const fs::path& dir, OutputStop& stop) {
  for (std::size_t k = 0; k < g.size(); ++k) {
    const auto& p = work.point(g[k]);
    if (results[k].summary.status == RunStatus::interrupted) {
      work.refuse(g[k], results[k].summary.message, "interrupted");
      continue;
    }
    try {
      RunDirectory out(dir / "runs" / p.id, false, "sweep", false);  // the caller cleans runs/ once
      out.commit(*work.cases[g[k]], results[k]);
      work.rows[g[k]] = row_from_summary(p, results[k].summary);
      work.rows[g[k]].batched = g.size() > 1;
    } catch (const OutputError& e) {
      stop.record(e);
      work.refuse(g[k], e.what());
    } catch (const std::exception& e) {
      work.refuse(g[k], e.what());
    }
  }
}

}  // namespace

std::vector<SweepRow> run_sweep(const SweepPlan& plan, const fs::path& dir, const std::vector<std::size_t>& todo,
                                const SweepOptions& options) {
  if (options.batch) (void)simd_path();  // a bad BARIMPACT_SIMD stops the sweep here, not case by case
  SweepWork work = read_cases(plan, todo);
  const auto groups = batch_groups(work.cases, options.batch);
  auto interrupted = [&] { return options.interrupt != nullptr && options.interrupt->load(); };
  OutputStop stop(dir);  // a full disk ends the sweep: the runs written so far stay, and a rerun resumes
  run_parallel(groups.size(), options.jobs, [&](std::size_t gi) {
    const auto& g = groups[gi];
    std::vector<RunResult> results;
    try {
      if (interrupted() || stop.stopped()) {
        for (auto i : g) work.refuse(i, "interrupted before it began", "interrupted");
        return;
      }
      results = run_group(work, g, options.interrupt);
    } catch (const std::exception& e) {
      for (auto i : g) work.refuse(i, e.what());
      return;
    }
    keep_runs(work, g, results, dir, stop);
  });
  stop.rethrow();
  return std::move(work.rows);
}

void prepare_sweep(const fs::path& dir, const SweepOptions& options, bool force, const CommandInputs& inputs,
                   std::string_view command, const std::vector<std::string>& entries) {
  check_jobs(options.jobs);
  if (options.batch) (void)simd_path();  // a bad BARIMPACT_SIMD is refused before anything is written
  prepare_output_directory(dir, command, entries, force, "--out", inputs);
  std::error_code ec;
  fs::create_directories(dir / "runs", ec);
  if (ec) throw InputError(fmt::format("--out {}: cannot create it ({})", dir.string(), ec.message()));
  remove_stale_staging(dir / "runs", "");  // what a killed sweep left
  remove_stale_staging(dir, "");
}

SweepStart resume_sweep(const SweepPlan& plan, const fs::path& dir) {
  SweepStart start;
  start.rows.resize(plan.points().size());
  for (std::size_t i = 0; i < plan.points().size(); ++i)
    if (!read_row(plan, dir, i, start.rows[i])) start.todo.push_back(i);
  return start;
}

SweepOutcome finish_sweep(const SweepPlan& plan, const fs::path& dir, SweepStart start,
                          const std::vector<SweepRow>& done) {
  SweepOutcome outcome;
  outcome.resumed = start.rows.size() - start.todo.size();
  outcome.run = done.size();
  for (const auto& r : done) {
    start.rows[static_cast<std::size_t>(std::stoll(r.id))] = r;
    if (r.batched) ++outcome.batched;
  }
  outcome.rows = std::move(start.rows);
  replace_text(dir / "sweep.csv", sweep_csv(plan, outcome.rows));
  return outcome;
}

SweepOutcome write_sweep(const SweepPlan& plan, const fs::path& dir, const SweepOptions& options, bool force) {
  prepare_sweep(dir, options, force, plan.inputs());
  SweepStart start = resume_sweep(plan, dir);
  const auto done = run_sweep(plan, dir, start.todo, options);
  return finish_sweep(plan, dir, std::move(start), done);
}

namespace {
using detail::csv_number;
using detail::csv_text;
}  // namespace

std::string sweep_csv(const SweepPlan& plan, const std::vector<SweepRow>& rows) {
  std::string out = "id";
  for (const auto& k : plan.keys()) {
    out += ',';
    out += k;
  }
  // A sweep of pile blows adds their columns after the contract's.
  const bool blows = std::any_of(rows.begin(), rows.end(), [](const SweepRow& r) { return r.blow; });
  out +=
      ",status,steps_done,t_end,contacts,first_contact,lift_off,rebound_velocity,max_penetration,max_reaction,"
      "energy_error_relative,run_seconds,message,warnings";
  out += blows ? ",set,blows_per_250mm,blows_per_m,max_compression,max_tension,enthru\n" : "\n";
  for (const auto& r : rows) {
    out += r.id;
    for (const auto& v : r.values) {
      out += ',';
      out += csv_text(v);
    }
    const std::string warnings = join_warnings(r.warnings);
    out += fmt::format(",{},{},{},{},{},{},{},{},{},{},{},{},{}", r.status, r.steps_done, csv_number(r.t_end),
                       r.contacts, csv_number(r.first_contact), csv_number(r.lift_off), csv_number(r.rebound_velocity),
                       csv_number(r.max_penetration), csv_number(r.max_reaction), csv_number(r.energy_error_relative),
                       csv_number(r.run_seconds), csv_text(r.message), csv_text(warnings));
    const double none = std::numeric_limits<double>::quiet_NaN();
    if (blows)
      for (const double v : {r.set, r.blows_per_250mm, r.blows_per_m, r.max_compression, r.max_tension, r.enthru}) {
        out += ',';
        out += csv_number(r.blow ? v : none);
      }
    out += "\n";
  }
  return out;
}

std::string row_to_json(const SweepRow& r) {
  auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  return nlohmann::json{{"id", r.id},
                        {"values", r.values},
                        {"status", r.status},
                        {"message", r.message},
                        {"steps_done", r.steps_done},
                        {"t_end", num(r.t_end)},
                        {"contacts", r.contacts},
                        {"first_contact", num(r.first_contact)},
                        {"lift_off", num(r.lift_off)},
                        {"rebound_velocity", num(r.rebound_velocity)},
                        {"max_penetration", num(r.max_penetration)},
                        {"max_reaction", num(r.max_reaction)},
                        {"energy_error_relative", num(r.energy_error_relative)},
                        {"run_seconds", num(r.run_seconds)},
                        {"warnings", r.warnings},
                        {"blow", r.blow},
                        {"blow_values",
                         {num(r.set), num(r.blows_per_250mm), num(r.blows_per_m), num(r.max_compression),
                          num(r.max_tension), num(r.enthru)}}}
      .dump();
}

SweepRow row_from_json(const std::string& text) {
  const auto j = nlohmann::json::parse(text);
  auto num = [&](const char* k) {
    return j[k].is_number() ? j[k].get<double>() : std::numeric_limits<double>::quiet_NaN();
  };
  SweepRow r;
  r.id = j["id"];
  r.values = j["values"].get<std::vector<std::string>>();
  r.status = j["status"];
  r.message = j["message"];
  r.steps_done = j["steps_done"];
  r.t_end = num("t_end");
  r.contacts = j["contacts"];
  r.first_contact = num("first_contact");
  r.lift_off = num("lift_off");
  r.rebound_velocity = num("rebound_velocity");
  r.max_penetration = num("max_penetration");
  r.max_reaction = num("max_reaction");
  r.energy_error_relative = num("energy_error_relative");
  r.run_seconds = num("run_seconds");
  r.warnings = j["warnings"].get<std::vector<std::string>>();
  r.blow = j.value("blow", false);
  if (r.blow) {
    const auto& v = j["blow_values"];
    auto at = [&](std::size_t i) { return v[i].is_number() ? v[i].get<double>() : std::nan(""); };
    r.set = at(0), r.blows_per_250mm = at(1), r.blows_per_m = at(2);
    r.max_compression = at(3), r.max_tension = at(4), r.enthru = at(5);
  }
  return r;
}

}  // namespace barimpact
