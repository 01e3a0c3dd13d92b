// barimpact._core: the C++ library seen from Python. Thin: every number is
// computed by the library; this file only converts and shares memory.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fmt/format.h>
#include <toml++/toml.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <filesystem>
#include <future>
#include <new>
#include <optional>
#include <sstream>

#include "barimpact/case/case.hpp"
#include "barimpact/exact/exact.hpp"
#include "barimpact/exact/tabulate.hpp"
#include "barimpact/hopkinson/analysis.hpp"
#include "barimpact/pda/case_method.hpp"
#include "barimpact/run/check.hpp"
#include "barimpact/run/figure_names.hpp"
#include "barimpact/run/output.hpp"
#include "barimpact/run/output_directory.hpp"
#include "barimpact/run/simulate.hpp"
#include "barimpact/study/bearing.hpp"
#include "barimpact/study/convergence.hpp"
#include "barimpact/study/drive.hpp"
#include "barimpact/study/executor.hpp"
#include "barimpact/study/match.hpp"
#include "barimpact/study/sweep.hpp"

namespace py = pybind11;
using namespace barimpact;

namespace {

// A run's result with the case that produced it (for summary.json and write).
struct PyResult {
  Case c;
  RunResult r;
  std::string command = "run";  // what wrote it: "run" or "exact" (the directory's marker says so)
};

// A Python int as TOML's 64-bit integer; InputError naming `where` beyond it.
long long integer_of(const py::handle& value, const std::string& where) {
  int overflow = 0;
  const long long v = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
  if (overflow != 0 || (v == -1 && PyErr_Occurred() != nullptr)) {
    PyErr_Clear();
    throw InputError(
        fmt::format("dict: {} = {} is beyond a 64-bit integer", where, py::str(value).cast<std::string>()));
  }
  return v;
}

// One table's keys: numbers, strings, booleans, lists of them.
toml::table keys_table(const py::dict& keys, const std::string& name) {
  toml::table t;
  for (auto [key, value] : keys) {
    const auto k = py::str(key).cast<std::string>();
    if (py::isinstance<py::bool_>(value)) {
      t.insert(k, value.cast<bool>());
    } else if (py::isinstance<py::int_>(value)) {
      t.insert(k, integer_of(value, name + "." + k));
    } else if (py::isinstance<py::float_>(value)) {
      t.insert(k, value.cast<double>());
    } else if (py::isinstance<py::str>(value)) {
      t.insert(k, value.cast<std::string>());
    } else if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value) ||
               py::isinstance<py::array>(value)) {
      toml::array a;
      for (auto item : value) {
        if (py::isinstance<py::int_>(item))
          a.push_back(integer_of(item, name + "." + k));
        else if (py::isinstance<py::float_>(item) || py::hasattr(item, "__float__"))
          a.push_back(item.cast<double>());
        else
          a.push_back(py::str(item).cast<std::string>());
      }
      t.insert(k, std::move(a));
    } else if (py::hasattr(value, "__float__")) {
      t.insert(k, value.cast<double>());
    } else {
      t.insert(k, py::str(value).cast<std::string>());
    }
  }
  return t;
}

// {section: {key: value}, array: [{key: value}, ...]} -> TOML text, so that
// the library's reader checks a dict exactly as it checks a file.
toml::table table_from_dict(const py::dict& d) {
  toml::table root;
  for (auto [section, keys] : d) {
    const auto name = py::str(section).cast<std::string>();
    // [[body]], [[joint]], [[gauge]]: a list of dicts.
    if ((py::isinstance<py::list>(keys) || py::isinstance<py::tuple>(keys)) && py::len(keys) > 0 &&
        py::isinstance<py::dict>(*keys.begin())) {
      toml::array tables;
      for (auto item : keys) {
        if (!py::isinstance<py::dict>(item)) throw InputError("dict: [[" + name + "]] must be a list of dicts");
        tables.push_back(keys_table(item.cast<py::dict>(), name));
      }
      root.insert(name, std::move(tables));
      continue;
    }
    if (!py::isinstance<py::dict>(keys))
      throw InputError("dict: [" + name + "] must be a dict of keys, or a list of dicts for [[" + name + "]] (got " +
                       py::str(keys.get_type().attr("__name__")).cast<std::string>() + ")");
    root.insert(name, keys_table(keys.cast<py::dict>(), name));
  }
  return root;
}

std::vector<Case::Override> overrides_from(const py::object& set) {
  std::vector<Case::Override> out;
  if (set.is_none()) return out;
  if (py::isinstance<py::dict>(set)) {
    for (auto [key, value] : set.cast<py::dict>()) {
      std::string text;
      if (py::isinstance<py::str>(value))
        text = value.cast<std::string>();  // a bare word, or TOML as written
      else if (py::isinstance<py::bool_>(value))
        text = value.cast<bool>() ? "true" : "false";
      else
        text = py::repr(value).cast<std::string>();
      out.push_back({py::str(key).cast<std::string>() + "=" + text});
    }
    return out;
  }
  if (py::isinstance<py::str>(set)) return {{set.cast<std::string>()}};  // one "section.key=value"
  if (!py::isinstance<py::iterable>(set))
    throw InputError(
        fmt::format("set: must be a dict {{\"section.key\": value}} or a list of \"section.key=value\" "
                    "(got {})",
                    py::str(set.get_type().attr("__name__")).cast<std::string>()));
  for (auto item : set) out.push_back({py::str(item).cast<std::string>()});
  return out;
}

