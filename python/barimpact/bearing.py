"""The bearing graph of a `barimpact bearing` directory: the static capacity
against the blow count (the way wave-equation programs draw it), and beside
it the pile's largest compression and tension stresses at each capacity."""
import csv
import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from .plot import DPI, _save, study_directory, units_of_runs  # noqa: E402


def _float(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return math.nan


def read_bearing(directory):
    """bearing.csv's rows as dicts of floats (finished as a bool, the rest as text)."""
    return read_study_table(directory, "bearing.csv")


def read_study_table(directory, name):
    """A pile study's table (bearing.csv, drive.csv): dicts of floats, finished a bool, the rest text."""
    rows = []
    with open(Path(directory) / name, newline="") as f:
        for r in csv.DictReader(f):
            row = {k: _float(v) for k, v in r.items() if k not in ("finished", "id", "status", "message", "warnings")}
            row.update(finished=r["finished"] == "true", id=r["id"], status=r["status"], message=r["message"])
            rows.append(row)
    return rows


def _capacity_axes(ax, ax2, rows, units):
    """The bearing graph (capacity against blow count) and the driving stresses at each capacity."""
    words, per = units.blow_count()  # per 250 mm, or per ft under US
    count = {id(r): per * r["blows_per_m"] for r in rows}
    moved = [r for r in rows if math.isfinite(count[id(r)])]
    refused = [r for r in rows if count[id(r)] == math.inf]
    cs = units.axis("static capacity", "force", [r["capacity"] for r in rows], sign=False)
    if moved:
        ax.plot([count[id(r)] for r in moved], cs([r["capacity"] for r in moved]), "o-", label="blow count")
    unfinished = [r for r in moved if not r["finished"]]
    if unfinished:
        ax.plot([count[id(r)] for r in unfinished], cs([r["capacity"] for r in unfinished]), "x",
                color="tab:red", label="pile not yet at rest")
    if refused:
        right = max([count[id(r)] for r in moved], default=1.0)
        ax.plot([right] * len(refused), cs([r["capacity"] for r in refused]), ">", color="tab:gray",
                label="refusal (set 0)")
    ax.set_xlabel(words)
    ax.set_ylabel(cs.label)
    ax.set_title("Bearing graph")
    ax.set_xlim(left=0)
    ok = [r for r in rows if math.isfinite(r["max_compression"])]
    ss = units.axis("largest stress in the pile, a magnitude", "stress",
                    [r[k] for r in ok for k in ("max_compression", "max_tension")], sign=False)
    ax2.plot(ss([r["max_compression"] for r in ok]), cs([r["capacity"] for r in ok]), "o-", label="largest compression")
    ax2.plot(ss([r["max_tension"] for r in ok]), cs([r["capacity"] for r in ok]), "s--", label="largest tension")
    ax2.set_xlabel(ss.label)
    ax2.set_title("Driving stresses")


def plot_bearing(directory, formats=("png", "svg")):
    """Draws bearing.png (and .svg) into the directory barimpact bearing
    wrote (nowhere else); returns the paths."""
    d = study_directory(directory, "bearing")
    rows = read_bearing(d)
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(10, 4.5), dpi=DPI, sharey=True, layout="constrained")
    _capacity_axes(ax, ax2, rows, units_of_runs(d, "SI"))
    for a in (ax, ax2):
        a.grid(True, alpha=0.3)
        a.legend()
    written = []
    _save(fig, d, "bearing", formats, written)
    return written
