"""barimpact: bodies hitting each other along a line (Do, Raupp & Feijoo 1979).

    import barimpact
    case = barimpact.Case("examples/paper-example1.toml", set={"time.lambda": 0.25})
    result = barimpact.run(case)
    result.t, result.U, result["R"]       # numpy views of the history, no copy
    result.u                              # field snapshots, shape (snapshots, nodes)
    result.summary                        # the summary.json dict
    result.to_pandas()                    # the history as a DataFrame (with pandas)
    barimpact.plot(result, "figures")     # PNG and SVG

Every command of `barimpact` has its function, with the command's options
as keywords (--toe-share is toe_share=...):

    barimpact run CASE --out DIR        barimpact.run(case, out=DIR)
    barimpact exact CASE --out DIR      barimpact.exact(case, out=DIR)
    barimpact converge CASE --out DIR   barimpact.converge(case, out=DIR, levels=3)
    barimpact sweep SWEEP --out DIR     barimpact.sweep(sweep, out=DIR, jobs=4)
    barimpact bearing CASE --out DIR    barimpact.bearing(case, DIR, capacity=(1e6, 5e7, 10))
    barimpact hopkinson SETUP --out DIR barimpact.hopkinson(setup, out=DIR)
    barimpact pda RECORD --out DIR      barimpact.pda(record, out=DIR)
    barimpact match RECORD --out DIR    barimpact.match(record, out=DIR, jobs=4)
    barimpact plot DIR                  barimpact.plot(DIR)

They write the same files by the same rules (the output directory, resuming,
--force), return the table the command writes (convergence.csv, sweep.csv,
bearing.csv, hopkinson.csv, pda.csv, match.csv) as a `Table`, release the
GIL while they run, and stop on Ctrl-C after writing what is done, as the
command does. The health checks' warnings are `HealthWarning`s; strict=True
raises `StrictError` after writing, where the command exits 4.

Every number comes from the C++ library (barimpact._core): the same code as
the `barimpact` command line, so the same case gives the same bits.
"""
import csv
import io
import json
import numbers
import os
import warnings
from pathlib import Path as _Path

import numpy as np

# The submodules first: importing one later would rebind the package's name
# (barimpact.bearing, barimpact.hopkinson, barimpact.match, barimpact.plot)
# from the function to the module.
from . import bearing as _bearing_figures
from . import drive as _drive_figures
from . import convergence as _convergence_figures
from . import hopkinson as _hopkinson_figures
from . import match as _match_figures
from . import pda as _pda_figures
from . import plot as _figures
from . import _core
from ._core import Case, InputError, MissingModuleError, OutOfMemoryError, OutputError, Result

InputError.__module__ = "barimpact"  # tracebacks say barimpact.InputError, where users catch it
OutputError.__module__ = "barimpact"
OutOfMemoryError.__module__ = "barimpact"
MissingModuleError.__module__ = "barimpact"
from .plot import RunData, load

__all__ = ["Case", "Result", "InputError", "OutputError", "OutOfMemoryError", "MissingModuleError", "HealthWarning", "StrictError", "Table", "HopkinsonTable",
           "PdaTable", "MatchTable",
           "RunData", "run", "check", "exact", "converge", "sweep", "bearing", "drive", "inspector", "hammers", "hopkinson", "pda", "match", "plot", "load",
           "read_table", "exact_example1"]


class HealthWarning(UserWarning):
    """A run's health checks warned (the command's `barimpact: warning:`
    lines): energy balance, an unresolved penalty and the like. The results
    are kept. Silence them with
    `warnings.simplefilter("ignore", barimpact.HealthWarning)`; a study's
    notes (runs that did not complete) come as HealthWarning too."""


class StrictError(RuntimeError):
    """strict=True and the health checks warned: the command's exit status 4.
    The results were written all the same; `result` holds what the call
    would have returned, `warnings` the warnings (one string each)."""

    def __init__(self, message, result, warnings):
        super().__init__(message)
        self.result = result
        self.warnings = list(warnings)


def _pandas(what):
    try:
        import pandas
    except ImportError as e:
        raise ImportError(f"{what} needs pandas, which is not installed here (Debian: apt-get install python3-pandas; "
                          "elsewhere: pip install pandas). Without it the columns are numpy arrays: "
                          "dict(table) or result[name].") from e
    return pandas