Case read_case(const py::object& source, const py::object& set) {
  const auto overrides = overrides_from(set);
  if (source.is_none()) return Case::from_string("", overrides, "defaults");
  if (py::isinstance<Case>(source)) {  // a case with overrides: still the file it was read from
    const auto& base = source.cast<const Case&>();
    Case c = Case::from_string(base.to_toml(), overrides, "string");
    c.source = base.source;
    return c;
  }
  if (py::isinstance<py::dict>(source)) {
    std::ostringstream text;
    text << toml::toml_formatter(table_from_dict(source.cast<py::dict>()));
    return Case::from_string(text.str(), overrides, "dict", false);
  }
  const bool is_path = py::hasattr(source, "__fspath__");
  const auto text =
      is_path ? py::str(source.attr("__fspath__")()).cast<std::string>() : py::str(source).cast<std::string>();
  // A path names a file; TOML text has a newline, a '[' or an '='.
  if (is_path || text.find_first_of("\n[=") == std::string::npos) return Case::from_file(text, overrides);
  return Case::from_string(text, overrides, "string");
}

// A case as the module hands it out: read, and fitted to its scheme (its
// step as the scheme takes it, every refusal made), as the command does.
Case make_case(const py::object& source, const py::object& set) {
  return fit_scheme(read_case(source, set)).c;
}

// A read-only numpy view of `n` doubles spaced `stride` apart, kept alive by `owner`.
py::array view(const double* data, std::vector<py::ssize_t> shape, std::vector<py::ssize_t> strides, py::handle owner) {
  py::array a(py::dtype::of<double>(), std::move(shape), std::move(strides), data, owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

constexpr std::array<const char*, 11> columns{"t",          "U",     "V",      "R",         "E_kin",    "E_strain",
                                              "E_obstacle", "W_ext", "D_visc", "D_contact", "D_plastic"};

// Any nested value as TOML (a sweep file's top level: case, zip, [set],
// [[axis]]): dicts are tables, lists arrays, numpy scalars numbers.
toml::table nested_table(const py::dict& d);
toml::array nested_array(const py::handle& items);

// Hands `put` the value as its TOML type (tables and arrays through the two
// functions above, so that this template is not instantiated without end).
template <class Put>
void put_value(const py::handle& value, Put&& put) {
  if (py::isinstance<py::dict>(value)) {
    put(nested_table(value.cast<py::dict>()));
  } else if (py::isinstance<py::bool_>(value)) {
    put(value.cast<bool>());
  } else if (py::isinstance<py::int_>(value)) {
    put(value.cast<long long>());
  } else if (py::isinstance<py::float_>(value)) {
    put(value.cast<double>());
  } else if (py::isinstance<py::str>(value)) {
    put(value.cast<std::string>());
  } else if (py::hasattr(value, "__fspath__")) {
    put(py::str(value.attr("__fspath__")()).cast<std::string>());
  } else if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value) || py::isinstance<py::array>(value)) {
    put(nested_array(value));
  } else if (py::hasattr(value, "__index__")) {
    put(value.attr("__index__")().cast<long long>());
  } else if (py::hasattr(value, "__float__")) {
    put(value.cast<double>());
  } else {
    put(py::str(value).cast<std::string>());
  }
}

toml::array nested_array(const py::handle& items) {
  toml::array a;
  for (auto item : items) put_value(item, [&a](auto&& x) { a.push_back(std::forward<decltype(x)>(x)); });
  return a;
}

toml::table nested_table(const py::dict& d) {
  toml::table t;
  for (auto [key, value] : d) {
    const auto k = py::str(key).cast<std::string>();
    put_value(value, [&t, &k](auto&& x) { t.insert(k, std::forward<decltype(x)>(x)); });
  }
  return t;
}

std::string fspath(const py::handle& path) {
  return py::str(py::module_::import("os").attr("fspath")(path)).cast<std::string>();
}

// Runs `work(options)` on a thread of its own, with `options.interrupt` set,
// while this one, without the GIL, looks every 0.1 s for a signal: Python's
// handlers run on the main thread only, so without this Ctrl-C would wait
// for a whole study. On a signal the interrupt is set (the library ends the
// runs under way after their step and starts no other) and the exception
// (KeyboardInterrupt) is kept, to be raised once what was done is written,
// as the command exits 130 after writing.
template <class Options, class Work>
auto interruptible(Options options, Work work) {
  std::atomic<bool> stop{false};
  std::optional<py::error_already_set> signal;
  options.interrupt = &stop;
  auto future = std::async(std::launch::async, [&] { return work(options); });
  for (;;) {
    {
      py::gil_scoped_release release;
      if (future.wait_for(std::chrono::milliseconds(100)) == std::future_status::ready) break;
    }
    if (!signal && PyErr_CheckSignals() != 0) {
      signal.emplace();  // fetches and clears the pending KeyboardInterrupt
      stop.store(true);
    }
  }
  auto result = future.get();
  if (signal) throw *signal;
  return result;
}

