"""The drivability of a `barimpact drive` directory: blow count, driving
stresses and capacity against depth, depth downwards (the way wave-equation
programs draw it), and the stroke for a diesel hammer."""
import json
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from .bearing import read_study_table  # noqa: E402
from .plot import DPI, _save, study_directory, units_of_runs  # noqa: E402


def read_drive(directory):
    """drive.csv's rows as dicts of floats (finished as a bool, the rest as text)."""
    return read_study_table(directory, "drive.csv")


def _depths(rows, units):
    """The depth axis' Scale (m, or ft under US), from every depth drawn."""
    return units.axis("toe depth", "length", [r["depth"] for r in rows] or [1.0], sign=units.sign("penetration"))


def _blow_counts(ax, rows, refusal, units, ds):
    """Blow counts up to twice the refusal; counts beyond it (and set 0) at the axis' right edge.
    Per 250 mm, or per ft under US (the refusal, given per 250 mm, likewise)."""
    words, per = units.blow_count()
    count = {id(r): per * r["blows_per_m"] for r in rows}
    refusal = per / 0.25 * refusal
    cap = 2.0 * refusal
    shown = [r for r in rows if count[id(r)] <= cap]
    ax.plot([count[id(r)] for r in shown], ds([r["depth"] for r in shown]), "o-", label="blow count")
    right = 1.1 * max([count[id(r)] for r in shown] + [refusal])
    beyond = [r for r in rows if count[id(r)] > cap]
    if beyond:
        right = 1.05 * cap
        ax.plot([cap] * len(beyond), ds([r["depth"] for r in beyond]), ">", color="tab:gray",
                label=f"beyond {cap:.3g} (set 0: inf)")
    unfinished = [r for r in shown if not r["finished"]]
    if unfinished:
        ax.plot([count[id(r)] for r in unfinished], ds([r["depth"] for r in unfinished]), "x", color="tab:red",
                label="pile not yet at rest")
    ax.axvline(refusal, color="tab:red", ls=":", label=f"refusal ({refusal:.3g})")
    ax.set_xlabel(words)
    ax.set_ylabel(ds.label)
    ax.set_xlim(0, right)
    ax.set_title("Blow count")


def _stresses(ax, rows, yield_stress, units, ds):
    ok = [r for r in rows if math.isfinite(r["max_compression"])]
    ss = units.axis("largest stress, a magnitude", "stress",
                    [r[k] for r in ok for k in ("max_compression", "max_tension")] + [yield_stress or 0.0], sign=False)
    ax.plot(ss([r["max_compression"] for r in ok]), ds([r["depth"] for r in ok]), "o-", label="largest compression")
    ax.plot(ss([r["max_tension"] for r in ok]), ds([r["depth"] for r in ok]), "s--", label="largest tension")
    if yield_stress:
        ax.axvline(ss(yield_stress), color="tab:red", ls=":", label="yield stress")
    ax.set_xlabel(ss.label)
    ax.set_xlim(left=0)
    ax.set_title("Driving stresses")


def _capacity(ax, rows, units, ds):
    depth = ds([r["depth"] for r in rows])
    cs = units.axis("static capacity", "force", [r[k] for r in rows for k in ("capacity", "long_term_capacity")],
                    sign=False)
    ax.plot(cs([r["capacity"] for r in rows]), depth, "o-", label="during driving")
    ax.plot(cs([r["long_term_capacity"] for r in rows]), depth, "--", label="long term (setup)")
    ax.plot(cs([r["toe"] for r in rows]), depth, ":", label="toe")
    ax.set_xlabel(cs.label)
    ax.set_xlim(left=0)
    ax.set_title("Capacity")


def plot_drive(directory, formats=("png", "svg")):
    """Draws drive.png (and .svg) into the directory barimpact drive wrote
    (nowhere else); returns the paths."""
    d = study_directory(directory, "drive")
    rows = read_drive(d)
    summary = json.loads((d / "summary.json").read_text())
    diesel = (summary.get("hammer") or {}).get("kind") == "diesel"
    panels = 4 if diesel else 3
    fig, axes = plt.subplots(1, panels, figsize=(3.6 * panels, 5), dpi=DPI, sharey=True, layout="constrained")
    units = units_of_runs(d, "SI")
    ds = _depths(rows, units)
    _blow_counts(axes[0], rows, summary["refusal"], units, ds)
    _stresses(axes[1], rows, (summary.get("pile") or {}).get("yield_stress"), units, ds)
    _capacity(axes[2], rows, units, ds)
    if diesel:
        strokes = units.axis("stroke", "length", [r["stroke"] for r in rows] or [1.0], sign=False)
        axes[3].plot(strokes([r["stroke"] for r in rows]), ds([r["depth"] for r in rows]), "o-", label="stroke")
        axes[3].set_xlabel(strokes.label)
        axes[3].set_title("Diesel hammer stroke")
    axes[0].invert_yaxis()  # depth downwards (the axes share it)
    refusal_depth = summary.get("refusal_depth")
    for ax in axes:
        if refusal_depth is not None:
            ax.axhline(ds(refusal_depth), color="tab:red", lw=0.8, ls="--",
                       label=f"refusal at {ds.text(refusal_depth)}" if ax is axes[0] else None)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize="small")
    hammer = summary.get("hammer") or {}
    pile = (summary.get("pile") or {}).get("name", "the pile")
    driven = "" if summary.get("total_blows") is None else (
        f": {summary['total_blows']:.0f} blows, {summary['driving_time']:.0f} min")
    fig.suptitle(f"Drivability of {pile} with {hammer.get('model') or hammer.get('kind') or 'its hammer'}{driven}")
    written = []
    _save(fig, d, "drive", formats, written)
    return written


def plot_inspector(directory, formats=("png", "svg")):
    """Draws inspector.png (and .svg), the inspector's chart, into the
    directory barimpact inspector wrote (nowhere else); returns the paths."""
    d = study_directory(directory, "inspector")
    rows = read_study_table(d, "inspector.csv")
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(10, 4.5), dpi=DPI, sharex=True, layout="constrained")
    units = units_of_runs(d, "SI")
    strokes = units.axis("stroke", "length", [r["stroke"] for r in rows] or [1.0], sign=False)
    stroke, stroke_label = strokes([r["stroke"] for r in rows]), strokes.label
    words, per = units.blow_count()
    ax.plot(stroke, [per * r["blows_per_m"] for r in rows], "o-", label="blow count")
    ax.set_xlabel(stroke_label)
    ax.set_ylabel(words)
    ax.set_title("Inspector's chart")
    ss = units.axis("largest stress, a magnitude", "stress",
                    [r[k] for r in rows for k in ("max_compression", "max_tension")], sign=False)
    ax2.plot(stroke, ss([r["max_compression"] for r in rows]), "o-", label="largest compression")
    ax2.plot(stroke, ss([r["max_tension"] for r in rows]), "s--", label="largest tension")
    ax2.set_xlabel(stroke_label)
    ax2.set_ylabel(ss.label)
    ax2.set_title("Driving stresses")
    for a in (ax, ax2):
        a.grid(True, alpha=0.3)
        a.legend(fontsize="small")
    written = []
    _save(fig, d, "inspector", formats, written)
    return written
