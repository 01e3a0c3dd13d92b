// barimpact._core: the C++ library seen from Python. Thin: every number is
// computed by the library; this file only converts and shares memory.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fmt/format.h>
#include <toml++/toml.h>
#include <exception>
#include <filesystem>
#include <sstream>

#include "barimpact/case/case.hpp"
#include "barimpact/exact/exact.hpp"
#include "barimpact/hopkinson/analysis.hpp"
#include "barimpact/run/output.hpp"
#include "barimpact/run/simulate.hpp"
#include "barimpact/study/bearing.hpp"

namespace py = pybind11;
using namespace barimpact;

namespace {

// A run's result with the case that produced it (for summary.json and write).
struct PyResult {
  Case c;
  RunResult r;
};

// One table's keys: numbers, strings, booleans, lists of them.
toml::table keys_table(const py::dict& keys) {
  toml::table t;
  for (auto [key, value] : keys) {
    const auto k = py::str(key).cast<std::string>();
    if (py::isinstance<py::bool_>(value)) {
      t.insert(k, value.cast<bool>());
    } else if (py::isinstance<py::int_>(value)) {
      t.insert(k, value.cast<long long>());
    } else if (py::isinstance<py::float_>(value)) {
      t.insert(k, value.cast<double>());
    } else if (py::isinstance<py::str>(value)) {
      t.insert(k, value.cast<std::string>());
    } else if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value) ||
               py::isinstance<py::array>(value)) {
      toml::array a;
      for (auto item : value) {
        if (py::isinstance<py::int_>(item))
          a.push_back(item.cast<long long>());
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
        tables.push_back(keys_table(item.cast<py::dict>()));
      }
      root.insert(name, std::move(tables));
      continue;
    }
    if (!py::isinstance<py::dict>(keys))
      throw InputError("dict: [" + name + "] must be a dict of keys, or a list of dicts for [[" + name + "]] (got " +
                       py::str(keys.get_type().attr("__name__")).cast<std::string>() + ")");
    root.insert(name, keys_table(keys.cast<py::dict>()));
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
  for (auto item : set) out.push_back({py::str(item).cast<std::string>()});
  return out;
}