// A study's warnings as (run id, warning) pairs, every one: Python shows
// the first few, as the command does.
template <class Rows>
py::list study_warnings(const Rows& rows) {
  py::list out;
  for (const auto& r : rows)
    for (const auto& w : r.warnings) out.append(py::make_tuple(r.id, w));
  return out;
}

template <class Rows>
long count_status(const Rows& rows, std::initializer_list<std::string_view> statuses) {
  return static_cast<long>(std::count_if(rows.begin(), rows.end(), [&](const auto& r) {
    return std::find(statuses.begin(), statuses.end(), r.status) != statuses.end();
  }));
}

// ---- converge, sweep, bearing: the library's writers (as the command),
// on a thread of their own (interruptible), without their figures.

py::dict converge_binding(const Case& c, const std::optional<std::string>& out, const StudyArguments& args, bool force,
                          const std::string& command) {
  const Study study = interruptible(study_options(args), [&](const StudyOptions& o) {
    return out ? write_convergence(c, o, *out, force, command) : converge(c, o);
  });
  py::dict d;
  d["csv"] = study_csv(study);
  d["markdown"] = study_markdown(study, command);
  d["reference"] = study.reference;
  d["abscissa"] = study.abscissa;
  d["warnings"] = study_warnings(study.runs);
  d["runs"] = study.runs.size();
  d["results"] = count_status(study.runs, {"complete", "reference"});
  d["stopped"] = count_status(study.runs, {"interrupted"});
  return d;
}

SweepPlan sweep_plan(const py::object& sweep) {
  if (py::isinstance<py::dict>(sweep)) {
    std::ostringstream text;  // the file's reader checks a dict too; `case` from the working directory
    text << toml::toml_formatter(nested_table(sweep.cast<py::dict>()));
    return SweepPlan::from_string(text.str(), "sweep", std::filesystem::current_path());
  }
  return SweepPlan::from_file(fspath(sweep));
}

py::dict sweep_binding(const py::object& sweep, const std::string& out, int jobs, bool batch, bool force) {
  const SweepPlan plan = sweep_plan(sweep);
  SweepOptions o;
  o.jobs = jobs;
  o.batch = batch;
  const auto outcome =
      interruptible(o, [&](const SweepOptions& options) { return write_sweep(plan, out, options, force); });
  py::dict d;
  d["csv"] = sweep_csv(plan, outcome.rows);
  d["cases"] = outcome.rows.size();
  d["run"] = outcome.run;
  d["batched"] = outcome.batched;
  d["resumed"] = outcome.resumed;
  d["warnings"] = study_warnings(outcome.rows);
  return d;
}

py::dict drive_binding(const py::object& case_file, const std::string& out, int jobs, bool force,
                       const py::object& set) {
  const DrivePlan plan(fspath(case_file), overrides_from(set));
  SweepOptions options;
  options.jobs = jobs;
  options.batch = false;  // Smith's soil runs on central differences
  const auto rows = interruptible(
      options, [&](const SweepOptions& sweep_options) { return write_drive(plan, out, sweep_options, force); });
  std::vector<SweepRow> runs;
  for (const auto& r : rows) runs.push_back(r.run);
  const DriveTotals t = drive_totals(plan, rows);
  py::dict d;
  d["csv"] = drive_csv(rows);
  d["total_blows"] = t.total_blows;
  d["driving_time"] = t.driving_time;
  d["refusal_depth"] = t.refusal_depth ? py::cast(*t.refusal_depth) : py::none();
  d["max_compression"] = t.max_compression;
  d["max_tension"] = t.max_tension;
  d["warnings"] = study_warnings(runs);
  return d;
}

py::dict inspector_binding(const py::object& case_file, const std::string& out, const std::string& stroke,
                           std::optional<double> depth, int jobs, bool force, const py::object& set) {
  const InspectorPlan plan(fspath(case_file), stroke, depth, overrides_from(set));
  SweepOptions options;
  options.jobs = jobs;
  options.batch = false;  // Smith's soil runs on central differences
  const auto rows = interruptible(
      options, [&](const SweepOptions& sweep_options) { return write_inspector(plan, out, sweep_options, force); });
  std::vector<SweepRow> runs;
  for (const auto& r : rows) runs.push_back(r.run);
  py::dict d;
  d["csv"] = inspector_csv(rows);
  d["warnings"] = study_warnings(runs);
  return d;
}

