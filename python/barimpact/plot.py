"""Figures of a run (matplotlib, PNG and SVG), from a `Result` or from a
directory written by `barimpact run` (CSV files, or results.h5 read with h5py):

- displacement: U(t), with the case's exact solution when it admits one
  (`barimpact.exact`), and the rigid-obstacle limit for the paper's Example 1
  family with a penalty obstacle (its Figure 3);
- reaction: R(t), likewise;
- energy: the budget E_kin, E_strain, E_obstacle, W_ext, D_visc and the
  balance E_kin + E_strain + E_obstacle - W_ext + D_visc (exact energies
  dashed where known);
- stress_map: sigma(x, t) over the field snapshots, where the waves and their
  reflections show;
- snapshots: u(x) at up to eight snapshot times (the paper's Figure 2);
- impacts: U and R with every contact episode shaded (Example 2's second
  impact, the paper's Figure 4);
- a line's joint_forces, gauges and masses, a yielding bar's plastic_map and
  plastic_snapshots, a pile blow's blow_head, blow_toe and blow_envelopes.

Large runs stay fast and small: curves are thinned to what an axis can show
(the smallest and largest point of each pixel column, so peaks stay), the
space-time maps are reduced to about one cell per pixel (each keeping its
largest magnitude) and rasterized in the SVG.

Axis labels follow the case's `[units] system`: "SI" adds units (N, m, m/s,
s, Pa, J, with a prefix that keeps the numbers readable), "none" (the
default) leaves the bare names.

`compare(sources, out)` draws several runs in one figure, each curve named
by the case keys that differ between the runs.
"""
import contextlib
import json
import os
import tomllib
import warnings
from itertools import islice
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from . import _core  # noqa: E402
from .style import Scale, Units, column_words, drawn_sign, is_pile, key_words, spoken, words_of  # noqa: E402,F401

COLUMNS = ("t", "U", "V", "R", "E_kin", "E_strain", "E_obstacle", "W_ext", "D_visc", "D_contact", "D_plastic")
FIGSIZE = (8.0, 4.5)  # inches; at DPI 120 a PNG of 960 x 540 pixels
DPI = 120
SCREEN_COLUMNS = 1000  # pixel columns of an axis, a little more than its width at FIGSIZE and DPI
MAP_ROWS = 600  # snapshot rows a space-time map keeps at most (the axis is about 450 pixels high)
EXACT_ROWS = 20000  # history rows of the exact solution at most: far more than a screen shows


# --- units (the shared style: barimpact.style) ------------------------------------

# The quantity of a case key, by its last part ([bar]'s stiffness is E A, a
# force, and its density a mass per unit length).
KEY_QUANTITIES = {"length": "length", "gap": "length", "at": "length", "velocity": "velocity", "end": "time",
                  "step": "time", "modulus": "stress", "yield_stress": "stress", "hardening_modulus": "stress",
                  "area": "area", "mass": "mass", "density": "density", "gravity": "acceleration",
                  "stiffness": "stiffness"}


def key_quantity(key):
    """The physical quantity of a dotted case key ("obstacle.stiffness"), or None."""
    parts = key.split(".")
    if parts[0] == "bar" and parts[-1] in ("stiffness", "density"):
        return "force" if parts[-1] == "stiffness" else "line_density"
    return KEY_QUANTITIES.get(parts[-1])


def units_of(case):
    """The Units of a case (a dict of its TOML): its `[units] system`, "none" when absent; a pile's words."""
    return Units((case or {}).get("units", {}).get("system", "none"), pile=is_pile(case))


def units_of_runs(directory, default="none"):
    """The Units of a study, from the case.toml of its first run (all share it); `default`'s without one."""
    for case in sorted(Path(directory).glob("runs/*/case.toml")):
        try:
            return units_of(tomllib.loads(case.read_text()))
        except (OSError, tomllib.TOMLDecodeError):
            continue
    return Units(default)


# --- reading -----------------------------------------------------------------

