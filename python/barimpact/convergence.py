"""Figures of studies.

A `barimpact converge` directory: the error of U against h (or dt, or the
varied key) on log-log axes, with reference slopes 1 and 2 and each
scheme's measured order, and against CPU time (work-precision), one line
per scheme.

A `barimpact sweep` directory: every numeric output column of sweep.csv
against the swept keys, one figure per output (log axes where the swept
values are log-spaced; with two swept keys or more, one curve per value of
the others; zipped keys count as one), and the runs' U(t) and R(t) overlaid
(runs_U, runs_R) when there are few enough to tell apart.
"""
import csv
import math
import re
import sys
from pathlib import Path

import numpy as np
from matplotlib.ticker import NullLocator

from .plot import (_figure, _save, compared, figures_directory, is_run_directory, key_quantity, legend_labels, load,
                   study_directory, units_of_runs)
from .style import key_words, spoken


def _float(text):
    """A cell as a finite float, None otherwise."""
    try:
        v = float(text)
        return v if math.isfinite(v) else None
    except (TypeError, ValueError):
        return None


# --- converge ------------------------------------------------------------------------

def _study_text(directory):
    try:
        return (Path(directory) / "convergence.md").read_text()
    except OSError:
        return ""


def _abscissa(rows, text):
    """(column, name, quantity, refined): what the errors are drawn against:
    the varied key's value, else h when the levels refine it, else dt."""
    # The command's `--vary key=...`, or the Python call's `vary='key=...'` / `vary=('key', ...)`.
    vary = re.search(r"--vary[ =]'?([^\s=']+)=", text) or re.search(r"vary=\(?['\"]([^'\"=]+)['\"=]", text)
    if any(r["value"] for r in rows) and all(_float(r["value"]) is not None for r in rows if r["value"]):
        key = vary.group(1) if vary else "varied value"
        return "value", key_words(key), key_quantity(key), False
    if len({r["h"] for r in rows}) > 1 or len({r["step"] for r in rows}) <= 1:
        return "h", "element length h", "length", True
    return "step", "time step dt", "time", True


def measured_order(xs, errors):
    """The least-squares slope of log(error) against log(x), None with fewer than two points."""
    pts = [(math.log(x), math.log(e)) for x, e in zip(xs, errors) if x and e and x > 0 and e > 0]
    if len({p[0] for p in pts}) < 2:
        return None
    return float(np.polyfit(*zip(*pts), 1)[0])


def _scheme_label(scheme, order, errors, refined, xname):
    """The scheme (what differs between the lines) and what its points measure."""
    if order is None:
        return scheme
    if not refined:  # a varied key, not a mesh: the error's power of it
        return f"{scheme}: error ~ {xname}^{order:.2f}"
    if order < 0.2 and max(errors) < 1e-9:
        return f"{scheme}: at round-off"  # no order to read: the errors are the arithmetic's
    return f"{scheme}: order {order:.2f}"


def reference_slopes(ax, points, orders=(1, 2)):
    """Dashed lines of slope 1 and 2 (labelled) from the coarsest point
    down over the x range, just above the highest error there: what the
    measured curves are read against."""
    points = [(x, y) for x, y in points if x > 0 and y > 0]
    if len({x for x, _ in points}) < 2:
        return
    lo, hi = min(x for x, _ in points), max(x for x, _ in points)
    top = 1.5 * max(y for x, y in points if x == hi)
    for order, dashes in zip(orders, ((0, (6, 3)), (0, (1, 2)))):
        ax.loglog([lo, hi], [top * (lo / hi) ** order, top], color="0.35", lw=1.0, ls=dashes,
                  label=f"slope {order}")


def _study_figure(rows, schemes, xkey, xname, xlabel, name, units, refined, note):
    fig, ax = _figure("Convergence" if name == "convergence" else "Work-precision")
    all_points = []
    for scheme in schemes:
        pts = [(_float(r[xkey]), _float(r["error_U_max"])) for r in rows if r["scheme"] == scheme]
        pts = [(x, y) for x, y in pts if x and y and x > 0 and y > 0]
        if not pts:
            continue
        label = scheme
        if name == "convergence":
            label = _scheme_label(scheme, measured_order(*zip(*pts)), [y for _, y in pts], refined, xname)
        ax.loglog(*zip(*pts), "o-", label=label)
        all_points += pts
    if name == "convergence" and refined:
        reference_slopes(ax, all_points)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(units.axis("largest error of the near-end displacement", "displacement", sign=False).label)
    if note:
        ax.text(0.99, 0.01, note, transform=ax.transAxes, ha="right", va="bottom", fontsize=7, color="0.3")
    ax.grid(True, which="both", alpha=0.3)
    if ax.lines:
        ax.legend(fontsize=8)
    return fig