// The shipped hammers as CSV (name, kind, ram_mass, stroke, energy, ...), for a Table.
std::string hammers_csv() {
  std::string out =
      "name,kind,ram_mass,stroke,energy,efficiency,cushion_stiffness,cushion_restitution,helmet_mass,source\n";
  auto quoted = [](const std::string& s) {
    std::string q = "\"";
    for (char ch : s) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return q + "\"";
  };
  for (const auto& h : shipped_hammers()) {
    const double stroke = h.stroke > 0 ? h.stroke : h.energy / (h.ram_mass * 9.81);
    out += fmt::format("{},{},{},{},{},{},{},{},{},{}\n", quoted(h.name), to_string(h.kind), h.ram_mass, stroke,
                       h.ram_mass * 9.81 * stroke, h.efficiency, h.cushion_stiffness, h.cushion_restitution,
                       h.helmet_mass, quoted(h.source));
  }
  return out;
}

py::dict bearing_binding(const py::object& case_file, const std::string& out, const std::string& capacity,
                         const std::optional<double>& toe_share, int jobs, bool force, const py::object& set) {
  BearingOptions o;
  parse_capacity(capacity, o);  // the command's rules
  o.toe_share = toe_share;      // BearingPlan checks it
  o.sets = overrides_from(set);
  const BearingPlan plan(fspath(case_file), o);
  SweepOptions options;
  options.jobs = jobs;
  options.batch = false;  // Smith's soil runs on central differences
  const auto rows = interruptible(
      options, [&](const SweepOptions& sweep_options) { return write_bearing(plan, out, sweep_options, force); });
  std::vector<SweepRow> runs;
  for (const auto& r : rows) runs.push_back(r.run);
  py::dict d;
  d["csv"] = bearing_csv(rows);
  d["toe_share"] = plan.toe_share();
  d["from"] = o.from;
  d["to"] = o.to;
  d["count"] = o.count;
  d["warnings"] = study_warnings(runs);
  return d;
}

HopkinsonSetup hopkinson_setup(const py::object& setup) {
  if (py::isinstance<py::dict>(setup)) {
    std::ostringstream text;  // the file's reader checks a dict too
    text << toml::toml_formatter(table_from_dict(setup.cast<py::dict>()));
    return HopkinsonSetup::from_string(text.str(), std::filesystem::current_path(), "setup");
  }
  return HopkinsonSetup::from_file(fspath(setup));
}

// The analysis, then (with `out`) hopkinson.csv, summary.json and what
// `draw(staging)` adds, moved into place together as the command does.
py::tuple hopkinson_binding(const py::object& setup, const std::optional<std::string>& out, bool force,
                            const py::object& draw) {
  const HopkinsonSetup s = hopkinson_setup(setup);
  HopkinsonResult r;
  {
    py::gil_scoped_release release;
    r = analyse_hopkinson(s);
  }
  if (out) {
    RunDirectory dir(*out, force, "hopkinson", true, hopkinson_inputs(s));
    dir.commit([&](const std::filesystem::path& staging) {
      write_text(staging / "hopkinson.csv", hopkinson_csv(r));
      write_text(staging / "summary.json", hopkinson_summary_json(r));
      if (!draw.is_none()) draw(staging.string());
    });
  }
  py::dict table;
  for (const auto& c : r.columns) {
    py::array_t<double> a(static_cast<py::ssize_t>(c.values.size()));
    std::copy(c.values.begin(), c.values.end(), a.mutable_data());
    table[py::str(c.name)] = a;
  }
  py::list warnings;
  for (const auto& w : r.warnings) warnings.append(w);
  return py::make_tuple(table, hopkinson_summary_json(r), warnings);
}

PileRecord pile_record(const py::object& record) {
  if (py::isinstance<py::dict>(record)) {
    std::ostringstream text;  // the file's reader checks a dict too
    text << toml::toml_formatter(table_from_dict(record.cast<py::dict>()));
    return PileRecord::from_string(text.str(), std::filesystem::current_path(), "record");
  }
  return PileRecord::from_file(fspath(record));
}

// The record's analysis, then (with `out`) pda.csv, summary.json and what
// `draw(staging)` adds, moved into place together as the command does.
py::tuple pda_binding(const py::object& record, const std::optional<std::string>& out, bool force,
                      const py::object& draw) {
  const PileRecord rec = pile_record(record);
  CaseMethodResult r;
  {
    py::gil_scoped_release release;
    r = analyse_pda(rec);
  }
  if (out) {
    RunDirectory dir(*out, force, "pda", true, pda_inputs(rec));
    dir.expect(pda_files());
    dir.commit([&](const std::filesystem::path& staging) {
      write_text(staging / "pda.csv", pda_csv(r));
      write_text(staging / "summary.json", pda_summary_json(r));
      if (!draw.is_none()) draw(staging.string());
    });
  }
  return py::make_tuple(pda_csv(r), pda_summary_json(r));
}

// What `interruptible` sets for the fit.
struct MatchOptions {
  const std::atomic<bool>* interrupt = nullptr;
};