def read_numbers(path, usecols=None):
    """A CSV file of numbers under a one-line header, as a 2-D array.
    numpy's loadtxt (C parser since numpy 1.23) reads about 80 MB/s here,
    faster than np.fromstring or genfromtxt on the same file."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # a header without rows: an empty table, not a warning
        return np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2, usecols=usecols, dtype=float)


class RunData:
    """What the figures need: history columns, field snapshots, case, summary.
    `case_source` is what builds a `barimpact.Case` for the exact solution
    (a case.toml path or a Case), None when unknown."""

    def __init__(self, history, x, field_t, u, sigma, case, summary, body=None, eps_p=None, case_source=None):
        self.history = history  # dict column -> 1-D array
        self.x, self.field_t, self.u, self.sigma = x, field_t, u, sigma
        self.case, self.summary = case, summary
        self.body = body  # the body of each field row (None: one bar)
        self.eps_p = eps_p  # plastic strain at each snapshot and row (None: not written)
        self.case_source = case_source
        self.units = units_of(case)

    # The history by column name, as a run's Result: r["U"], r.U, r.columns.
    @property
    def columns(self):
        """The history's column names, in history.csv's order."""
        return tuple(self.history)

    def __getitem__(self, column):
        try:
            return self.history[column]
        except KeyError:
            raise KeyError(f'no history column "{column}"') from None

    def __contains__(self, column):
        return column in self.history

    def __getattr__(self, name):  # only for names that are not attributes
        history = self.__dict__.get("history")
        if history is not None and name in history:
            return history[name]
        raise AttributeError(f"'RunData' object has no attribute or history column '{name}'")

    def to_pandas(self):
        """The history as a pandas DataFrame (pandas must be installed)."""
        import pandas as pd
        return pd.DataFrame(self.history)


def _read_fields(path):
    """fields.csv as (x, field_t, {column: (snapshots, nodes) array}, body):
    rows are snapshot after snapshot, each over the same nodes."""
    with open(path) as stream:
        header = stream.readline().strip().split(",")
    numbers = [i for i, name in enumerate(header) if name != "body"]
    f = read_numbers(path, usecols=numbers)
    if not f.size:
        return np.empty(0), np.empty(0), {}, None
    col = {header[i]: k for k, i in enumerate(numbers)}
    t = f[:, col["t"]]
    changes = np.flatnonzero(t[1:] != t[:-1])
    nodes = int(changes[0]) + 1 if changes.size else t.size
    count = t.size // nodes
    fields = {name: f[:count * nodes, k].reshape(count, nodes) for name, k in col.items() if name not in ("t", "x")}
    body = None
    if "body" in header:  # the same bodies in every snapshot: read them from the first one only
        at = header.index("body")
        with open(path) as stream:
            stream.readline()
            body = np.array([line.rstrip("\n").split(",")[at] for line in islice(stream, nodes)])
    return f[:nodes, col["x"]], t[::nodes][:count], fields, body


def is_run_directory(run_dir):
    """True when `run_dir` holds a run's history: history.csv, or results.h5
    (a case with `[output] format = "hdf5"`)."""
    d = Path(run_dir)
    return (d / "history.csv").is_file() or (d / "results.h5").is_file()


def _h5py(path):
    try:
        import h5py
    except ImportError:
        raise ImportError(f"{path}: reading it needs h5py, which is not installed here (Debian: apt-get install "
                          "python3-h5py; elsewhere: pip install h5py)") from None
    return h5py


def _read_results_h5(path, with_fields):
    """results.h5 as (history, (x, field_t, {column: (snapshots, nodes) array}, body)): what
    history.csv and fields.csv give, the same doubles (the file's layout: barimpact/run/results_h5.hpp).
    barimpact.InputError naming the file when it is not one barimpact wrote (damaged, truncated, another file)."""
    h5py = _h5py(path)
    try:
        return _results_h5_contents(h5py, path, with_fields)
    except (OSError, KeyError, ValueError, TypeError, IndexError) as e:
        raise _core.InputError(f"{os.fspath(path)}: cannot be read as a run's results.h5 ({e})") from None


def _results_h5_contents(h5py, path, with_fields):
    with h5py.File(path, "r") as f:
        g = f["history"]
        history = {str(name): g[str(name)][()] for name in g.attrs["columns"]}
        if not with_fields or "fields" not in f or not f["fields/t"].size:
            return history, (np.empty(0), np.empty(0), {}, None)
        g = f["fields"]
        fields = {str(n): g[str(n)][()] for n in g.attrs["columns"] if str(n) not in ("t", "x", "body")}
        body = np.array([str(n) for n in g["body"].attrs["names"]])[g["body"][()]]
        return history, (g["x"][()], g["t"][()], fields, body)


def load(run_dir, with_fields=True):
    """Read a directory written by `barimpact run` (or `barimpact exact`):
    history.csv and fields.csv, or results.h5 when its case says `[output]
    format = "hdf5"` (read with h5py), the same RunData either way.
    with_fields=False leaves the fields unread (what a comparison of runs needs)."""
    d = Path(run_dir)
    if not is_run_directory(d):
        raise ValueError(f"{run_dir}: no history.csv or results.h5 (not a directory written by barimpact run)")
    case_file = Path(_core._run_case_file(d))  # case.toml, or case.resolved.toml beside the user's case.toml
    case = tomllib.loads(case_file.read_text())
    if case.get("output", {}).get("format") == "hdf5":  # the file the case says (a user's may lie beside it)
        history, (x, field_t, fields, body) = _read_results_h5(d / "results.h5", with_fields)
    else:
        with open(d / "history.csv") as stream:
            names = stream.readline().strip().split(",")
        h = read_numbers(d / "history.csv")
        if h.shape[1] != len(names):
            h = np.empty((0, len(names)))
        history = {name: h[:, i] for i, name in enumerate(names)}
        x, field_t, fields, body = np.empty(0), np.empty(0), {}, None
        if with_fields and (d / "fields.csv").is_file():
            x, field_t, fields, body = _read_fields(d / "fields.csv")
    u = sigma = np.empty(0)
    eps_p = None
    if fields:
        u, sigma, eps_p = fields["u"], fields["sigma"], fields.get("eps_p")
    summary = json.loads((d / "summary.json").read_text())
    return RunData(history, x, field_t, u, sigma, case, summary, body, eps_p, case_source=case_file)


def _from_result(result):
    history = {name: np.asarray(result[name]) for name in result.history_columns}
    return RunData(history, np.asarray(result.x), np.asarray(result.field_t), np.asarray(result.u),
                   np.asarray(result.sigma), tomllib.loads(result.case.to_toml()), result.summary,
                   np.asarray(result.field_body), np.asarray(result.eps_p), case_source=result.case)


# --- what a screen can show --------------------------------------------------

def screen_points(x, y, columns=SCREEN_COLUMNS):
    """(x, y) thinned to what an axis `columns` pixels wide can show: in each
    run of consecutive points, the smallest and the largest (in their order),
    so every peak and the envelope stay. Short series come back whole."""
    x, y = np.asarray(x), np.asarray(y)
    n = y.size
    if n <= 4 * columns:
        return x, y
    k = -(-n // columns)  # points per column
    m = n // k * k
    runs = y[:m].reshape(-1, k)
    finite = np.isfinite(runs)
    lowest = np.where(finite, runs, np.inf).argmin(axis=1)  # an all-NaN run keeps its first point: a gap
    highest = np.where(finite, runs, -np.inf).argmax(axis=1)
    starts = np.arange(0, m, k)
    keep = np.unique(np.concatenate([starts + lowest, starts + highest, [0, n - 1], np.arange(m, n)]))
    return x[keep], y[keep]


def _bin_starts(n, bins):
    k = max(1, -(-n // max(1, bins)))
    starts = np.arange(0, n, k)
    return starts, np.diff(np.append(starts, n)), k


def peak_cells(values, coords, bins, axis):
    """`values` (2-D) reduced along `axis` to about `bins` cells of
    consecutive entries, each keeping the entry of largest magnitude (a wave
    front or a one-node peak stays visible), with the cells' mean coordinate."""
    n = values.shape[axis]
    starts, counts, k = _bin_starts(n, bins)
    if k == 1:
        return coords, values
    v = np.moveaxis(values, axis, -1)
    pad = starts.size * k - n
    v = np.concatenate([v, np.zeros(v.shape[:-1] + (pad,))], axis=-1).reshape(v.shape[:-1] + (starts.size, k))
    pick = np.abs(np.nan_to_num(v, nan=0.0)).argmax(axis=-1)
    reduced = np.take_along_axis(v, pick[..., None], axis=-1)[..., 0]
    return np.add.reduceat(np.asarray(coords, dtype=float), starts) / counts, np.moveaxis(reduced, -1, axis)


def _line(ax, x, y, *args, **kwargs):
    """ax.plot of a series thinned to the screen."""
    return ax.plot(*screen_points(x, y), *args, **kwargs)


# --- exact solutions -----------------------------------------------------------

def _number(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return None


def exact_parameters(case):
    """(L, a, rho, v0) when the case is the paper's Example 1 family (one
    elastic bar (no yield), uniform v0 < 0, no load, no initial strain, an obstacle at
    x = 0 without gap), else None."""
    bodies, near = case.get("body", []), case.get("near_end", {})
    if len(bodies) != 1 or bodies[0].get("kind") != "bar" or case.get("joint"):
        return None
    bar = bodies[0]
    v0 = _number(bar["velocity"])
    if (near.get("law", "free") not in ("elastic", "viscoelastic", "rigid", "cushion") or near.get("gap", 0) != 0
            or bar.get("material", "elastic") != "elastic"
            or bar["viscosity"] != 0 or _number(case["load"]["body_force"]) != 0
            or case["load"].get("gravity", 0) != 0 or _number(bar["displacement"]) != 0 or v0 is None or v0 >= 0):
        return None
    return bar["length"], bar["modulus"] * bar["area"], bar["density"] * bar["area"], v0


def _exact_case(source, case):
    """The barimpact.Case whose exact solution the figures draw: the run's
    case, its history thinned to EXACT_ROWS rows when longer (each row costs
    an evaluation, and no screen shows more)."""
    from . import Case
    if isinstance(source, (str, Path)):
        source = Case(os.fspath(source))
    every = -(-getattr(source, "steps", 0) // EXACT_ROWS)
    if every > case.get("output", {}).get("every", 1):
        source = Case(source.to_toml(), set={"output.every": every})
    return source


def exact_solution(data):
    """The exact solution of the run's case (`barimpact.exact`) as a RunData
    with the run's columns, or None when the case admits none."""
    if data.case_source is None:
        return None
    try:
        from . import exact
        return _from_result(exact(_exact_case(data.case_source, data.case)))
    except (ImportError, ValueError, OSError, RuntimeError):
        return None  # InputError (a ValueError): the case admits no exact solution


class Reference:
    """A reference curve set: history columns drawn with one label and style."""

    def __init__(self, history, label, **style):
        self.history, self.label, self.style = history, label, style


def references(data):
    """The references a run's figures draw: its case's exact solution
    (dashed), and for the paper's Example 1 with a penalty obstacle the
    rigid-obstacle limit (dotted), as in the paper's Figure 3."""
    refs = []
    exact = exact_solution(data)
    if exact is not None:
        refs.append(Reference(exact.history, "exact", color="k", ls="--", lw=1.1))
    params = exact_parameters(data.case)
    law = data.case.get("near_end", {}).get("law", "free")
    if params is not None and (law != "rigid" or exact is None) and data.history["t"].size:
        from . import exact_example1
        t = data.history["t"]
        fine_t = np.linspace(t[0], t[-1], 2001)
        ref = exact_example1(0.0, fine_t, *params)
        label = "exact, rigid obstacle" if law == "rigid" else "rigid-obstacle limit"
        refs.append(Reference({"t": fine_t, "U": ref["u"], "R": ref["R"]}, label, color="0.45", ls=":", lw=1.4))
    return refs, exact


def _exact_entry(ax):
    """One legend entry for exact curves drawn dashed in their computed curve's colour."""
    ax.plot([], [], ls="--", lw=1.0, color="0.3", label="exact (dashed, same colour)")


def _draw_references(ax, refs, column, ts, ys):
    for ref in refs:
        y = ref.history.get(column)
        if y is not None and np.any(np.isfinite(y)):
            _line(ax, ts(ref.history["t"]), ys(y), label=ref.label, **ref.style)


# --- legends that name what differs ---------------------------------------------

def flat_case(case):
    """A case's TOML (a dict) as {dotted key: value}, the keys --set uses:
    body.<name>.<key> for the [[body]], [[joint]] and [[gauge]] entries."""
    flat = {}
    for section, keys in case.items():
        if isinstance(keys, list) and keys and all(isinstance(k, dict) for k in keys):
            for i, entry in enumerate(keys):
                name = entry.get("name", str(i + 1))
                flat.update({f"{section}.{name}.{k}": v for k, v in entry.items() if k != "name"})
        elif isinstance(keys, dict):
            flat.update({f"{section}.{k}": v for k, v in keys.items()})
        else:
            flat[section] = keys
    return flat


def differing_keys(settings):
    """The keys whose values are not the same in every dict of `settings`, in first-seen order."""
    keys = list(dict.fromkeys(k for s in settings for k in s))
    return [k for k in keys if len({repr(s.get(k)) for s in settings}) > 1]


def _shown(value, key, units):
    if isinstance(value, float):
        value = float(f"{value:.6g}")
    return units.value(value, key_quantity(key)) if units else str(value)


def legend_labels(settings, units=None):
    """One label per dict of `settings` naming only the keys that differ
    between them, in words ("near-end stiffness = 100, bar velocity = -1"), none
    of those they all share."""
    keys = differing_keys(settings)
    if not keys:
        return [f"run {i + 1}" for i in range(len(settings))]
    return [", ".join(f"{key_words(k)} = {_shown(s.get(k), k, units)}" for k in keys) for s in settings]


# --- the figures of a run -------------------------------------------------------------

def _figure(title, grid=True):
    fig, ax = plt.subplots(figsize=FIGSIZE, dpi=DPI, layout="constrained")
    ax.set_title(title)
    if grid:
        ax.grid(True, alpha=0.3)
    return fig, ax


def _replace_whole(path, write):
    """Calls write(staged) for a hidden file beside `path` (.NAME.partial-PID,
    which barimpact's output rule knows as its own), then renames it over
    `path`: no reader sees half of it. What the file system refuses (a full
    disk) is an OSError naming `path`; no part of it is left."""
    path = Path(path)
    staged = path.with_name(f".{path.name}.partial-{os.getpid()}")
    try:
        write(staged)
        os.replace(staged, path)
    except BaseException as e:
        with contextlib.suppress(OSError):
            staged.unlink(missing_ok=True)
        if isinstance(e, OSError) and e.errno is not None:
            raise OSError(e.errno, e.strerror, str(path)) from e
        raise


# Called as hook(fig, name) before each figure is saved: what reads the
# figures' text (titles, labels, legends) without comparing images.
SAVE_HOOKS: list = []


def _save(fig, out, name, formats, written):
    """The figure in each format, each file whole or not at all; closed either way."""
    try:
        for hook in SAVE_HOOKS:
            hook(fig, name)
        for fmt in formats:
            path = Path(out) / f"{name}.{fmt}"
            _replace_whole(path, lambda staged, fmt=fmt: fig.savefig(staged, dpi=DPI, format=fmt))
            written.append(path)
    finally:
        plt.close(fig)


def _near_end(case, units):
    """The near end in words, for titles: "elastic obstacle k = 100 N/m", "Smith soil at the toe"."""
    near = case.get("near_end", {})
    law = near.get("law", "free")
    if law in ("elastic", "viscoelastic", "cushion") and "stiffness" in near:
        return f"{law} obstacle k = {units.value(near['stiffness'], 'stiffness')}"
    return {"free": "", "rigid": "rigid obstacle", "smith": "Smith soil at the toe"}.get(law, f"{law} near end")


def _titled(title, data):
    near = _near_end(data.case, data.units)
    return f"{title}, {near}" if near else title


def _run_label(data):
    return spoken(data.case.get("time", {}).get("scheme", "computed"))


def _column(data, column, values=None, sign=True):
    """(words, Scale) of a history column's axis: its words, sign and unit."""
    words, quantity = column_words(column, data.case) or (words_of(column), None)
    return words, data.units.axis(words, quantity, values, sign=sign)


def _capital(text):
    return text[:1].upper() + text[1:]


def _history_figure(data, refs, column, name, out, formats, written):
    """A history column against time with its references (U: the displacement figure, R: the reaction's)."""
    h, units = data.history, data.units
    ts = units.time(h["t"])
    words, ys = _column(data, column, h[column])
    fig, ax = _figure(_titled(_capital(words), data))
    t, y = screen_points(h["t"], h[column])
    style = dict(ls="none", marker=".", ms=3) if t.size <= 400 else dict(lw=1.6)  # dots only while they stay apart
    ax.plot(ts(t), ys(y), label=_run_label(data), **style)
    _draw_references(ax, refs, column, ts, ys)
    near = data.case.get("near_end", {})
    if column == "U" and near.get("law", "free") in ("elastic", "viscoelastic", "rigid", "cushion"):
        ax.axhline(ys(-near.get("gap", 0.0)), color="gray", lw=0.8, ls="--", label="obstacle face")
    ax.set_xlabel(ts.label)
    ax.set_ylabel(ys.label)
    ax.legend()
    _save(fig, out, name, formats, written)


ENERGIES = ("E_kin", "E_strain", "E_obstacle", "W_ext", "D_visc", "D_contact", "D_plastic")


def _energy_figure(data, exact, out, formats, written):
    h, units = data.history, data.units
    balance = (h["E_kin"] + h["E_strain"] + h["E_obstacle"] - h["W_ext"] + h["D_visc"] + h.get("D_contact", 0.0) +
               h.get("D_plastic", 0.0))
    ts = units.time(h["t"])
    es = units.axis("energy", "energy", np.concatenate([h[n] for n in ENERGIES if n in h]))
    fig, ax = _figure("Energy budget")
    exact_drawn = False
    for name in ENERGIES:
        if name in h and (name not in ("D_contact", "D_plastic") or np.any(h[name] != 0)):
            line, = _line(ax, ts(h["t"]), es(h[name]), lw=1.0, label=words_of(name, data.case))
            y = exact.history.get(name) if exact is not None else None
            if y is not None and np.any(np.isfinite(y)) and np.any(y != 0):  # same colour, dashed
                _line(ax, ts(exact.history["t"]), es(y), ls="--", lw=1.0, color=line.get_color())
                exact_drawn = True
    _line(ax, ts(h["t"]), es(balance), "k-", lw=1.8, label="balance: kinetic + strain + obstacle - work + dissipation")
    if exact_drawn:
        _exact_entry(ax)
    ax.set_xlabel(ts.label)
    ax.set_ylabel(es.label)
    ax.legend(fontsize=8, loc="best")
    _save(fig, out, "energy", formats, written)


def _body_rows(data):
    """Index arrays of each bar body's rows in the field snapshots."""
    if data.body is None or len(data.body) == 0:
        return [np.arange(data.x.size)]
    names = list(dict.fromkeys(data.body))
    return [np.flatnonzero(data.body == name) for name in names]


def _position_axis(data):
    """The axis of x along the line: a pile's height above its toe."""
    words = "height above the toe x" if data.units.pile else "position x"
    return data.units.axis(words, "length", data.x, sign=False)


def between_snapshots(cells, snapshot_t, grid_t):
    """`cells` (snapshots, columns) interpolated linearly in time onto
    `grid_t`, masked outside the snapshots' span: a map shows only where
    there is data, never a snapshot stretched past the last one."""
    j = np.clip(np.searchsorted(snapshot_t, grid_t, side="right") - 1, 0, max(snapshot_t.size - 2, 0))
    gap = np.diff(snapshot_t)[j] if snapshot_t.size > 1 else np.ones_like(grid_t)
    w = np.clip((grid_t - snapshot_t[j]) / np.where(gap > 0, gap, 1.0), 0.0, 1.0)[:, None]
    values = cells[j] * (1.0 - w) + cells[np.minimum(j + 1, snapshot_t.size - 1)] * w
    outside = (grid_t < snapshot_t[0]) | (grid_t > snapshot_t[-1])
    mask = np.zeros(values.shape, dtype=bool)
    mask[outside] = True
    return np.ma.masked_array(values, mask)


def _map_grid(data, snapshot_t):
    """The time rows of a map: MAP_ROWS over the snapshots' span (where there
    is data; the run's, the history's, when they span no time)."""
    lo, hi = float(snapshot_t[0]), float(snapshot_t[-1])
    t = data.history.get("t", np.empty(0))
    if not hi > lo and t.size:
        lo, hi = min(lo, float(t[0])), max(hi, float(t[-1]))
    edges = np.linspace(lo, hi, MAP_ROWS + 1)
    return edges, 0.5 * (edges[1:] + edges[:-1])


def _run_beyond(data, edges, ts):
    """The title's note of a run that goes on past the map's last row."""
    t = data.history.get("t", np.empty(0))
    if t.size and float(t[-1]) > edges[-1] + 0.01 * (edges[-1] - edges[0]):
        return f"; the run goes on to {ts.text(t[-1], 3)}"
    return ""


def _mark_snapshots(ax, snapshot_t):
    """A tick at each snapshot time on the map's right edge."""
    ax.plot(np.ones(snapshot_t.size), snapshot_t, ls="none", marker="_", ms=7, mew=0.7, color="k", clip_on=False,
            transform=ax.get_yaxis_transform(), label=f"the {snapshot_t.size} snapshot times")


def _map_figure(data, symbol, name, what, quantity, cmap, out, formats, written):
    """A field (`symbol`: sigma or eps_p) over x and t from its snapshots,
    one map per bar body (the gaps between them stay blank), interpolated in
    time between snapshots only, reduced to about a cell per pixel and
    rasterized; drawn with drawn_sign (compression positive)."""
    units, field = data.units, drawn_sign(symbol) * getattr(data, symbol)
    finite = np.abs(field[np.isfinite(field)])
    limit = float(finite.max()) if finite.size and finite.max() > 0 else 1.0
    xs = _position_axis(data)
    edges, grid = _map_grid(data, data.field_t)
    ts, vs = units.time(edges), units.axis(what, quantity, limit)
    line = "pile" if units.pile else "line"
    fig, ax = _figure(f"{_capital(what)} along the {line} from {data.field_t.size} snapshots\n"
                      f"(linear in time between them{_run_beyond(data, edges, ts)})", grid=False)
    span = float(np.ptp(data.x)) or 1.0
    for rows in _body_rows(data):
        bins = max(2, round(SCREEN_COLUMNS * float(np.ptp(data.x[rows])) / span))
        x, cells = peak_cells(field[:, rows], data.x[rows], bins, axis=1)
        t, cells = peak_cells(cells, data.field_t, MAP_ROWS, axis=0)
        mesh = ax.pcolormesh(xs(_cell_edges(x)), ts(edges), vs(between_snapshots(cells, t, grid)), cmap=cmap,
                             vmin=-vs(limit), vmax=vs(limit), shading="flat", rasterized=True)
    _mark_snapshots(ax, ts(data.field_t))
    ax.set_facecolor("0.88")  # no snapshot there: grey, not the colour of zero
    ax.set_ylim(ts(edges[0]), ts(edges[-1]))
    fig.colorbar(mesh, ax=ax, label=vs.label)
    ax.set_xlabel(xs.label)
    ax.set_ylabel(ts.label)
    _save(fig, out, name, formats, written)


def _cell_edges(x):
    """Edges of cells centred on the sorted coordinates `x`."""
    x = np.asarray(x, dtype=float)
    if x.size == 1:
        return np.array([x[0] - 0.5, x[0] + 0.5])
    mid = 0.5 * (x[1:] + x[:-1])
    return np.concatenate(([x[0] - (mid[0] - x[0])], mid, [x[-1] + (x[-1] - mid[-1])]))


def run_step(data):
    """The time step the run took: summary.json's (case.toml's time.step may
    be "auto"), else the spacing of its history's rows over output.every."""
    step = data.summary.get("step") if data.summary else None
    if isinstance(step, (int, float)) and not isinstance(step, bool) and step > 0:
        return float(step)
    spacing = np.diff(np.asarray(data.history.get("t", ())))
    spacing = spacing[spacing > 0]
    every = data.case.get("output", {}).get("every", 1)
    return float(np.median(spacing)) / every if spacing.size else 0.0


def _run_settings(data):
    """The run's case as {dotted key: value} (flat_case), time.step the step it took."""
    settings = flat_case(data.case)
    settings["time.step"] = run_step(data)
    return settings


def _exact_snapshot(data, exact, field):
    """{run snapshot: exact snapshot} of the same times, where the exact
    `field` is known (an exact solution may hold fewer snapshots)."""
    values = getattr(exact, field, None) if exact is not None else None
    if values is None or not values.size or not exact.field_t.size:
        return {}
    distance = np.abs(np.subtract.outer(data.field_t, exact.field_t))  # a few hundred snapshots at most
    j = distance.argmin(axis=1)
    close = distance[np.arange(j.size), j] <= 0.5 * run_step(data) + 1e-12 * np.abs(data.field_t)
    return {i: int(j[i]) for i in np.flatnonzero(close) if np.any(np.isfinite(values[j[i]]))}


def _snapshots(data, symbol, what, quantity, out, name, formats, written, exact=None):
    """A field (`symbol`: u or eps_p) over x at up to eight snapshot times,
    one colour per time across the bodies, drawn with drawn_sign; `exact`
    (a RunData) adds the exact field dashed."""
    units, sign = data.units, drawn_sign(symbol)
    field = sign * getattr(data, symbol)
    xs, fs = _position_axis(data), units.axis(what, quantity, field)
    ts = units.time(data.field_t)
    matched = _exact_snapshot(data, exact, symbol)
    line = "pile" if units.pile else "line"
    fig, ax = _figure(f"{_capital(what)} along the {line} at snapshot times")
    chosen = np.unique(np.linspace(0, data.field_t.size - 1, min(8, data.field_t.size)).round().astype(int))
    for i in chosen:
        when = f"t = {ts.text(data.field_t[i], 3)}"
        color = None  # the first body's line picks it, the others follow
        for n, rows in enumerate(_body_rows(data)):
            drawn, = _line(ax, xs(data.x[rows]), fs(field[i, rows]), lw=1.2, label=when if n == 0 else None,
                           color=color)
            color = drawn.get_color()
        if i in matched:
            values = sign * getattr(exact, symbol)[matched[i]]
            for rows in _body_rows(exact):
                _line(ax, xs(exact.x[rows]), fs(values[rows]), ls="--", lw=0.9, color=color)
    if any(i in matched for i in chosen):
        _exact_entry(ax)
    ax.set_xlabel(xs.label)
    ax.set_ylabel(fs.label)
    ax.legend(fontsize=8, ncol=2)
    _save(fig, out, name, formats, written)


def _contact_spans(summary, t):
    """The contact episodes as (start, end) spans, those closer than a pixel
    merged (a chattering contact has thousands)."""
    spans = sorted((c["start"], c["end"]) for c in summary.get("contacts", []))
    pixel = (float(t[-1] - t[0]) if t.size else 1.0) / SCREEN_COLUMNS
    merged = []
    for start, end in spans:
        if merged and start - merged[-1][1] <= pixel:
            merged[-1][1] = max(merged[-1][1], end)
        else:
            merged.append([start, end])
    return merged


def _impacts_figure(data, refs, out, formats, written):
    h, units = data.history, data.units
    ts = units.time(h["t"])
    (_, us), (_, rs) = _column(data, "U", h["U"]), _column(data, "R", h["R"])
    contacts = data.summary.get("contacts", [])
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=FIGSIZE, dpi=DPI, layout="constrained")
    fig.suptitle(f"Impacts: {len(contacts)} contact episode{'s' if len(contacts) != 1 else ''}")
    _line(top, ts(h["t"]), us(h["U"]), lw=1.0, label=_run_label(data))
    _line(bottom, ts(h["t"]), rs(h["R"]), lw=1.0, color="tab:red", label=_run_label(data))
    exact = [r for r in refs if r.label == "exact"]
    _draw_references(top, exact, "U", ts, us)
    _draw_references(bottom, exact, "R", ts, rs)
    top.set_ylabel(us.label, fontsize=9)
    bottom.set_ylabel(rs.label, fontsize=9)
    bottom.set_xlabel(ts.label)
    for ax in (top, bottom):
        for i, (start, end) in enumerate(_contact_spans(data.summary, h["t"])):
            ax.axvspan(ts(start), ts(end), color="tab:orange", alpha=0.15, lw=0, label="contact" if i == 0 else None)
        ax.grid(True, alpha=0.3)
    if contacts or exact:
        top.legend(loc="best", fontsize=8)
    _save(fig, out, "impacts", formats, written)


def _line_groups(h):
    """(figure, title, axis words, quantity, columns) of what a line adds to the history."""
    return (("joint_forces", "Joint forces" + (" and the far end's" if "far_end.force" in h else ""), "force",
             "force", [c for c in h if c.startswith("joint.") and c.endswith(".force") or c == "far_end.force"]),
            ("gauges", "Gauge forces", "force", "force",
             [c for c in h if c.startswith("gauge.") and c.endswith(".force")]),
            ("masses", "Mass displacements", "displacement", "displacement",
             [c for c in h if c.startswith("body.") and c.endswith(".u")]))


def _line_figures(data, exact, out, formats, written):
    """Joint and end forces, gauges, mass motions: the columns a line adds
    (with the exact ones dashed when the line admits an exact solution),
    each drawn with its drawn_sign."""
    h, t, units = data.history, data.history["t"], data.units
    ts = units.time(t)
    for name, title, words, quantity, columns in _line_groups(h):
        if not columns:
            continue
        ys = units.axis(words, quantity, [drawn_sign(c) * h[c] for c in columns])
        fig, ax = _figure(title)
        exact_drawn = False
        for c in columns:
            line, = _line(ax, ts(t), ys(drawn_sign(c) * h[c]), lw=1.0, label=words_of(c, data.case))
            y = exact.history.get(c) if exact is not None else None
            if y is not None and np.any(np.isfinite(y)):
                _line(ax, ts(exact.history["t"]), ys(drawn_sign(c) * y), ls="--", lw=1.0, color=line.get_color())
                exact_drawn = True
        if exact_drawn:
            _exact_entry(ax)
        ax.set_xlabel(ts.label)
        ax.set_ylabel(ys.label)
        ax.legend(fontsize=8)
        _save(fig, out, name, formats, written)


def _blow_figures(data, out, formats, written):
    """A blow's figures: force and Z v at the gauge (the analyser's plot,
    compression and downward velocity positive), the toe's resistance, and
    the stress envelopes along the pile."""
    blow = data.summary.get("blow")
    if not blow:
        return
    rows, note = _blow_rows(data, blow)
    h = {k: np.asarray(v)[rows] for k, v in data.history.items()}  # the blow's rows, for its head and toe
    gauge = blow.get("gauge")
    if gauge and f"gauge.{gauge}.force" in h and blow.get("impedance"):
        _head_figure(data, h, note, gauge, blow["impedance"], out, formats, written)
    if data.case.get("near_end", {}).get("law") == "smith":
        _toe_figure(data, h, note, blow, out, formats, written)
    env = blow.get("envelope")
    if env and env.get("x"):
        _envelope_figure(data, blow, env, out, formats, written)


def _round_trip(data, blow):
    """The pile's wave round trip 2 L / c from the case (None: not numbers)."""
    pile = next((b for b in data.case.get("body", []) if b.get("name") == blow.get("pile")), None)
    try:
        return 2.0 * float(pile["length"]) / (float(pile["modulus"]) / float(pile["density"])) ** 0.5
    except (TypeError, KeyError, ValueError, ZeroDivisionError):
        return None


def _blow_rows(data, blow):
    """The history's rows of the blow, and the title's note: from impact to
    six wave round trips past the soil's last slip, never past the ram's
    re-strike; every row when the round trip is unknown."""
    t = np.asarray(data.history["t"], dtype=float)
    end = float(t[-1])
    trip = _round_trip(data, blow)
    if trip:
        since = max(float(blow.get("last_slip_time") or 0.0), float(blow.get("impact_time") or 0.0))
        end = min(end, since + 6.0 * trip)
    if blow.get("restrike_time") is not None:
        end = min(end, float(blow["restrike_time"]))
    rows = t <= end
    if rows.all():
        return rows, ""
    ts = data.units.time(t)
    return rows, f"\n(the blow: to {ts.text(end, 3)} of a run to {ts.text(t[-1], 3)})"


def _head_figure(data, h, note, gauge, z, out, formats, written):
    units = data.units
    force = -h[f"gauge.{gauge}.force"]  # compression positive
    zv = -z * h[f"gauge.{gauge}.velocity"]  # downward positive: Z v = F in a wave going down
    ts = units.time(h["t"])
    fs = units.axis("force, Z v", "force", np.concatenate([force, zv]), sign="compression +, Z v: down +")
    fig, ax = _figure(f"Pile {words_of(f'gauge.{gauge}.force', data.case).removesuffix(' force')}: force and "
                      f"impedance times velocity{note}")
    _line(ax, ts(h["t"]), fs(force), lw=1.1, label="force F")
    _line(ax, ts(h["t"]), fs(zv), lw=1.1, label=f"Z v, Z = {units.axis('', 'impedance', z).text(z)}")
    ax.set_xlabel(ts.label)
    ax.set_ylabel(fs.label)
    ax.legend(fontsize=8)
    _save(fig, out, "blow_head", formats, written)


def _toe_figure(data, h, note, blow, out, formats, written):
    units = data.units
    ts = units.time(h["t"])
    words, rs = _column(data, "R", h["R"])
    penetration = -h["U"]  # the toe's displacement is up the pile: into the soil is down
    ps = units.axis("toe penetration", "displacement", np.append(penetration, blow.get("set", 0.0)),
                    sign=units.sign("penetration"))
    fig, ax = _figure(f"Toe resistance and penetration, Smith soil{note}")
    _line(ax, ts(h["t"]), rs(h["R"]), lw=1.1, color="tab:brown", label=words)
    ax.set_xlabel(ts.label)
    ax.set_ylabel(rs.label)
    right = ax.twinx()
    _line(right, ts(h["t"]), ps(penetration), lw=1.0, color="tab:blue", label="toe penetration")
    if blow.get("set", 0) > 0:
        right.axhline(ps(blow["set"]), color="tab:blue", lw=0.8, ls="--", label=f"set {ps.text(blow['set'], 3)}")
    right.set_ylabel(ps.label)
    lines = ax.get_legend_handles_labels(), right.get_legend_handles_labels()
    ax.legend(lines[0][0] + lines[1][0], lines[0][1] + lines[1][1], fontsize=8)
    _save(fig, out, "blow_toe", formats, written)


def _envelope_figure(data, blow, env, out, formats, written):
    """The largest compression and tension of each element, magnitudes, against the height above the toe."""
    units = data.units
    x, compression, tension = (np.asarray(env[k], dtype=float) for k in ("x", "compression", "tension"))
    ss = units.axis("largest stress, a magnitude", "stress", np.concatenate([compression, tension]), sign=False)
    xs = units.axis("height above the toe", "length", x, sign=False)
    fig, ax = _figure(f"Stress envelopes along the {spoken(blow.get('pile', 'pile'))}")
    ax.plot(ss(compression), xs(x), lw=1.2, label="largest compression")
    ax.plot(ss(tension), xs(x), lw=1.2, label="largest tension")
    ax.set_xlabel(ss.label)
    ax.set_ylabel(xs.label)
    ax.legend(fontsize=8)
    _save(fig, out, "blow_envelopes", formats, written)


# --- where figures go: the library's output rule ------------------------------------------

def _is_directory(source):
    return isinstance(source, (str, os.PathLike))


def prepare_figures(out, names, formats, force=False, reads=()):
    """`out` made ready for the figures `names` (in each of `formats`) by the
    library's output rule, as `barimpact run --out` (output_directory.hpp): a
    new or empty directory, or one barimpact wrote; someone else's only with
    force (beside their files); never $HOME, / or a parent of the working
    directory, nor one of the directories `reads` (or a parent of one). It
    is created and marked as listing the figures before they are drawn.
    barimpact.InputError (one line) when refused. Returns `out` as a Path."""
    entries = [f"{name}.{fmt}" for name in names for fmt in formats]
    reads = [os.fspath(r) for r in reads]
    if entries:
        _core._prepare_output_directory(out, "plot", entries, bool(force), reads)
    else:  # nothing will be saved: checked, not made
        _core._check_output_directory(out, bool(force), reads)
    return Path(out)


def figures_directory(directory, out, names, formats, force=False):
    """prepare_figures for the figures of a run or sweep `directory` (which
    is read, so never written over): into `out`, else DIR/figures, which is
    then listed in DIR's marker as the run's (a rerun replaces it with them)."""
    ours = out is None and _core._written_by_barimpact(directory)  # asked before figures/ is there
    target = prepare_figures(Path(directory) / "figures" if out is None else out, names, formats, force, [directory])
    if ours:
        _core._mark_entries(directory, ["figures"])
    return target


def study_directory(directory, command):
    """`directory` as a Path when barimpact's `command` (converge, bearing,
    hopkinson) wrote it, which lists that command's figures, or when it is
    the staging directory barimpact fills for it; barimpact.InputError
    otherwise (drawn anywhere else, they could replace someone's files)."""
    if _core._output_command(directory) != command and not _core._is_staging(directory):
        raise _core.InputError(f"{os.fspath(directory)}: not a directory barimpact {command} wrote (its figures go "
                               "only there)")
    return Path(directory)


def read_table_summary(directory, name):
    """A command's table NAME (hopkinson.csv, pda.csv) as a dict of numpy
    arrays (nan where a cell is missing), and its summary.json."""
    d = Path(directory)
    with open(d / name) as f:
        names = f.readline().strip().split(",")
    data = np.loadtxt(d / name, delimiter=",", skiprows=1, ndmin=2)
    table = {column: data[:, i] for i, column in enumerate(names)}
    with open(d / "summary.json") as f:
        summary = json.load(f)
    return table, summary


def draw_into(draw, staging, shown, formats=("png", "svg")):
    """draw(staging, formats) into the staging directory of `shown`, the
    directory the results are moved to once whole: an OSError (a full disk)
    names the figure there, not in the staging directory, which is gone by then."""
    try:
        return draw(staging, formats)
    except OSError as e:
        if e.filename is None or not Path(e.filename).is_relative_to(staging):
            raise
        raise OSError(e.errno, e.strerror, str(Path(shown) / Path(e.filename).relative_to(staging))) from e


# --- entry points ---------------------------------------------------------------------

def _data_of(source):
    if isinstance(source, RunData):
        return source
    return load(source) if _is_directory(source) else _from_result(source)


def plot(source, out=None, formats=("png", "svg"), force=False):
    """Write the figures of `source` (a Result, a RunData or a run directory)
    into `out` (default: DIR/figures for a directory, else ./figures) by the
    output rule (prepare_figures; `force` as --force). Returns the paths written."""
    names = _core._figure_names
    if _is_directory(source):
        # The rule first, then the run read whole: results it cannot read are
        # refused before figures/ is made or listed in the run's marker.
        _core._check_output_directory(Path(source) / "figures" if out is None else out, bool(force),
                                     [os.fspath(source)])
        data = _data_of(source)
        out = figures_directory(source, out, names, formats, force)
    else:
        data = _data_of(source)
        out = prepare_figures("figures" if out is None else out, names, formats, force)
    written = []
    refs, exact = references(data)
    _history_figure(data, refs, "U", "displacement", out, formats, written)
    _history_figure(data, refs, "R", "reaction", out, formats, written)
    _energy_figure(data, exact, out, formats, written)
    if data.field_t.size >= 2:
        _map_figure(data, "sigma", "stress_map", "stress", "stress", "RdBu_r", out, formats, written)
    eps_p = data.eps_p
    if data.field_t.size >= 2 and eps_p is not None and eps_p.size and np.any(eps_p != 0):
        _map_figure(data, "eps_p", "plastic_map", "plastic strain", "strain", "PuOr_r", out, formats, written)
        _snapshots(data, "eps_p", "plastic strain", "strain", out, "plastic_snapshots", formats, written, exact)
    if data.field_t.size >= 1:
        _snapshots(data, "u", "displacement", "displacement", out, "snapshots", formats, written, exact)
    _impacts_figure(data, refs, out, formats, written)
    _line_figures(data, exact, out, formats, written)
    _blow_figures(data, out, formats, written)
    return written


COMPARED = ("U", "R")  # the history columns compare draws, one figure each


def compare(sources, out, formats=("png", "svg"), labels=None, name="compare", force=False):
    """Several runs (Results, RunData or run directories) in one figure per
    quantity, `name`_U and `name`_R in `out` (by the output rule:
    prepare_figures, never over a run directory compared): each curve is
    named by the case keys that differ between the runs (or by `labels`),
    the keys they share go unnamed. Returns the paths written."""
    reads = [s for s in sources if _is_directory(s)]
    out = prepare_figures(out, [f"{name}_{column}" for column in COMPARED], formats, force, reads)
    return compared([_data_of(s) for s in sources], out, formats, labels, name)


def compared(runs, out, formats=("png", "svg"), labels=None, name="compare"):
    """compare's figures of the RunData `runs`, drawn into `out`, which the
    caller has made ready (prepare_figures)."""
    units = runs[0].units
    if labels is None:
        labels = legend_labels([_run_settings(r) for r in runs], units)
    written = []
    ts = units.time(*(r.history["t"] for r in runs))
    for column in COMPARED:
        words, ys = _column(runs[0], column, np.concatenate([r.history[column] for r in runs]))
        fig, ax = _figure(_capital(words))
        # past the ten colours of the cycle, a colour map keeps every curve its own
        colors = plt.cm.viridis(np.linspace(0, 0.9, len(runs))) if len(runs) > 10 else [None] * len(runs)
        for run, label, color in zip(runs, labels, colors):
            _line(ax, ts(run.history["t"]), ys(run.history[column]), lw=1.0, label=label, color=color)
        ax.set_xlabel(ts.label)
        ax.set_ylabel(ys.label)
        if len(runs) > 4:  # beside the axes: over them it would hide the curves
            ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
        else:
            ax.legend(fontsize=8)
        _save(fig, out, f"{name}_{column}", formats, written)
    return written


# A study's or analysis's table, the command that wrote it, and the module
# and function that draw its figures where the command draws them.
REDRAWN = {
    "hopkinson.csv": ("hopkinson", "hopkinson", "plot_hopkinson"),
    "pda.csv": ("pda", "pda", "plot_pda"),
    "match.csv": ("match", "match", "plot_match"),
    "bearing.csv": ("bearing", "bearing", "plot_bearing"),
    "drive.csv": ("drive", "drive", "plot_drive"),
    "inspector.csv": ("inspector", "drive", "plot_inspector"),
    "convergence.csv": ("converge", "convergence", "plot_study"),
}


def redraw(directory, out=None):
    """The figures of a hopkinson, pda, match, bearing, drive, inspector or
    converge directory drawn again (after --no-plot) where the command draws
    them: into the directory (hopkinson's into its figures/), which must be
    the one barimpact wrote; they join its marker, so that a rerun replaces
    them. Returns the paths, or None when `directory` holds no such table."""
    import importlib
    d = Path(directory)
    for table, (command, module, draw) in REDRAWN.items():
        if (d / table).is_file():
            if out is not None:
                raise ValueError(f"{d}: a barimpact {command} directory's figures go into it, as the command draws "
                                 "them (leave out --out)")
            written = getattr(importlib.import_module(f".{module}", __package__), draw)(d)
            # Each figure's entry in the directory: the figure, or figures/ holding it (hopkinson's).
            _core._mark_entries(os.fspath(d), sorted({Path(p).relative_to(d).parts[0] for p in written}))
            return written
    return None