class Table(dict):
    """A results table (convergence.csv, sweep.csv, bearing.csv,
    hopkinson.csv): its columns by name, in the file's order, as numpy arrays
    (floats with nan where a cell is missing and inf where the file says inf;
    integers; booleans; text as str arrays, so `t.status == "complete"` is a
    mask). A dict: t["status"]; and by attribute where the name allows it:
    t.status. `summary` holds what the file does not (a dict, or None)."""

    summary = None

    def __init__(self, columns=(), summary=None):
        super().__init__(columns)
        if summary is not None:
            self.summary = summary

    def __getattr__(self, name):
        if name.startswith("__"):
            raise AttributeError(name)  # copy, pickle and friends probe dunders
        try:
            return self[name]
        except KeyError:
            raise AttributeError(f"{type(self).__name__} has no column or attribute {name!r} "
                                 f"(columns: {', '.join(self)})") from None

    def __dir__(self):
        return sorted(set(super().__dir__()) | {name for name in self if name.isidentifier()})

    @property
    def columns(self):
        """The column names, in the file's order."""
        return tuple(self)

    @property
    def rows(self):
        """The number of rows."""
        return len(next(iter(self.values()))) if self else 0

    def row(self, i):
        """Row `i` as a dict of Python scalars."""
        return {name: values[i].item() if isinstance(values[i], np.generic) else values[i]
                for name, values in self.items()}

    def to_pandas(self):
        """The table as a pandas DataFrame, the same columns in the same
        order. ImportError (saying so) without pandas."""
        pandas = _pandas("Table.to_pandas")
        return pandas.DataFrame({name: np.asarray(values) for name, values in self.items()})

    def __repr__(self):
        return f"<barimpact.{type(self).__name__}: {self.rows} rows, columns {', '.join(self)}>"


class HopkinsonTable(Table):
    """hopkinson.csv's columns by name (numpy arrays, nan where missing), and
    `summary`, summary.json as a dict."""


class PdaTable(Table):
    """pda.csv's columns by name (numpy arrays), and `summary`, summary.json
    as a dict (t1, t2, fmx, vmx, emx, dmx, csx, tsx, rmx, rmx_time, rsp, bta,
    bta_depth, ...)."""


class MatchTable(Table):
    """match.csv's columns by name (numpy arrays: t, force_measured,
    force_computed, velocity_z, wave_up_measured, wave_up_computed; N, s),
    `summary`, summary.json as a dict (capacity, shaft, toe, match_quality,
    s_c, t1, t2, start_results, ...), and the other two files as `Table`s:
    `soil`, soil.csv (segment as text, "1" .. and "toe" for the last row;
    top, bottom in m below the gauges, resistance in N, quake in m, damping
    in s/m) and `static`, static.csv (settlement in m, load in N)."""

    soil = None
    static = None

    def __init__(self, columns=(), summary=None, soil=None, static=None):
        super().__init__(columns, summary)
        if soil is not None:
            self.soil = soil
        if static is not None:
            self.static = static


# The columns whose type the name fixes; the others (a sweep's axes,
# convergence's value, hopkinson's) are numbers when every cell is one.
_INTEGER = frozenset({"level", "elements", "contact_episodes", "steps_done", "contacts"})
_BOOLEAN = frozenset({"finished"})
_TEXT = frozenset({"id", "scheme", "status", "message", "warnings"})


def _column(name, cells):
    if name in _TEXT:
        return np.array(cells, dtype=str)
    if name in _INTEGER:
        return np.array([int(c) for c in cells], dtype=np.int64)
    if name in _BOOLEAN:
        return np.array([c == "true" for c in cells], dtype=bool)
    if cells and all(c == "" for c in cells):
        return np.array(cells, dtype=str)  # convergence.csv's value without --vary
    try:
        return np.array([float(c) if c != "" else np.nan for c in cells], dtype=float)
    except ValueError:
        return np.array(cells, dtype=str)  # an axis of words: schemes, laws


