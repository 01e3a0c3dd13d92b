"""Figures of a `barimpact converge` directory: error against h (or the
varied key) on log-log axes, and error against CPU time (work-precision),
one line per scheme."""
import csv
import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from .plot import DPI, FIGSIZE  # noqa: E402


def _float(text):
    try:
        v = float(text)
        return v if math.isfinite(v) else None
    except ValueError:
        return None


def plot_study(directory, formats=("png", "svg")):
    d = Path(directory)
    rows = list(csv.DictReader(open(d / "convergence.csv")))
    schemes = list(dict.fromkeys(r["scheme"] for r in rows))
    varied = any(r["value"] for r in rows) and all(_float(r["value"]) is not None for r in rows if r["value"])
    written = []
    for name, xkey, xlabel in (("convergence", "value" if varied else "h", "varied value" if varied else "h"),
                               ("work_precision", "cpu_seconds", "CPU time (s)")):
        fig, ax = plt.subplots(figsize=FIGSIZE, dpi=DPI, layout="constrained")
        for scheme in schemes:
            pts = [(_float(r[xkey]), _float(r["error_U_max"])) for r in rows if r["scheme"] == scheme]
            pts = [(x, y) for x, y in pts if x and y and x > 0 and y > 0]
            if pts:
                ax.loglog(*zip(*pts), "o-", label=scheme)
        ax.set_xlabel(xlabel)
        ax.set_ylabel("max error of U")
        ax.set_title("Convergence" if name == "convergence" else "Work-precision")
        ax.grid(True, which="both", alpha=0.3)
        if ax.lines:
            ax.legend()
        for fmt in formats:
            fig.savefig(d / f"{name}.{fmt}", dpi=DPI)
            written.append(d / f"{name}.{fmt}")
        plt.close(fig)
    return written