// The record's match, then (with `out`) match.csv, soil.csv, static.csv,
// summary.json and what `draw(staging)` adds, moved into place together as
// the command does. As the command, `out` is checked before the fit, and
// Ctrl-C ends the fit at its next iterations with nothing written.
py::tuple match_binding(const py::object& record, const std::optional<std::string>& out, bool force, int jobs,
                        const py::object& draw) {
  const PileRecord rec = pile_record(record);
  check_jobs(jobs);
  std::optional<RunDirectory> dir;
  if (out) {
    dir.emplace(*out, force, "match", true, pda_inputs(rec));
    dir->expect(match_files());  // before the fit
  }
  const MatchResult r =
      interruptible(MatchOptions{}, [&](const MatchOptions& o) { return match_pile(rec, jobs, o.interrupt); });
  if (dir) {
    dir->commit([&](const std::filesystem::path& staging) {
      write_text(staging / "match.csv", match_csv(r));
      write_text(staging / "soil.csv", soil_csv(r));
      write_text(staging / "static.csv", static_csv(r));
      write_text(staging / "summary.json", match_summary_json(r));
      if (!draw.is_none()) draw(staging.string());
    });
  }
  return py::make_tuple(match_csv(r), soil_csv(r), static_csv(r), match_summary_json(r));
}

py::list history_names(const PyResult& p) {
  py::list names;
  for (const char* c : columns) names.append(py::str(c));
  for (const auto& c : p.r.columns) names.append(py::str(c));
  return names;
}

std::unique_ptr<PyResult> run_binding(const Case& c, const py::object& progress) {
  RunOptions options;
  std::exception_ptr failure;
  // Called about every 0.2 s: Ctrl-C (KeyboardInterrupt) stops the run
  // after the step under way, then the user's callback, if any.
  options.progress_interval = progress.is_none() ? 0.2 : 0.5;
  options.progress = [&progress, &failure](const Progress& p) {
    py::gil_scoped_acquire gil;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (progress.is_none()) return true;
      const py::object answer =
          progress(py::dict(py::arg("step") = p.step, py::arg("steps") = p.steps, py::arg("t") = p.t,
                            py::arg("t_end") = p.t_end, py::arg("elapsed") = p.elapsed_seconds));
      return answer.is_none() || answer.cast<bool>();
    } catch (...) {
      failure = std::current_exception();
      return false;
    }
  };
  auto result = std::make_unique<PyResult>(PyResult{c, {}});
  {
    py::gil_scoped_release release;
    result->r = run(c, options);
  }
  if (failure) std::rethrow_exception(failure);
  return result;
}

py::dict check_binding(const Case& c) {
  CaseCheck k;
  {
    py::gil_scoped_release released;
    k = check_case(c);
  }
  py::list penalties;
  for (const auto& p : k.penalties)
    penalties.append(py::dict(py::arg("link") = p.link, py::arg("tau") = p.tau,
                              py::arg("dt_over_tau") = c.time.step / p.tau, py::arg("basis") = p.basis,
                              py::arg("resolved") = c.time.step <= p.tau));
  return py::dict(py::arg("steps") = k.steps, py::arg("step") = c.time.step, py::arg("nodes") = k.nodes,
                  py::arg("stable_step") = k.stable_step ? py::cast(*k.stable_step) : py::none(),
                  py::arg("mass") = k.stable_step ? py::cast(k.mass) : py::none(), py::arg("stability") = k.stability,
                  py::arg("penalties") = penalties, py::arg("timed_steps") = k.timed_steps,
                  py::arg("timed_seconds") = k.timed_seconds, py::arg("estimate_seconds") = k.estimate_seconds,
                  py::arg("trouble") = k.trouble.empty() ? py::none() : py::cast(k.trouble),
                  py::arg("text") = check_text(c, k));
}

// ---- the module, phase by phase

using ResultClass = py::class_<PyResult>;

void bind_case(py::module_& m) {
  py::class_<Case>(m, "Case")
      .def(py::init(&make_case), py::arg("source") = py::none(), py::arg("set") = py::none(),
           "A validated case from a TOML file path, TOML text, a dict {section: {key: value}} or a Case;\n"
           "`set` overrides keys: {'bar.elements': 200} or ['bar.elements=200'].")
      .def("to_toml", &Case::to_toml, "The resolved case as TOML, every default filled in")
      .def_property_readonly("steps", &Case::step_count, "The number of steps N")
      .def("__repr__", [](const Case& c) {
        return "<barimpact.Case " + c.time.scheme + ", " + std::to_string(c.bar_elements()) + " elements, " +
               std::to_string(c.step_count()) + " steps>";
      });
}