def _table_from_csv(text, summary=None, table=Table):
    """A table from the text of a CSV that barimpact wrote."""
    reader = csv.reader(io.StringIO(text))
    header = next(reader, [])
    rows = list(reader)
    cells = [[row[i] for row in rows] for i in range(len(header))]
    return table({name: _column(name, c) for name, c in zip(header, cells)}, summary)


_TABLES = ("convergence.csv", "sweep.csv", "bearing.csv", "drive.csv", "hopkinson.csv", "pda.csv", "match.csv")


def read_table(path):
    """A table the command wrote, as a `Table`: `path` a CSV file or a
    directory holding one (convergence.csv, sweep.csv, bearing.csv,
    hopkinson.csv, pda.csv, match.csv). A Hopkinson or pda directory's
    table is a `HopkinsonTable` or `PdaTable` with summary.json as
    `summary`; a match directory's a `MatchTable`, with soil.csv and
    static.csv beside it as `soil` and `static`."""
    p = _Path(os.fspath(path))
    if p.is_dir():
        found = [p / name for name in _TABLES if (p / name).is_file()]
        if not found:
            raise InputError(f"{path}: holds none of {', '.join(_TABLES)} (give a directory barimpact wrote)")
        p = found[0]
    kind = {"hopkinson.csv": HopkinsonTable, "pda.csv": PdaTable, "match.csv": MatchTable}.get(p.name)
    if kind is not None:
        summary_file = p.with_name("summary.json")
        summary = json.loads(summary_file.read_text()) if summary_file.is_file() else None
        if kind is MatchTable:
            return _match_table(p.read_text(), *(p.with_name(n).read_text() for n in ("soil.csv", "static.csv")),
                                summary)
        return _table_from_csv(p.read_text(), summary, kind)
    return _table_from_csv(p.read_text())


def _match_table(match_csv, soil_csv, static_csv, summary):
    table = _table_from_csv(match_csv, summary, MatchTable)
    table.soil, table.static = _table_from_csv(soil_csv), _table_from_csv(static_csv)
    return table


def _result_to_pandas(self):
    """The history as a pandas DataFrame: one column per history.csv column,
    in its order (copies). ImportError (saying so) without pandas."""
    pandas = _pandas("Result.to_pandas")
    return pandas.DataFrame({name: np.array(self[name]) for name in self.keys()})


def _fields_table(self):
    """fields.csv's columns as a `Table`, one row per snapshot and node:
    t, x, u, v, sigma, eps_p, body (views where numpy allows)."""
    nodes, snapshots = self.x.size, self.field_t.size
    return Table({"t": np.repeat(self.field_t, nodes), "x": np.tile(self.x, snapshots), "u": self.u.ravel(),
                  "v": self.v.ravel(), "sigma": self.sigma.ravel(), "eps_p": self.eps_p.ravel(),
                  "body": np.tile(np.array(self.field_body, dtype=str), snapshots)})


def _fields_to_pandas(self):
    """fields.csv as a pandas DataFrame (long form: t, x, u, v, sigma, eps_p,
    body; one row per snapshot and node). ImportError without pandas."""
    _pandas("Result.fields_to_pandas")
    return self.fields_table().to_pandas()


def _result_repr(self):
    s = self.summary
    return (f"<barimpact.Result {s.get('status', '?')}: {self.t.size} rows, {len(self)} history columns, "
            f"{self.field_t.size} snapshots>")


Result.summary = property(lambda self: json.loads(self.summary_json), doc="summary.json as a dict")
Result.to_pandas = _result_to_pandas
Result.fields_table = _fields_table
Result.fields_to_pandas = _fields_to_pandas
Result.__repr__ = _result_repr


# ---- shared by the commands' functions


def _case(case, set):
    if isinstance(case, Case) and set is None:
        return case
    return Case(case, set=set)  # a Case with overrides keeps the file it was read from


def _jobs(jobs):
    """--jobs: None or 0 for every core, else 1 .. 1024."""
    # The studies' check_jobs refuses the same range but names 0, not None, and
    # a non-integer would reach it as the binding's TypeError: refused here.
    if jobs is None or jobs == 0:
        return 0
    if not isinstance(jobs, numbers.Integral) or not 1 <= jobs <= 1024:
        raise InputError(f"--jobs: must be 1 .. 1024, or None for every core (got {jobs!r})")
    return int(jobs)


