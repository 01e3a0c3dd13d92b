"""The figures of a `barimpact match` directory (match.csv, soil.csv,
static.csv, summary.json): the measured and computed force and wave up at
the gauges, the soil's resistance along the pile, and the simulated static
load test."""
import csv
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .plot import DPI, FIGSIZE, _line, _save, draw_into, read_table_summary, study_directory  # noqa: E402
from .style import Units  # noqa: E402


def read_soil(directory):
    """soil.csv as the shaft's rows (a dict of numpy arrays: top, bottom,
    resistance, quake, damping) and the toe's row (a dict of floats)."""
    with open(Path(directory) / "soil.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    columns = ("top", "bottom", "resistance", "quake", "damping")
    shaft = {c: np.array([float(r[c]) for r in rows if r["segment"] != "toe"]) for c in columns}
    toe = next(({c: float(r[c]) for c in columns} for r in rows if r["segment"] == "toe"), None)
    return shaft, toe


def read_match(directory):
    """match.csv and static.csv as dicts of numpy arrays, soil.csv as
    read_soil gives it, and summary.json."""
    m, s = read_table_summary(directory, "match.csv")
    static, _ = read_table_summary(directory, "static.csv")
    return m, read_soil(directory), static, s


def _units(s):
    """The record's units (summary.json's), SI when it says none."""
    return Units((s.get("units") or {}).get("system", "SI"))


def _time_marks(ax, s, ts, label):
    for key, style in (("t1", "--"), ("t2", ":")):
        ax.axvline(ts(s[key]), color="0.4", lw=0.9, ls=style, label=f"{key} = {ts.text(s[key])}" if label else None)
    ax.axhline(0, color="0.6", lw=0.6)
    ax.grid(True, alpha=0.3)


def _measured_computed(ax, t, fs, m, column, colour, what):
    """Measured wide and computed thin on top: where they agree, both show."""
    _line(ax, t, fs(m[f"{column}_measured"]), color=colour, lw=2.4, alpha=0.6, label=f"{what} measured")
    _line(ax, t, fs(m[f"{column}_computed"]), color="tab:red", lw=1.0, ls="--", label=f"{what} computed")


def _match_figure(m, s, out, formats, written):
    """The force at the gauges above, the wave up below (its misfit is the
    soil's), t1 and t2 marked."""
    units = _units(s)
    ts = units.time(m["t"])
    t = ts(m["t"])
    forces = [m["force_measured"], m["force_computed"]]  # one unit for both panels: the force's
    fs, ws = (units.axis(words, "force", forces) for words in ("force at the gauges", "wave up Wu"))
    cs = units.axis("", "force", s["capacity"])
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(FIGSIZE[0], 6.0), dpi=DPI, sharex=True, layout="constrained",
                                  height_ratios=(3, 2))
    fig.suptitle(f"Signal match: capacity {cs.text(s['capacity'])} (shaft {cs.text(s['shaft'])}, toe "
                 f"{cs.text(s['toe'])}), match quality {100 * s['match_quality']:.3g}%")
    _measured_computed(ax, t, fs, m, "force", "k", "force")
    _time_marks(ax, s, ts, True)
    ax.set_ylabel(fs.label, fontsize=9)
    ax.legend(fontsize=8, loc="best")
    _measured_computed(ax2, t, ws, m, "wave_up", "tab:green", "wave up")
    _time_marks(ax2, s, ts, False)
    ax2.set_xlabel(ts.label)
    ax2.set_ylabel(ws.label, fontsize=9)
    ax2.legend(fontsize=8, loc="best")
    _save(fig, out, "force_match", formats, written)


