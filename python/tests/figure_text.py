"""Reading the figures' text from matplotlib objects (the `drawn` fixture of
conftest.py, by barimpact.plot's SAVE_HOOKS), and the style's promises checked on it."""
import re

import numpy as np

# A history column's raw name: joint.NAME.force, gauge.NAME.strain, body.NAME.u, far_end.force, ...
RAW_COLUMN = re.compile(r"\b(joint|gauge|body|hammer)\.[\w-]+\.\w+|\bfar_end\.\w+")
UNIT = re.compile(r"\[([^\]]+)\]$")
# Axis labels that hold no physical quantity with a unit: counts, ratios, scales.
UNITLESS = ("blows per 250 mm", "blows/ft", "equilibrium ratio")


def figure_texts(fig):
    """What a figure holds, per axes: its title, labels, scales, legend texts
    and lines (label, x, y), the figure's title beside each."""
    suptitle = fig._suptitle.get_text() if fig._suptitle else ""
    return [{"suptitle": suptitle, "title": ax.get_title(), "xlabel": ax.get_xlabel(), "ylabel": ax.get_ylabel(),
             "xscale": ax.get_xscale(), "yscale": ax.get_yscale(), "xticks": [float(x) for x in ax.get_xticks()],
             "ylim": tuple(float(y) for y in ax.get_ylim()),
             "legend": [t.get_text() for t in ax.get_legend().get_texts()] if ax.get_legend() else [],
             "lines": [(ln.get_label(), np.asarray(ln.get_xdata(), float), np.asarray(ln.get_ydata(), float))
                       for ln in ax.get_lines()],
             "meshes": [m.get_array() for m in ax.collections if hasattr(m, "get_coordinates")]}
            for ax in fig.axes]


def texts(axes):
    """Every title, label and legend text of a figure's axes."""
    return [t for ax in axes for t in (ax["suptitle"], ax["title"], ax["xlabel"], ax["ylabel"], *ax["legend"]) if t]


def raw_names(figures):
    """(figure, text) of every text that shows a raw history column name."""
    return [(name, t) for name, axes in figures.items() for t in texts(axes) if RAW_COLUMN.search(t)]


def time_units(axes):
    """The units of a figure's time axes and of the times in its legends ("t1 = 2.1 ms")."""
    labels = [label.split(",")[0] for ax in axes for label in (ax["xlabel"], ax["ylabel"]) if label.startswith("time")]
    units = {m.group(1) for m in map(UNIT.search, labels) if m}
    for t in texts(axes):
        units.update(re.findall(r"\bt\w* = [-\d.e+]+ (µs|ms|s)\b", t))
    return units


def axes_without_unit(figures):
    """(figure, label) of every axis label naming no unit, but those of UNITLESS."""
    return [(name, label) for name, axes in figures.items() for ax in axes for label in (ax["xlabel"], ax["ylabel"])
            if label and not label.startswith(UNITLESS) and not re.search(r"\[[^\]]+\]", label)]