def _out(out):
    return None if out is None else os.fspath(out)


def _warn(lines, stacklevel=3):
    """Warnings pointing at the line that called the public function."""
    for line in lines:
        warnings.warn(line, HealthWarning, stacklevel=stacklevel)


def _study_warnings(pairs, report, shown=20):
    """The runs' warnings, the first 20 of them as the command prints them
    (a large sweep would bury the output); the CSV's warnings column has all."""
    lines = [f"{run_id}: {w}" for run_id, w in pairs]
    _warn(lines[:shown], stacklevel=4)
    if len(lines) > shown:
        _warn([f"... {len(lines) - shown} more (the warnings column of {report})"], stacklevel=4)
    return lines


def _strict(strict, lines, result, what):
    """--strict: the results are written; then the warnings are an error."""
    if strict and lines:
        raise StrictError(f"strict: {what} warned ({len(lines)} warning{'s' if len(lines) != 1 else ''}; the results "
                          "are written)", result, lines)


def _call_text(name, args, options, defaults):
    """The call as Python, for convergence.md's first line (the command puts
    its command line there): the options that differ from the defaults."""
    def show(v):
        return repr(os.fspath(v)) if isinstance(v, os.PathLike) else repr(v)

    def given(k, v):
        try:
            return bool(v != defaults.get(k))
        except ValueError:  # an array: shown
            return True
    parts = [show(a) for a in args] + [f"{k}={show(v)}" for k, v in options.items() if given(k, v)]
    return f"barimpact.{name}({', '.join(parts)})"