// The history's column names: what r[name], `in`, len() and iteration see.
void bind_history_names(ResultClass& result) {
  result
      .def_property_readonly(
          "columns", [](const PyResult& p) { return py::tuple(history_names(p)); },
          "Every column of history.csv by name, in its order (what r[name] takes): the budget's, then joints, far "
          "end, masses, gauges")
      .def(
          "keys", [](const PyResult& p) { return history_names(p); }, "The history's column names, as `columns`")
      .def(
          "__iter__", [](const PyResult& p) { return py::iter(history_names(p)); },
          "Iterates over the history's column names (so dict(r) is the history)")
      .def(
          "__contains__",
          [](const PyResult& p, const py::object& name) {
            if (!py::isinstance<py::str>(name)) return false;
            const auto n = name.cast<std::string>();
            return std::find(columns.begin(), columns.end(), n) != columns.end() ||
                   std::find(p.r.columns.begin(), p.r.columns.end(), n) != p.r.columns.end();
          },
          py::arg("name"), "Whether the history has a column of that name")
      .def(
          "__len__", [](const PyResult& p) { return columns.size() + p.r.columns.size(); },
          "The number of history columns")
      .def_property_readonly(
          "history_columns", [](const PyResult& p) { return history_names(p); },
          "Every column of history.csv, in its order (a list; `columns` as a tuple)");
}

// The history's numbers as numpy views of the result's memory (no copy).
void bind_history_views(ResultClass& result) {
  result
      .def_property_readonly(
          "history",
          [](py::object self) {
            const auto& h = self.cast<const PyResult&>().r.history;
            static_assert(sizeof(HistoryRow) == columns.size() * sizeof(double));
            return view(h.empty() ? nullptr : &h.front().t,
                        {static_cast<py::ssize_t>(h.size()), static_cast<py::ssize_t>(columns.size())},
                        {sizeof(HistoryRow), sizeof(double)}, self);
          },
          "The budget's history rows, shape (rows, 11), columns as the first eleven of history.csv (a view, no copy)")
      .def(
          "__getitem__",
          [](py::object self, const std::string& name) -> py::object {
            const auto& r = self.cast<const PyResult&>().r;
            const auto rows = static_cast<py::ssize_t>(r.history.size());
            for (std::size_t i = 0; i < columns.size(); ++i)
              if (name == columns[i])
                return view(r.history.empty() ? nullptr : &r.history.front().t + i, {rows}, {sizeof(HistoryRow)}, self);
            for (std::size_t i = 0; i < r.columns.size(); ++i)
              if (name == r.columns[i])
                return view(r.extra.empty() ? nullptr : r.extra.data() + i, {rows},
                            {static_cast<py::ssize_t>(r.columns.size() * sizeof(double))}, self);
            throw py::key_error("no history column \"" + name + "\"");
          },
          py::arg("column"), "A history column by its name in history.csv, e.g. r['joint.cushion.force'] (a view)");
  for (std::size_t i = 0; i < columns.size(); ++i) {
    result.def_property_readonly(
        columns[i],
        [i](py::object self) {
          const auto& h = self.cast<const PyResult&>().r.history;
          return view(h.empty() ? nullptr : &h.front().t + i, {static_cast<py::ssize_t>(h.size())},
                      {sizeof(HistoryRow)}, self);
        },
        "One history column (a strided view of `history`, no copy)");
  }
}

// fields.csv's snapshots: the rows' bodies and positions, the times, the fields.
void bind_fields(ResultClass& result) {
  result
      .def_property_readonly(
          "field_body",
          [](const PyResult& p) {
            py::list names;
            for (std::size_t b : p.r.fields.body) names.append(py::str(p.r.fields.body_names[b]));
            return names;
          },
          "The body of each field row (fields.csv's `body` column)")
      .def_property_readonly(
          "x",
          [](py::object self) {
            const auto& f = self.cast<const PyResult&>().r.fields;
            return view(f.x.data(), {static_cast<py::ssize_t>(f.x.size())}, {sizeof(double)}, self);
          },
          "The field rows' positions (fields.csv's `x` of one snapshot)")
      .def_property_readonly(
          "field_t",
          [](py::object self) {
            const auto& f = self.cast<const PyResult&>().r.fields;
            return view(f.t.data(), {static_cast<py::ssize_t>(f.t.size())}, {sizeof(double)}, self);
          },
          "The snapshots' times");
  for (const auto& [name, member] : {std::pair{"u", &Fields::u}, std::pair{"v", &Fields::v},
                                     std::pair{"sigma", &Fields::sigma}, std::pair{"eps_p", &Fields::eps_p}}) {
    result.def_property_readonly(
        name,
        [member](py::object self) {
          const auto& f = self.cast<const PyResult&>().r.fields;
          const auto n = static_cast<py::ssize_t>(f.nodes());
          return view((f.*member).data(), {static_cast<py::ssize_t>(f.count()), n},
                      {n * static_cast<py::ssize_t>(sizeof(double)), sizeof(double)}, self);
        },
        "Field snapshots, shape (snapshots, nodes), a view");
  }
}

