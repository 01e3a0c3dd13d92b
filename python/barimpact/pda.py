"""The figures of a `barimpact pda` directory (pda.csv, summary.json): the
analyser's plot of force and velocity times impedance against time with
marks at t1 and t2, and the waves down and up at the gauges."""
from .plot import _figure, _line, _save, draw_into, read_table_summary, study_directory
from .style import Units


def read_pda(directory):
    """pda.csv as a dict of numpy arrays, and summary.json."""
    return read_table_summary(directory, "pda.csv")


def _against_time(h, s, title, series, words, sign, out, name, formats, written):
    """Columns of pda.csv against time, with t1 and t2 marked, in the
    record's units. `series`: (column, colour, label) each."""
    units = Units((s.get("units") or {}).get("system", "SI"))
    ts = units.time(h["t"])
    fs = units.axis(words, "force", [h[c] for c, _, _ in series], sign=sign)
    fig, ax = _figure(title)
    for column, colour, label in series:
        _line(ax, ts(h["t"]), fs(h[column]), color=colour, lw=1.2, label=label)
    for key, style in (("t1", "--"), ("t2", ":")):
        ax.axvline(ts(s[key]), color="0.4", lw=0.9, ls=style, label=f"{key} = {ts.text(s[key])}")
    ax.axhline(0, color="0.6", lw=0.6)
    ax.set_xlabel(ts.label)
    ax.set_ylabel(fs.label)
    ax.legend(fontsize=8)
    _save(fig, out, name, formats, written)


def plot_pda(directory, formats=("png", "svg")):
    """Draws the two figures into the directory barimpact pda fills or wrote
    (nowhere else); returns their paths: force_velocity (the analyser's
    plot: F and Z v proportional until the first reflections) and waves."""
    out = study_directory(directory, "pda")
    h, s = read_pda(out)
    rmx = Units((s.get("units") or {}).get("system", "SI")).axis("", "force", s["rmx"])
    written = []
    _against_time(h, s, "Force and impedance times velocity at the gauges",
                  (("force", "k", "force F"), ("velocity_z", "tab:blue", "Z v")),
                  "force, Z v", "compression +, Z v: down +", out, "force_velocity", formats, written)
    _against_time(h, s, f"Waves at the gauges (RMX {rmx.text(s['rmx'])}, J_c = {s.get('damping', 0.5):g})",
                  (("wave_down", "tab:red", "wave down Wd = (F + Z v)/2"),
                   ("wave_up", "tab:green", "wave up Wu = (F - Z v)/2")),
                  "wave force", "compression +", out, "waves", formats, written)
    return written


def plot_pda_into(staging, shown, formats=("png", "svg")):
    """plot_pda into the staging directory of `shown` (see draw_into)."""
    return draw_into(plot_pda, staging, shown, formats)