def plot_study(directory, formats=("png", "svg")):
    """Draws convergence and work_precision (PNG, SVG) into a converge
    directory; returns the paths. Each scheme's legend entry names the
    scheme (what differs between the lines) and its measured order."""
    d = study_directory(directory, "converge")
    with open(d / "convergence.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    schemes = list(dict.fromkeys(r["scheme"] for r in rows))
    units = units_of_runs(d)
    text = _study_text(d)
    xkey, xname, quantity, refined = _abscissa(rows, text)
    reference = re.search(r"^Reference: (.*?)\.?$", text, re.M)
    note = f"reference: {reference.group(1)}" if reference else ""
    written = []
    for name, key, label in (("convergence", xkey, units.axis(xname, quantity, sign=False).label),
                             ("work_precision", "cpu_seconds", "CPU time [s]")):  # seconds whatever the case's units
        _save(_study_figure(rows, schemes, key, xname, label, name, units, refined, note), d, name, formats, written)
    return written


# --- sweep ------------------------------------------------------------------------------

# The quantity of each sweep.csv output (None: a count or a ratio), and its words.
OUTPUT_QUANTITIES = {"t_end": "time", "first_contact": "time", "lift_off": "time", "rebound_velocity": "velocity",
                     "max_penetration": "displacement", "max_reaction": "force", "set": "displacement",
                     "max_compression": "stress", "max_tension": "stress", "enthru": "energy", "run_seconds": None}
OUTPUT_WORDS = {"steps_done": "steps done", "t_end": "end time", "contacts": "contact episodes",
                "first_contact": "first contact time", "lift_off": "lift-off time",
                "rebound_velocity": "rebound velocity", "max_penetration": "largest penetration",
                "max_reaction": "largest reaction", "energy_error_relative": "relative energy error",
                "run_seconds": "run time [s]", "set": "set (permanent penetration of the blow)",
                "blows_per_250mm": "blows per 250 mm", "blows_per_m": "blows per m",
                "max_compression": "largest compression stress", "max_tension": "largest tension stress",
                "enthru": "energy through the gauge (EMX)", "transfer_ratio": "energy transfer ratio"}


def output_words(column):
    """A sweep.csv output column in words."""
    return OUTPUT_WORDS.get(column, spoken(column))
RUNS_OVERLAID = 12  # more curves than this in one figure cannot be told apart


def read_sweep(directory):
    """sweep.csv as (keys, outputs, rows): the swept keys (the columns
    between id and status), the numeric output columns, and the rows as
    dicts of text."""
    with open(Path(directory) / "sweep.csv", newline="") as f:
        reader = csv.DictReader(f)
        header, rows = reader.fieldnames, list(reader)
    status = header.index("status")
    keys = header[1:status]

    def numeric(column):
        cells = [r[column] for r in rows if r[column] != ""]
        return cells and all(_number(c) is not None for c in cells)

    outputs = [c for c in header[status + 1:] if c not in ("message", "warnings") and numeric(c)]
    return keys, outputs, rows


def _number(text):
    """A cell as a float (nan and inf included), None when not a number."""
    try:
        return float(text)
    except (TypeError, ValueError):
        return None


def _one_to_one(rows, a, b):
    pairs = {(r[a], r[b]) for r in rows}
    return len(pairs) == len({p for p, _ in pairs}) == len({q for _, q in pairs})


def sweep_dimensions(keys, rows):
    """The swept keys grouped into the sweep's dimensions: keys whose values
    go one to one (a zip) make one dimension, named by its first key."""
    dims = []
    for key in keys:
        for dim in dims:
            if _one_to_one(rows, dim[0], key):
                dim.append(key)
                break
        else:
            dims.append([key])
    return dims


def log_spaced(values):
    """True when positive numbers are spaced by a ratio rather than a
    difference (or span three decades): they belong on a log axis."""
    v = np.unique([x for x in values if x is not None])
    if v.size < 2 or v[0] <= 0:
        return False
    if v.size == 2:
        return v[1] / v[0] >= 10
    ratios, steps = v[1:] / v[:-1], np.diff(v)
    geometric = np.ptp(ratios) <= 0.01 * ratios.mean()
    linear = np.ptp(steps) <= 0.01 * steps.mean()
    return (geometric and not linear) or (not linear and v[-1] / v[0] >= 1000)


def _positions(rows, key):
    """Where each row sits on the x axis: its number, or the rank of its text
    among the key's values (a key of words: schemes, laws) with their ticks."""
    values = [_number(r[key]) for r in rows]
    if all(v is not None for v in values):
        return values, None
    words = list(dict.fromkeys(r[key] for r in rows))
    return [words.index(r[key]) for r in rows], words


def _setting(row, keys):
    """A row's values of `keys`, numbers as numbers (100.0 and 100 alike)."""
    return {k: _number(row[k]) if _number(row[k]) is not None else row[k] for k in keys}


def _curves(rows, dims):
    """The rows grouped into one curve per combination of the dimensions
    after the first, each curve's label naming only the keys that differ."""
    rest = [k for dim in dims[1:] for k in dim]
    groups = {}
    for r in rows:
        groups.setdefault(tuple(r[k] for k in rest), []).append(r)
    return list(groups.values()), rest


def _ring_warned(ax, rows, output, position, yscale):
    """Rings the points of cases that ran but doubt themselves (health
    warnings in sweep.csv): their values may not be trusted. True if any."""
    warned = [(position[r["id"]], _number(r[output])) for r in rows
              if r.get("warnings") and _number(r[output]) is not None]
    if warned:
        ax.plot([x for x, _ in warned], yscale([y for _, y in warned]), "o", ms=10, mfc="none", mec="tab:red",
                mew=1.2, label="has warnings (sweep.csv)")
    return bool(warned)


def _sweep_figure(output, dims, rows, units, dropped):
    """One output against the first dimension, a curve per value of the others."""
    x_key = dims[0][0]
    xs_all, words = _positions(rows, x_key)
    log_x = words is None and log_spaced(xs_all)
    ys = [_number(r[output]) for r in rows]
    finite = [y for y in ys if y is not None and math.isfinite(y)]
    log_y = bool(finite) and min(finite) > 0 and max(finite) / min(finite) >= 1000
    said = output_words(output)
    yscale = units.axis(said, OUTPUT_QUANTITIES.get(output), None if log_y else finite or None, sign=False)
    groups, rest = _curves(rows, dims)
    labels = legend_labels([_setting(g[0], rest) for g in groups], units) if rest else [None]
    position = dict(zip((r["id"] for r in rows), xs_all))
    title = f"{said[:1].upper()}{said[1:]} against {key_words(x_key)}"
    fig, ax = _figure(title + (f" ({dropped})" if dropped else ""))
    if not rows:
        ax.text(0.5, 0.5, "no complete case", transform=ax.transAxes, ha="center", color="0.4")
    for group, label in zip(groups, labels):
        pts = sorted((position[r["id"]], _number(r[output])) for r in group if _number(r[output]) is not None)
        if pts:
            ax.plot([x for x, _ in pts], yscale([y for _, y in pts]), "o-", ms=4, lw=1.2, label=label)
    warned = _ring_warned(ax, rows, output, position, yscale)
    if log_x:
        ax.set_xscale("log")
        swept = sorted(set(xs_all))
        if len(swept) <= 12:  # the swept values as the ticks, read as written (100, not 10^2)
            ax.set_xticks(swept, [f"{v:g}" for v in swept])
            ax.xaxis.set_minor_locator(NullLocator())
    if log_y:
        ax.set_yscale("log")
    if words is not None:
        ax.set_xticks(range(len(words)), words)
    partners = dims[0][1:]
    partners = ", ".join(key_words(k) for k in partners)
    ax.set_xlabel(units.axis(key_words(x_key), key_quantity(x_key), sign=False).label +
                  (f", with {partners}" if partners else ""))
    ax.set_ylabel(yscale.label)
    if (rest and len(groups) > 1) or warned:
        ax.legend(fontsize=8)
    return fig


def _dropped(rows, complete):
    left = len(rows) - len(complete)
    return f"{left} of {len(rows)} cases not complete, left out" if left else ""


def _run_overlays(d, out, keys, complete, units, formats):
    """U(t) and R(t) of every complete run in one figure each, named by the swept keys that differ."""
    runs = [d / "runs" / r["id"] for r in complete if is_run_directory(d / "runs" / r["id"])]
    if not 2 <= len(runs) <= RUNS_OVERLAID:
        return []
    by_id = {r["id"]: r for r in complete}
    leaders = [dim[0] for dim in sweep_dimensions(keys, complete)]  # a zipped key goes with its leader
    labels = legend_labels([_setting(by_id[p.name], leaders) for p in runs], units)
    try:
        data = [load(p, with_fields=False) for p in runs]
    except ImportError as e:  # runs in results.h5 without h5py: the sweep's own figures still drawn
        print(f"barimpact plot: the runs' overlays are left out: {e}", file=sys.stderr)
        return []
    return compared(data, out, formats, labels, "runs")


def plot_sweep(directory, out=None, formats=("png", "svg"), force=False):
    """The figures of a sweep directory into `out` (default DIR/figures, by
    the output rule: barimpact.plot's; `force` as --force): one per numeric
    output column of sweep.csv, named after it, and the runs' overlays.
    Returns the paths written."""
    d = Path(directory)
    keys, outputs, rows = read_sweep(d)
    out = figures_directory(d, out, [*outputs, "runs_U", "runs_R"], formats, force)
    complete = [r for r in rows if r["status"] == "complete"]
    units = units_of_runs(d)
    dims = sweep_dimensions(keys, rows) or [["id"]]  # no swept key: the cases in their order
    written = []
    for output in outputs:
        fig = _sweep_figure(output, dims, complete, units, _dropped(rows, complete))
        _save(fig, out, output, formats, written)
    written += _run_overlays(d, out, keys, complete, units, formats)
    return written