// The run as a whole: its summary, its case, and writing its directory.
void bind_run_record(ResultClass& result) {
  result
      .def_property_readonly(
          "summary_json", [](const PyResult& p) { return summary_json(p.c, p.r.summary); }, "summary.json's text")
      .def_property_readonly(
          "complete", [](const PyResult& p) { return p.r.summary.complete; },
          "False when the run stopped early (non-finite state, stopped by the callback, interrupted)")
      .def_property_readonly(
          "case", [](const PyResult& p) { return p.c; }, "The case that produced it (every default filled in)")
      .def(
          "write",
          [](const PyResult& p, const std::string& dir, bool force) {
            RunDirectory out(dir, force, p.command, true, {{p.c.source}, {}});
            out.commit(p.c, p.r);
          },
          py::arg("dir"), py::kw_only(), py::arg("force") = false,
          "Write history.csv, fields.csv (or results.h5: output.format), case.toml, summary.json as `barimpact run "
          "--out dir` does, by the same "
          "rule: a new or empty directory, or one barimpact wrote (replaced); force=True writes beside someone "
          "else's files and deletes none of them");
}

void bind_result(py::module_& m) {
  auto result = ResultClass(m, "Result");
  bind_history_names(result);
  bind_history_views(result);
  bind_fields(result);
  bind_run_record(result);
}

void bind_run(py::module_& m) {
  m.def("run", &run_binding, py::arg("case"), py::arg("progress") = py::none(),
        "Run a case (the GIL is released); `progress(info: dict)` is called about twice a second,\n"
        "returning False stops the run. Ctrl-C stops it too, raising KeyboardInterrupt.");

  m.def(
      "exact",
      [](const Case& c) {
        auto result = std::make_unique<PyResult>(PyResult{c, {}, "exact"});
        result->r = run_exact(c);
        return result;
      },
      py::arg("case"), "Tabulate the exact solution the case admits (as `barimpact exact`); InputError if none");

  m.def("_check", &check_binding, py::arg("case"), "check_case and check_text (run/check.hpp); use barimpact.check");
}

void bind_studies(py::module_& m) {
  m.def(
      "_converge",
      [](const Case& c, const std::optional<std::string>& out, int levels, int ratio,
         const std::optional<std::string>& refine, const std::optional<std::string>& vary,
         const std::vector<std::string>& schemes, const std::string& reference, int jobs, bool force,
         const std::string& command) {
        StudyArguments args;
        args.levels = levels;
        args.ratio = ratio;
        args.refine = refine;
        args.vary = vary;
        args.schemes = schemes;
        args.reference = reference;
        args.jobs = jobs;
        return converge_binding(c, out, args, force, command);
      },
      py::arg("case"), py::arg("out"), py::arg("levels"), py::arg("ratio"), py::arg("refine"), py::arg("vary"),
      py::arg("schemes"), py::arg("reference"), py::arg("jobs"), py::arg("force"), py::arg("command"),
      "write_convergence, or converge without `out` (the converge command without its figures); use "
      "barimpact.converge");

  m.def("_sweep", &sweep_binding, py::arg("sweep"), py::arg("out"), py::arg("jobs"), py::arg("batch"), py::arg("force"),
        "write_sweep (the sweep command without MPI); use barimpact.sweep");

  m.def("_bearing", &bearing_binding, py::arg("case"), py::arg("out"), py::arg("capacity"), py::arg("toe_share"),
        py::arg("jobs"), py::arg("force"), py::arg("set") = py::none(),
        "write_bearing (the bearing command without its figure); use barimpact.bearing");

  m.def("_drive", &drive_binding, py::arg("case"), py::arg("out"), py::arg("jobs"), py::arg("force"),
        py::arg("set") = py::none(), "write_drive (the drive command without its figure); use barimpact.drive");
  m.def("_inspector", &inspector_binding, py::arg("case"), py::arg("out"), py::arg("stroke"), py::arg("depth"),
        py::arg("jobs"), py::arg("force"), py::arg("set") = py::none(),
        "write_inspector (the inspector command without its figure); use barimpact.inspector");
  m.def("_hammers_csv", &hammers_csv, "The shipped hammers as CSV; use barimpact.hammers");

  m.def("_pda", &pda_binding, py::arg("record"), py::arg("out") = py::none(), py::arg("force") = false,
        py::arg("draw") = py::none(),
        "The analysis of a pile's record, and with `out` its directory; use barimpact.pda");
  m.def("_match", &match_binding, py::arg("record"), py::arg("out") = py::none(), py::arg("force") = false,
        py::arg("jobs") = 0, py::arg("draw") = py::none(),
        "The signal matching of a pile's record, and with `out` its directory; use barimpact.match");
  m.def("_hopkinson", &hopkinson_binding, py::arg("setup"), py::arg("out") = py::none(), py::arg("force") = false,
        py::arg("draw") = py::none(), "The Hopkinson analysis, and with `out` its directory; use barimpact.hopkinson");
}

// What a Python writer reads: directories it never writes over.
CommandInputs directories_read(const std::vector<std::string>& reads) {
  return {{}, std::vector<std::filesystem::path>(reads.begin(), reads.end())};
}

