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

from .plot import DPI, FIGSIZE, _save, draw_into, read_table_summary, study_directory  # noqa: E402


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


def _time_marks(ax, s, label):
    for key, style in (("t1", "--"), ("t2", ":")):
        ax.axvline(1e3 * s[key], color="0.4", lw=0.9, ls=style,
                   label=f"{key} = {1e3 * s[key]:.4g} ms" if label else None)
    ax.axhline(0, color="0.6", lw=0.6)
    ax.grid(True, alpha=0.3)


def _measured_computed(ax, t, m, column, colour, what):
    """Measured wide and computed thin on top: where they agree, both show."""
    ax.plot(t, 1e-3 * m[f"{column}_measured"], color=colour, lw=2.4, alpha=0.6, label=f"{what} measured")
    ax.plot(t, 1e-3 * m[f"{column}_computed"], color="tab:red", lw=1.0, ls="--", label=f"{what} computed")


def _match_figure(m, s, out, formats, written):
    """The force at the gauges above, the wave up below (its misfit is the
    soil's), t1 and t2 marked."""
    t = 1e3 * m["t"]
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(FIGSIZE[0], 6.0), dpi=DPI, sharex=True, layout="constrained",
                                  height_ratios=(3, 2))
    fig.suptitle(f"Signal match: capacity {1e-3 * s['capacity']:.4g} kN (shaft {1e-3 * s['shaft']:.4g} kN, toe "
                 f"{1e-3 * s['toe']:.4g} kN), match quality {100 * s['match_quality']:.3g}%")
    _measured_computed(ax, t, m, "force", "k", "force")
    _time_marks(ax, s, True)
    ax.set_ylabel("force at the gauges (kN, compression > 0)")
    ax.legend(fontsize=8, loc="best")
    _measured_computed(ax2, t, m, "wave_up", "tab:green", "wave up")
    _time_marks(ax2, s, False)
    ax2.set_xlabel("t (ms)")
    ax2.set_ylabel("wave up Wu = (F - Z v)/2 (kN)")
    ax2.legend(fontsize=8, loc="best")
    _save(fig, out, "force_match", formats, written)


def _resistance_figure(shaft, toe, s, out, formats, written):
    """Each shaft segment's resistance as a bar over its depths, and the
    resistance above each depth, the toe's its step at the bottom (several
    segments' worth: not drawn to the bars' scale). Depth downward, as a
    pile is drawn."""
    length = s["length"]
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=FIGSIZE, dpi=DPI, sharey=True, layout="constrained")
    fig.suptitle(f"Soil resistance: shaft {1e-3 * s['shaft']:.4g} kN on {len(shaft['top'])} segments, toe "
                 f"{1e-3 * s['toe']:.4g} kN")
    top, bottom, r = shaft["top"], shaft["bottom"], 1e-3 * shaft["resistance"]
    ax.barh(top, r, height=bottom - top, align="edge", color="tab:brown", alpha=0.7, edgecolor="k", lw=0.6)
    ax.set_xlabel("shaft resistance per segment (kN)")
    ax.set_ylabel("depth below the gauges (m)")
    ax.set_xlim(0, 1.15 * max(r.max(initial=0.0), 1e-9))
    ax.set_title("Shaft, per segment", fontsize=10)
    # Each segment's resistance spreads evenly over its length: the sum above a depth is piecewise linear.
    cumulative = np.concatenate(([0.0], np.cumsum(r)))
    depth = np.concatenate((top[:1], bottom))
    ax2.plot(np.append(cumulative, 1e-3 * s["capacity"]), np.append(depth, length), "k", lw=1.4,
             label="resistance above the depth")
    ax2.axvline(1e-3 * s["shaft"], color="tab:brown", ls=":", lw=1.0, label=f"shaft {1e-3 * s['shaft']:.4g} kN")
    ax2.axvline(1e-3 * s["capacity"], color="tab:red", ls="--", lw=1.0,
                label=f"capacity {1e-3 * s['capacity']:.4g} kN")
    ax2.annotate(f"toe {1e-3 * toe['resistance']:.4g} kN", (1e-3 * s["capacity"], length), xytext=(-4, 3),
                 textcoords="offset points", ha="right", va="bottom", fontsize=9,
                 bbox=dict(boxstyle="square,pad=0.1", fc="white", ec="none", alpha=0.8))
    ax2.set_xlabel("cumulative resistance (kN)")
    ax2.set_xlim(0, 1.08 * 1e-3 * s["capacity"])
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
    load, settlement = 1e-3 * static["load"], 1e3 * static["settlement"]
    capacity, s_c = 1e-3 * s["capacity"], 1e3 * s["s_c"]
    fig, ax = plt.subplots(figsize=FIGSIZE, dpi=DPI, layout="constrained")
    ax.set_title(f"Simulated static load test: capacity {capacity:.4g} kN reached at s_c = {s_c:.3g} mm")
    ax.plot(load, settlement, "k", lw=1.4, label="load at the gauges")
    ax.axvline(capacity, color="tab:red", ls="--", lw=1.0, label=f"capacity {capacity:.4g} kN")
    ax.axhline(s_c, color="tab:blue", ls=":", lw=1.0, label=f"s_c = {s_c:.3g} mm (largest quake + shortening)")
    ax.plot([capacity], [s_c], "o", color="tab:red", ms=5)
    ax.set_xlabel("load (kN)")
    ax.set_ylabel("settlement (mm)")
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
