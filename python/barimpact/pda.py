"""The figures of a `barimpact pda` directory (pda.csv, summary.json): the
analyser's plot of force and velocity times impedance against time with
marks at t1 and t2, and the waves down and up at the gauges."""
from .plot import _figure, _save, draw_into, read_table_summary, study_directory


def read_pda(directory):
    """pda.csv as a dict of numpy arrays, and summary.json."""
    return read_table_summary(directory, "pda.csv")


def _against_time(h, s, title, series, ylabel, out, name, formats, written):
    """Columns of pda.csv in kN against t in ms, with t1 and t2 marked.
    `series`: (column, colour, label) each."""
    t = 1e3 * h["t"]
    fig, ax = _figure(title)
    for column, colour, label in series:
        ax.plot(t, 1e-3 * h[column], color=colour, lw=1.2, label=label)
    for key, style in (("t1", "--"), ("t2", ":")):
        ax.axvline(1e3 * s[key], color="0.4", lw=0.9, ls=style, label=f"{key} = {1e3 * s[key]:.4g} ms")
    ax.axhline(0, color="0.6", lw=0.6)
    ax.set_xlabel("t (ms)")
    ax.set_ylabel(ylabel)
    ax.legend(fontsize=8)
    _save(fig, out, name, formats, written)


def plot_pda(directory, formats=("png", "svg")):
    """Draws the two figures into the directory barimpact pda fills or wrote
    (nowhere else); returns their paths: force_velocity (the analyser's
    plot: F and Z v proportional until the first reflections) and waves."""
    out = study_directory(directory, "pda")
    h, s = read_pda(out)
    written = []
    _against_time(h, s, "Force and velocity times impedance at the gauges",
                  (("force", "k", "force F"), ("velocity_z", "tab:blue", "Z v")),
                  "kN (compression, downward velocity > 0)", out, "force_velocity", formats, written)
    _against_time(h, s, f"Waves at the gauges (RMX {1e-3 * s['rmx']:.4g} kN, J_c = {s.get('damping', 0.5):g})",
                  (("wave_down", "tab:red", "wave down Wd = (F + Z v)/2"),
                   ("wave_up", "tab:green", "wave up Wu = (F - Z v)/2")),
                  "kN", out, "waves", formats, written)
    return written


def plot_pda_into(staging, shown, formats=("png", "svg")):
    """plot_pda into the staging directory of `shown` (see draw_into)."""
    return draw_into(plot_pda, staging, shown, formats)