// The output rule for what Python writes itself (figures, plot's directory).
void bind_output_rule(py::module_& m) {
  m.def(
      "_prepare_output_directory",
      [](const py::object& target, const std::string& command, const std::vector<std::string>& entries, bool force,
         const std::vector<std::string>& reads) {
        prepare_output_directory(fspath(target), command, entries, force, "--out", directories_read(reads));
      },
      py::arg("target"), py::arg("command"), py::arg("entries"), py::arg("force"), py::arg("reads") = py::list(),
      "The output rule for a directory filled bit by bit (output_directory.hpp): checks (never over the "
      "directories `reads`, which the caller reads), creates, marks");

  m.def(
      "_check_output_directory",
      [](const py::object& target, bool force, const std::vector<std::string>& reads) {
        (void)check_output_directory(fspath(target), force, "--out", directories_read(reads));
      },
      py::arg("target"), py::arg("force"), py::arg("reads") = py::list(),
      "The output rule's check alone (output_directory.hpp): InputError when `target` may not be written");

  m.def(
      "_output_command", [](const py::object& dir) { return output_command(fspath(dir)); }, py::arg("dir"),
      "The command that wrote `dir` by its marker (\"run\", \"converge\", ...), or \"\"");

  m.def(
      "_is_staging",
      [](const py::object& dir) { return std::filesystem::exists(std::filesystem::path(fspath(dir)) / staging_flag); },
      py::arg("dir"), "Whether `dir` is a staging directory barimpact fills (output.hpp's RunDirectory)");

  m.def(
      "_run_case_file", [](const py::object& dir) { return run_case_file(fspath(dir)).string(); }, py::arg("dir"),
      "The resolved case of a run directory: case.toml, or case.resolved.toml (output.hpp)");

  m.def(
      "_written_by_barimpact", [](const py::object& dir) { return written_by_barimpact(fspath(dir)); }, py::arg("dir"),
      "Whether barimpact wrote `dir` (its marker lists everything in it)");

  m.def(
      "_mark_entries",
      [](const py::object& dir, const std::vector<std::string>& entries) {
        const std::filesystem::path d(fspath(dir));
        write_output_marker(d, output_command(d), entries);
      },
      py::arg("dir"), py::arg("entries"), "Adds `entries` to the marker of a directory barimpact wrote");

  m.attr("_figure_names") =
      py::tuple(py::cast(std::vector<std::string>(run_figure_names.begin(), run_figure_names.end())));
}

void bind_exact_solutions(py::module_& m) {
  m.def(
      "_exact_example1",
      [](py::array_t<double, py::array::c_style | py::array::forcecast> x,
         py::array_t<double, py::array::c_style | py::array::forcecast> t, double length, double stiffness,
         double density, double v0) {
        const exact::Example1 e(length, stiffness, density, v0);
        const auto n = x.size();
        if (t.size() != n) throw std::invalid_argument("x and t must have the same size");
        py::array_t<double> u(n), v(n), strain(n), R(n);
        auto xs = x.unchecked<1>();
        auto ts = t.unchecked<1>();
        auto uu = u.mutable_unchecked<1>(), vv = v.mutable_unchecked<1>(), ss = strain.mutable_unchecked<1>(),
             rr = R.mutable_unchecked<1>();
        for (py::ssize_t i = 0; i < n; ++i) {
          uu(i) = e.u(xs(i), ts(i));
          vv(i) = e.v(xs(i), ts(i));
          ss(i) = e.strain(xs(i), ts(i));
          rr(i) = e.R(ts(i));
        }
        return py::make_tuple(u, v, strain, R);
      },
      py::arg("x"), py::arg("t"), py::arg("length"), py::arg("stiffness"), py::arg("density"), py::arg("v0"));
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "barimpact's C++ core; use the package `barimpact`";
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
  // What the file system refused (a full disk): caught as either kind.
  py::register_exception<OutputError>(m, "OutputError",
                                      py::make_tuple(m.attr("InputError"), py::handle(PyExc_OSError)));
  // A module of the install missing (the fitting module): bad input's one
  // line, and an ImportError to code that catches one.
  py::register_exception<MissingModule>(m, "MissingModuleError",
                                        py::make_tuple(m.attr("InputError"), py::handle(PyExc_ImportError)));
  // A case too large for the memory there is: bad input as any other (the
  // command line's words), and still a MemoryError to code that catches one.
  static py::exception<std::bad_alloc> out_of_memory(
      m, "OutOfMemoryError", py::make_tuple(m.attr("InputError"), py::handle(PyExc_MemoryError)));
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const MemoryRefusal& e) {
      PyErr_SetString(out_of_memory.ptr(), e.what());  // refused before it was built
    } catch (const std::bad_alloc&) {
      PyErr_SetString(out_of_memory.ptr(),
                      "out of memory: the case needs more than there is (reduce its elements or bodies, or raise "
                      "output.every)");
    }
  });
  bind_case(m);
  bind_result(m);
  bind_run(m);
  bind_studies(m);
  bind_output_rule(m);
  bind_exact_solutions(m);
}