Case make_case(const py::object& source, const py::object& set) {
  const auto overrides = overrides_from(set);
  if (source.is_none()) return Case::from_string("", overrides, "defaults");
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

// A read-only numpy view of `n` doubles spaced `stride` apart, kept alive by `owner`.
py::array view(const double* data, std::vector<py::ssize_t> shape, std::vector<py::ssize_t> strides, py::handle owner) {
  py::array a(py::dtype::of<double>(), std::move(shape), std::move(strides), data, owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

constexpr std::array<const char*, 11> columns{"t",          "U",     "V",      "R",         "E_kin",    "E_strain",
                                              "E_obstacle", "W_ext", "D_visc", "D_contact", "D_plastic"};

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "barimpact's C++ core; use the package `barimpact`";
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError);

  py::class_<Case>(m, "Case")
      .def(py::init(&make_case), py::arg("source") = py::none(), py::arg("set") = py::none(),
           "A validated case from a TOML file path, TOML text or a dict {section: {key: value}};\n"
           "`set` overrides keys: {'bar.elements': 200} or ['bar.elements=200'].")
      .def("to_toml", &Case::to_toml, "The resolved case as TOML, every default filled in")
      .def_property_readonly("steps", &Case::step_count, "The number of steps N")
      .def("__repr__", [](const Case& c) {
        return "<barimpact.Case " + c.time.scheme + ", " + std::to_string(c.bar.elements) + " elements, " +
               std::to_string(c.step_count()) + " steps>";
      });

  auto result = py::class_<PyResult>(m, "Result");
  result
      .def_property_readonly_static("columns",
                                    [](py::object) {
                                      py::tuple names(columns.size());
                                      for (std::size_t i = 0; i < columns.size(); ++i) names[i] = py::str(columns[i]);
                                      return names;
                                    })
      .def_property_readonly(
          "history",
          [](py::object self) {
            const auto& h = self.cast<const PyResult&>().r.history;
            static_assert(sizeof(HistoryRow) == columns.size() * sizeof(double));
            return view(h.empty() ? nullptr : &h.front().t,
                        {static_cast<py::ssize_t>(h.size()), static_cast<py::ssize_t>(columns.size())},
                        {sizeof(HistoryRow), sizeof(double)}, self);
          },
          "The budget's history rows, shape (rows, 10), columns as the first ten of history.csv (a view, no copy)")
      .def_property_readonly(
          "history_columns",
          [](const PyResult& p) {
            py::list names;
            for (const char* c : columns) names.append(py::str(c));
            for (const auto& c : p.r.columns) names.append(py::str(c));
            return names;
          },
          "Every column of history.csv, in its order: the budget's, then joints, far end, masses, gauges")
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
          py::arg("column"), "A history column by its name in history.csv, e.g. r['joint.cushion.force'] (a view)")
      .def_property_readonly(
          "field_body",
          [](const PyResult& p) {
            py::list names;
            for (std::size_t b : p.r.fields.body) names.append(py::str(p.r.fields.body_names[b]));
            return names;
          },
          "The body of each field row (fields.csv's `body` column)")
      .def_property_readonly("x",
                             [](py::object self) {
                               const auto& f = self.cast<const PyResult&>().r.fields;
                               return view(f.x.data(), {static_cast<py::ssize_t>(f.x.size())}, {sizeof(double)}, self);
                             })
      .def_property_readonly("field_t",
                             [](py::object self) {
                               const auto& f = self.cast<const PyResult&>().r.fields;
                               return view(f.t.data(), {static_cast<py::ssize_t>(f.t.size())}, {sizeof(double)}, self);
                             })
      .def_property_readonly("summary_json", [](const PyResult& p) { return summary_json(p.c, p.r.summary); })
      .def_property_readonly("complete", [](const PyResult& p) { return p.r.summary.complete; })
      .def_property_readonly("case", [](const PyResult& p) { return p.c; })
      .def(
          "write",
          [](const PyResult& p, const std::string& dir, bool force) {
            RunDirectory out(dir, force);
            out.commit(p.c, p.r);
          },
          py::arg("dir"), py::kw_only(), py::arg("force") = false,
          "Write history.csv, fields.csv, case.toml, summary.json as `barimpact run --out dir` does, by the same "
          "rule: a new or empty directory, or one barimpact wrote (replaced); force=True writes beside someone "
          "else's files and deletes none of them");

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

  m.def(
      "run",
      [](const Case& c, const py::object& progress) {
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
      },
      py::arg("case"), py::arg("progress") = py::none(),
      "Run a case (the GIL is released); `progress(info: dict)` is called about twice a second,\n"
      "returning False stops the run. Ctrl-C stops it too, raising KeyboardInterrupt.");

  m.def(
      "_bearing",
      [](const std::string& case_file, const std::string& out, double from, double to, int count,
         const py::object& toe_share, int jobs, bool force) {
        BearingOptions o;
        o.from = from;
        o.to = to;
        o.count = count;
        parse_capacity(fmt::format("{}:{}:{}", from, to, count), o);  // the command's rules
        if (!toe_share.is_none()) o.toe_share = toe_share.cast<double>();
        const BearingPlan plan(case_file, o);
        SweepOptions options;
        options.jobs = jobs;
        options.batch = false;
        py::gil_scoped_release release;
        (void)write_bearing(plan, out, options, force);
      },
      py::arg("case"), py::arg("out"), py::arg("capacity_from"), py::arg("capacity_to"), py::arg("count"),
      py::arg("toe_share") = py::none(), py::arg("jobs") = 0, py::arg("force") = false);

  m.def(
      "exact",
      [](const Case& c) {
        auto result = std::make_unique<PyResult>(PyResult{c, {}});
        result->r = run_exact(c);
        return result;
      },
      py::arg("case"), "Tabulate the exact solution the case admits (as `barimpact exact`); InputError if none");

  m.def(
      "_hopkinson",
      [](const py::object& setup) {
        HopkinsonSetup s;
        if (py::isinstance<py::dict>(setup)) {
          std::ostringstream text;  // the file's reader checks a dict too
          text << toml::toml_formatter(table_from_dict(setup.cast<py::dict>()));
          s = HopkinsonSetup::from_string(text.str(), std::filesystem::current_path(), "setup");
        } else {
          s = HopkinsonSetup::from_file(py::str(setup).cast<std::string>());
        }
        HopkinsonResult r;
        {
          py::gil_scoped_release release;
          r = analyse_hopkinson(s);
        }
        py::dict table;
        for (const auto& c : r.columns) {
          py::array_t<double> a(static_cast<py::ssize_t>(c.values.size()));
          std::copy(c.values.begin(), c.values.end(), a.mutable_data());
          table[py::str(c.name)] = a;
        }
        return py::make_tuple(table, hopkinson_summary_json(r));
      },
      py::arg("setup"));

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