def _resistance_figure(shaft, toe, s, out, formats, written):
    """Each shaft segment's resistance as a bar over its depths, and the
    resistance above each depth, the toe's its step at the bottom (several
    segments' worth: not drawn to the bars' scale). Depth downward, as a
    pile is drawn."""
    length = s["length"]
    units = _units(s)
    cs = units.axis("", "force", s["capacity"])
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=FIGSIZE, dpi=DPI, sharey=True, layout="constrained")
    fig.suptitle(f"Soil resistance: shaft {cs.text(s['shaft'])} on {len(shaft['top'])} segments, toe "
                 f"{cs.text(s['toe'])}")
    top, bottom, r = shaft["top"], shaft["bottom"], cs(shaft["resistance"])
    ax.barh(top, r, height=bottom - top, align="edge", color="tab:brown", alpha=0.7, edgecolor="k", lw=0.6)
    ax.set_xlabel(f"shaft resistance per segment [{cs.unit}]" if cs.unit else "shaft resistance per segment")
    ax.set_ylabel(units.axis("depth below the gauges", "length", None, sign=False).label)
    ax.set_xlim(0, 1.15 * max(r.max(initial=0.0), 1e-9))
    ax.set_title("Shaft, per segment", fontsize=10)
    # Each segment's resistance spreads evenly over its length: the sum above a depth is piecewise linear.
    cumulative = np.concatenate(([0.0], np.cumsum(r)))
    depth = np.concatenate((top[:1], bottom))
    ax2.plot(np.append(cumulative, cs(s["capacity"])), np.append(depth, length), "k", lw=1.4,
             label="resistance above the depth")
    ax2.axvline(cs(s["shaft"]), color="tab:brown", ls=":", lw=1.0, label=f"shaft {cs.text(s['shaft'])}")
    ax2.axvline(cs(s["capacity"]), color="tab:red", ls="--", lw=1.0,
                label=f"capacity {cs.text(s['capacity'])}")
    ax2.annotate(f"toe {cs.text(toe['resistance'])}", (cs(s["capacity"]), length), xytext=(-4, 3),
                 textcoords="offset points", ha="right", va="bottom", fontsize=9,
                 bbox=dict(boxstyle="square,pad=0.1", fc="white", ec="none", alpha=0.8))
    ax2.set_xlabel(f"cumulative resistance [{cs.unit}]" if cs.unit else "cumulative resistance")
    ax2.set_xlim(0, 1.08 * cs(s["capacity"]))
    ax2.set_title("Cumulative, from the gauges down", fontsize=10)
    for a in (ax, ax2):
        a.axhline(length, color="k", lw=1.5)
        a.grid(True, alpha=0.3)
    marks = [(length, "toe")]
    if top.size and top[0] > 0:  # [match] embedded: the soil starts below the gauges
        marks.append((top[0], "top of the soil"))
        for a in (ax, ax2):
            a.axhline(top[0], color="tab:olive", lw=1.0, ls="-.")
    for depth, text in marks:
        ax.text(0.98, depth, text, transform=ax.get_yaxis_transform(), ha="right", va="bottom", fontsize=9)
    ax.set_ylim(1.04 * length, 0)  # depth downward, the gauges at the top (shared)
    ax2.legend(fontsize=8, loc="best")
    _save(fig, out, "resistance", formats, written)


def _static_figure(static, s, out, formats, written):
    """Load against settlement, settlement downward as a load test's plot."""
    units = _units(s)
    ls = units.axis("load at the gauges", "force", s["capacity"], sign=False)
    ds = units.axis("settlement", "displacement", np.append(static["settlement"], s["s_c"]),
                    sign=units.sign("penetration"))
    load, settlement = ls(static["load"]), ds(static["settlement"])
    capacity, s_c = ls(s["capacity"]), ds(s["s_c"])
    fig, ax = plt.subplots(figsize=FIGSIZE, dpi=DPI, layout="constrained")
    ax.set_title(f"Simulated static load test: capacity {ls.text(s['capacity'])} reached at s_c = "
                 f"{ds.text(s['s_c'], 3)}")
    ax.plot(load, settlement, "k", lw=1.4, label="load at the gauges")
    ax.axvline(capacity, color="tab:red", ls="--", lw=1.0, label=f"capacity {ls.text(s['capacity'])}")
    ax.axhline(s_c, color="tab:blue", ls=":", lw=1.0,
               label=f"s_c = {ds.text(s['s_c'], 3)} (largest quake + shortening)")
    ax.plot([capacity], [s_c], "o", color="tab:red", ms=5)
    ax.set_xlabel(ls.label)
    ax.set_ylabel(ds.label)
    ax.set_xlim(0, 1.1 * capacity)
    ax.set_ylim(settlement.max(initial=s_c), 0)  # settlement downward
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="lower left")
    _save(fig, out, "static_test", formats, written)


def plot_match(directory, formats=("png", "svg")):
    """Draws the three figures into the directory barimpact match fills or
    wrote (nowhere else); returns their paths: force_match (measured and
    computed force and wave up), resistance (per segment and cumulative,
    against depth) and static_test (load against settlement)."""
    out = study_directory(directory, "match")
    m, (shaft, toe), static, s = read_match(out)
    written = []
    _match_figure(m, s, out, formats, written)
    _resistance_figure(shaft, toe, s, out, formats, written)
    _static_figure(static, s, out, formats, written)
    return written


def plot_match_into(staging, shown, formats=("png", "svg")):
    """plot_match into the staging directory of `shown` (see draw_into)."""
    return draw_into(plot_match, staging, shown, formats)