def _toml_text(value):
    """A value as the command line writes it after key=."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        return repr(float(value))
    return str(value)


def _finish_run(result, out, force, strict, what):
    if out is not None:
        result.write(os.fspath(out), force=force)
    lines = result.summary.get("warnings", [])
    _warn(lines, stacklevel=4)
    _strict(strict, lines, result, what)
    return result


# ---- the commands


def run(case, progress=None, *, out=None, set=None, force=False, strict=False):
    """Run a case (`barimpact run CASE [--out DIR] [--set ...]`): `case` a
    `Case`, or anything `Case` accepts (a path, TOML text, a dict); `set`
    overrides keys ({"bar.elements": 200} or ["bar.elements=200"]). The GIL is
    released while it runs; Ctrl-C stops it, raising KeyboardInterrupt.
    `progress`, if given, is called about twice a second with a dict (step,
    steps, t, t_end, elapsed); returning False stops the run (the result is
    then marked incomplete). With `out`, writes history.csv, fields.csv
    (or results.h5, when the case says `[output] format = "hdf5"`), case.toml
    and summary.json there by the command's output rule (`force` as --force);
    what the file system refuses (a full disk) raises `OutputError`, an
    InputError and an OSError, with nothing half-written left there.
    The health checks' warnings are `HealthWarning`s; strict=True raises
    `StrictError` after writing instead (the command's exit 4)."""
    result = _core.run(_case(case, set), progress)
    return _finish_run(result, out, force, strict, "the run")


def check(case, *, set=None):
    """Validate a case without running it (`barimpact check CASE [--set ...]`):
    a dict with `steps`, `step`, `nodes`, `stable_step` and the `mass` matrix
    it was bounded with (explicit schemes, and the implicit ones only
    conditionally stable; else None), `stability` in words, `penalties` (per
    penalty law: link, tau, dt_over_tau, basis such as "Z/k", resolved),
    `estimate_seconds` (timed on `timed_steps` steps), `trouble` (the timed
    stretch went non-finite: where; else None) and `text`, the command's
    report. InputError (one line) for a bad case, as the command's exit 2."""
    return _core._check(_case(case, set))


def exact(case, *, out=None, set=None, force=False, strict=False):
    """The exact solution the case admits, tabulated on its grid like a run
    (`barimpact exact CASE [--out DIR]`): rigid impact with gap, with a
    constant load, elastic obstacle, or the clamped periodic benchmark.
    InputError if none. `out`, `set`, `force`, `strict` as for `run`."""
    result = _core.exact(_case(case, set))
    return _finish_run(result, out, force, strict, "the exact solution")


_CONVERGE_DEFAULTS = dict(out=None, set=None, levels=4, ratio=2, refine=None, vary=None, schemes=None,
                          reference="auto", jobs=None, no_plot=False, force=False, strict=False)


def _vary_text(vary):
    """--vary: "key=v1,v2,..." | "key=a:b:n" | "key=log:a:b:n", or (key,
    [values]), or (key, "a:b:n")."""
    if vary is None or isinstance(vary, str):
        return vary
    key, values = vary
    spec = values if isinstance(values, str) else ",".join(_toml_text(v) for v in values)
    return f"{key}={spec}"


def _scheme_list(schemes):
    if schemes is None:
        return []
    return schemes.split(",") if isinstance(schemes, str) else [str(s) for s in schemes]


def converge(case, out=None, *, set=None, levels=4, ratio=2, refine=None, vary=None, schemes=None, reference="auto",
             jobs=None, no_plot=False, force=False, strict=False):
    """A convergence and work-precision study (`barimpact converge CASE --out
    DIR`): the case run at `levels` refinements (2 .. 12), h and/or dt divided
    by `ratio` (2 .. 16) per level as `refine` says ("both", the default, "h",
    "dt", "none"), or along `vary` ("key=v1,v2,..." | "key=a:b:n" |
    "key=log:a:b:n", or (key, [values]); refine then defaults to "none"), for
    each of `schemes` ("a,b" or a list; default the case's), each run measured
    against `reference` ("auto": the exact solution if the case admits one,
    else the finest run; "rigid"; "finest"). `case` anything `Case` accepts,
    `set` its overrides; `jobs` threads (None: every core).

    With `out` the study goes there as the command's: runs/<scheme>-<level>/,
    convergence.csv, convergence.md and, unless no_plot, convergence.png and
    work_precision.png (a rerun resumes; `force` as --force). Without it
    nothing is written. Returns convergence.csv's table with `summary`
    {"reference", "abscissa", "markdown", "directory"}. Ctrl-C stops the runs
    under way, writes what is done and raises KeyboardInterrupt. Warnings are
    `HealthWarning`s; strict=True raises `StrictError` after writing."""
    options = dict(out=out, set=set, levels=levels, ratio=ratio, refine=refine, vary=vary, schemes=schemes,
                   reference=reference, jobs=jobs, no_plot=no_plot, force=force, strict=strict)
    command = _call_text("converge", [case], options, _CONVERGE_DEFAULTS)
    done = _core._converge(_case(case, set), _out(out), int(levels), int(ratio), refine, _vary_text(vary),
                           _scheme_list(schemes), reference, _jobs(jobs), bool(force), command)
    table = _table_from_csv(done["csv"], {"reference": done["reference"], "abscissa": done["abscissa"],
                                          "markdown": done["markdown"], "directory": _out(out)})
    if out is not None and not no_plot and done["results"] > 0:
        _convergence_figures.plot_study(out)
    lines = _study_warnings(done["warnings"], "convergence.csv")
    if done["results"] < done["runs"]:
        _warn([f"{done['runs'] - done['results']} of {done['runs']} runs did not complete; see their rows"])
    _strict(strict, lines, table, "the study's runs")
    return table


def _nested(keys):
    """{"time.step": 0.1} -> {"time": {"step": 0.1}}: a sweep's [set] as TOML nests it."""
    out = {}
    for key, value in keys.items():
        *sections, last = str(key).split(".")
        d = out
        for s in sections:
            d = d.setdefault(s, {})
        d[last] = _nested(value) if isinstance(value, dict) else value
    return out


def sweep(sweep_file, out, *, jobs=None, no_batch=False, force=False, strict=False):
    """Every case of a sweep (`barimpact sweep SWEEP --out DIR`): `sweep_file` a
    sweep file, or the same as a dict ({"case": "paper-example1.toml", "set":
    {"time.end": 2.0}, "axis": [{"key": "obstacle.stiffness", "values": [100.0,
    1000.0]}], "zip": [[...]]}; `case` then from the working directory).
    Writes runs/<id>/ and sweep.csv into `out` (a rerun resumes: cases whose
    run is there are read back, not run); `jobs` threads (None: every core),
    `no_batch` runs every case alone (no SIMD batches), `force` as --force.
    Returns sweep.csv's table (the axes' values as numbers where they are)
    with `summary` {"cases", "run", "batched", "resumed", "complete",
    "directory"}. Ctrl-C stops the cases under way, writes sweep.csv and
    raises KeyboardInterrupt; a rerun finishes them. Warnings are
    `HealthWarning`s; strict=True raises `StrictError` after writing."""
    if isinstance(sweep_file, dict):
        sweep_file = {k: _nested(v) if k == "set" and isinstance(v, dict) else v for k, v in sweep_file.items()}
    done = _core._sweep(sweep_file, os.fspath(out), _jobs(jobs), not no_batch, bool(force))
    summary = {k: done[k] for k in ("cases", "run", "batched", "resumed")}
    table = _table_from_csv(done["csv"], summary)
    summary.update(complete=int(np.sum(table["status"] == "complete")), directory=os.fspath(out))
    lines = _study_warnings(done["warnings"], "sweep.csv")
    if summary["complete"] == 0 and summary["cases"] > 0:
        _warn(["no case produced a result; see the status and message columns of sweep.csv"])
    _strict(strict, lines, table, "the sweep's cases")
    return table


def bearing(case, out, capacity, toe_share=None, jobs=None, plot=True, force=False, *, no_plot=False, strict=False,
            set=None):
    """The bearing graph (`barimpact bearing CASE --out OUT --capacity
    FROM:TO:COUNT`): `case` a case file with Smith's soil, `capacity`
    "FROM:TO:COUNT" or (from, to, count), in N, `toe_share` R_toe / capacity
    in [0, 1] (None: the case's), `set` overrides of the case for every
    capacity, as --set ({"time.end": 0.2}). Runs every capacity on `jobs` threads (None:
    every core; resumes a bearing directory), writes bearing.csv and, unless
    no_plot (or plot=False, the older spelling), bearing.png. Returns
    bearing.csv's table (blow counts inf where the hammer cannot move the
    pile) with `summary` {"toe_share", "from", "to", "count", "directory"}.
    Ctrl-C writes what is done and raises KeyboardInterrupt. Warnings are
    `HealthWarning`s; strict=True raises `StrictError` after writing."""
    if not isinstance(capacity, str):
        lo, hi, count = capacity
        capacity = f"{float(lo)!r}:{float(hi)!r}:{int(count)}"
    done = _core._bearing(case, os.fspath(out), capacity, toe_share, _jobs(jobs), bool(force), set)
    summary = {k: done[k] for k in ("toe_share", "from", "to", "count")}
    summary["directory"] = os.fspath(out)
    table = _table_from_csv(done["csv"], summary)
    if plot and not no_plot and np.any(table["status"] == "complete"):
        _bearing_figures.plot_bearing(out)
    lines = _study_warnings(done["warnings"], "bearing.csv")
    _strict(strict, lines, table, "the capacities' runs")
    return table


def drive(case, out, jobs=None, *, no_plot=False, force=False, strict=False, set=None):
    """Drivability (`barimpact drive CASE --out OUT`): `case` a case file
    with [drive] and [[layer]], `set` overrides of the case for every depth,
    as --set ({"hammer.stroke": 1.2}). Runs every depth on `jobs` threads
    (None: every core; resumes a drive directory), writes drive.csv and
    summary.json and, unless no_plot, drive.png. Returns drive.csv's table
    (blow counts inf where the hammer cannot advance the pile) with
    `summary` {"total_blows", "driving_time" (minutes), "refusal_depth"
    (None: no refusal), "max_compression", "max_tension", "directory"}.
    Ctrl-C writes what is done and raises KeyboardInterrupt. Warnings are
    `HealthWarning`s; strict=True raises `StrictError` after writing."""
    done = _core._drive(case, os.fspath(out), _jobs(jobs), bool(force), set)
    summary = {k: done[k] for k in ("total_blows", "driving_time", "refusal_depth", "max_compression",
                                    "max_tension")}
    summary["directory"] = os.fspath(out)
    table = _table_from_csv(done["csv"], summary)
    if not no_plot and np.any(table["status"] == "complete"):
        _drive_figures.plot_drive(out)
    lines = _study_warnings(done["warnings"], "drive.csv")
    _strict(strict, lines, table, "the depths' runs")
    return table


def inspector(case, out, stroke, depth=None, jobs=None, *, no_plot=False, force=False, strict=False, set=None):
    """The inspector's chart (`barimpact inspector CASE --out OUT --stroke
    FROM:TO:COUNT [--depth D]`): `stroke` "FROM:TO:COUNT" or (from, to,
    count) in m, `depth` the penetration of a [drive] case's profile (required
    for one, refused otherwise). Writes inspector.csv and, unless no_plot,
    inspector.png; returns inspector.csv's table."""
    if not isinstance(stroke, str):
        lo, hi, count = stroke
        stroke = f"{float(lo)!r}:{float(hi)!r}:{int(count)}"
    done = _core._inspector(case, os.fspath(out), stroke, depth, _jobs(jobs), bool(force), set)
    table = _table_from_csv(done["csv"], {"directory": os.fspath(out)})
    if not no_plot and np.any(table["status"] == "complete"):
        _drive_figures.plot_inspector(out)
    lines = _study_warnings(done["warnings"], "inspector.csv")
    _strict(strict, lines, table, "the strokes' runs")
    return table


def hammers():
    """The hammers barimpact ships (`barimpact hammers`; `[hammer] model =
    NAME` in a case): a table with name, kind, ram_mass (kg), stroke (m),
    energy (J, m g stroke), efficiency, cushion_stiffness (N/m),
    cushion_restitution, helmet_mass (kg) and source."""
    return _table_from_csv(_core._hammers_csv(), {})


def hopkinson(setup, out=None, *, no_plot=False, force=False, strict=False):
    """The split Hopkinson bar analysis (`barimpact hopkinson SETUP --out
    DIR`): `setup` a setup file's path, or the same as a dict of sections
    ({"bar": {...}, "incident": {...}, ...}; relative paths then from the
    working directory). Returns hopkinson.csv's table (t, strain_1w,
    strain_rate_1w, stress_1w, strain_3w, strain_rate_3w, stress_2w,
    stress_3w, force_front, force_back, equilibrium, incident, reflected,
    transmitted) with `summary`, summary.json as a dict. With `out`, writes
    hopkinson.csv, summary.json and (unless no_plot) the figures there, moved
    into place together by the command's output rule (`force` as --force);
    without it nothing is written. InputError (one line) for a signal it
    cannot analyse. Warnings are `HealthWarning`s; strict=True raises
    `StrictError` after writing."""
    draw = None if no_plot or out is None else (
        lambda staging: _hopkinson_figures.plot_hopkinson_into(staging, _out(out)))
    table, summary, lines = _core._hopkinson(setup, _out(out), bool(force), draw)
    result = HopkinsonTable(table, json.loads(summary))
    _warn(lines)
    _strict(strict, lines, result, "the analysis")
    return result


def pda(record, out=None, *, no_plot=False, force=False):
    """The analysis of a measured blow on a pile (`barimpact pda RECORD --out
    DIR`): `record` a record file's path, or the same as a dict of sections
    ({"pile": {...}, "record": {...}, "case_method": {...}}; relative paths
    then from the working directory). Returns pda.csv's table (t, force,
    velocity_z, wave_down, wave_up, displacement, velocity, energy) with
    `summary`, summary.json as a dict (t1, t2, fmx, vmx, emx, dmx, csx, tsx,
    rmx, rmx_time, rsp, bta, bta_depth, ...). With `out`, writes pda.csv,
    summary.json and (unless no_plot) the figures there, moved into place
    together by the command's output rule (`force` as --force); without it
    nothing is written. InputError (one line) for a record it cannot analyse."""
    draw = None if no_plot or out is None else (
        lambda staging: _pda_figures.plot_pda_into(staging, _out(out)))
    csv, summary = _core._pda(record, _out(out), bool(force), draw)
    return _table_from_csv(csv, json.loads(summary), PdaTable)


def match(record, out=None, *, no_plot=False, force=False, jobs=0, strict=False):
    """Signal matching of a measured blow on a pile (`barimpact match RECORD
    --out DIR`): the soil resistance along the pile whose computed force at
    the gauges, under the measured velocity, matches the measured force.
    `record` a record file's path, or the same as a dict of sections
    ({"pile": {...}, "record": {...}, "match": {...}}; relative paths then
    from the working directory); `jobs` threads for the fit (0 or None:
    every core). Returns a `MatchTable`: match.csv's columns (t,
    force_measured, force_computed, velocity_z, wave_up_measured,
    wave_up_computed), `summary` (summary.json: capacity, shaft, toe,
    match_quality, s_c, t1, t2, start_results, ...), `soil` (soil.csv:
    segment, top, bottom, resistance, quake, damping; the last row the toe)
    and `static` (static.csv: settlement, load). With `out`, writes the
    four files and (unless no_plot) the figures force_match, resistance and
    static_test there, moved into place together by the command's output
    rule (`force` as --force), `out` refused before the fit; without it
    nothing is written. The GIL is released during the fit; Ctrl-C during
    it raises KeyboardInterrupt with nothing written. InputError (one line)
    for a record it cannot match. summary.json's warnings (match-unfiltered,
    match-not-converged) are `HealthWarning`s; strict=True raises
    `StrictError` after writing."""
    draw = None if no_plot or out is None else (
        lambda staging: _match_figures.plot_match_into(staging, _out(out)))
    match_csv, soil_csv, static_csv, summary = _core._match(record, _out(out), bool(force), _jobs(jobs), draw)
    table = _match_table(match_csv, soil_csv, static_csv, json.loads(summary))
    lines = table.summary.get("warnings", [])
    _warn(lines)
    _strict(strict, lines, table, "the match")
    return table


def plot(dir, out=None, *, force=False, formats=("png", "svg")):
    """The figures of a run, PNG and SVG (`barimpact plot DIR [--out
    FIGURES]`). `dir` a run directory (written by `barimpact run` or
    `Result.write`): the figures go to DIR/figures (listed as the run's), or
    `out`; a sweep's likewise; a hopkinson, pda, match, bearing, drive,
    inspector or converge directory: its figures where the command draws
    them (`out` refused). Or `dir` a `Result` (or `RunData`): the figures go to `out`
    (default ./figures). Either way by the command's output rule: a new or
    empty directory, or one barimpact wrote; someone else's only with force
    (beside their files, as --force); never $HOME, / or a parent of the
    working directory, nor the directory plotted (InputError). Returns the
    paths written."""
    if not isinstance(dir, (str, os.PathLike)):
        return _figures.plot(dir, out, formats, force=force)
    run_dir = _Path(os.fspath(dir))
    if _figures.is_run_directory(run_dir):
        return _figures.plot(run_dir, out, formats, force=force)
    if (run_dir / "sweep.csv").is_file():  # each sweep.csv output against the swept keys, as `barimpact plot SWEEP_DIR`
        return _convergence_figures.plot_sweep(run_dir, out, formats, force=force)
    try:  # a study's or analysis's directory: its figures where the command draws them
        written = _figures.redraw(run_dir, out)
    except ValueError as e:
        raise InputError(f"plot: {e}") from None
    if written is None:
        raise InputError(f"plot: {os.fspath(dir)} holds no history.csv, results.h5, sweep.csv or a study's table "
                         f"({', '.join(_figures.REDRAWN)}): give a directory written by barimpact")
    return written


def exact_example1(x, t, length=1.0, stiffness=1.0, density=1.0, v0=-1.0):
    """The paper's Example 1 with a rigid obstacle (exact): a bar at rest,
    undeformed, moving at v0 < 0 towards x = 0. Returns a dict of arrays u, v,
    strain, R, broadcast over x and t."""
    xb, tb = np.broadcast_arrays(np.asarray(x, dtype=float), np.asarray(t, dtype=float))
    u, v, strain, R = _core._exact_example1(xb.ravel(), tb.ravel(), length, stiffness, density, v0)
    shape = xb.shape
    return {"u": u.reshape(shape), "v": v.reshape(shape), "strain": strain.reshape(shape), "R": R.reshape(shape)}
