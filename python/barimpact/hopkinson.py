"""The figures of a `barimpact hopkinson` directory (hopkinson.csv, summary.json),
in its figures/: the aligned waves, the stress-strain curves of the three analyses, the strain
rate against strain, and the specimen's equilibrium against time."""
import numpy as np

from .plot import _figure, _line, _save, draw_into, prepare_figures, read_table_summary, study_directory
from .style import Units, drawn_sign


def read_hopkinson(directory):
    """hopkinson.csv as a dict of numpy arrays (nan where a cell is missing), and summary.json."""
    return read_table_summary(directory, "hopkinson.csv")


# Hopkinson analyses are in SI (docs/hopkinson.md): their figures in the engineering units.
UNITS = Units("SI")
FIGURES = ("waves", "stress_strain", "strain_rate", "equilibrium")
WAVES = (("incident", "incident wave (incident bar gauge)"), ("reflected", "reflected wave (incident bar gauge)"),
         ("transmitted", "transmitted wave (transmission bar gauge)"))


def _waves_figure(h, out, formats, written):
    """The three waves at the specimen's faces, and the front face's sum,
    compression positive (hopkinson.csv's gauge strains are tension positive)."""
    ts = UNITS.time(h["t"])
    ss = UNITS.axis("bar strain", "strain", [h[n] for n, _ in WAVES if n in h])
    fig, ax = _figure("The three waves, moved to the specimen's faces")
    for name, label in WAVES:
        if name in h:
            _line(ax, ts(h["t"]), ss(drawn_sign(name) * h[name]), lw=1.2, label=label)
    if "incident" in h and "reflected" in h:
        _line(ax, ts(h["t"]), ss(-(h["incident"] + h["reflected"])), "k--", lw=0.9,
                label="incident + reflected (front face)")
    ax.axhline(0, color="0.6", lw=0.6)
    ax.set_xlabel(f"{ts.label}, 0 at the incident wave's foot")
    ax.set_ylabel(ss.label)
    ax.legend(fontsize=8)
    _save(fig, out, "waves", formats, written)


def _fit_lines(ax, fit, top, ss):
    """The fitted modulus, the 0.2% offset line and the yield point."""
    e, e0 = fit["modulus"], fit["strain_intercept"]
    eps = np.array([e0, e0 + top / e])
    modulus = UNITS.axis("", "stress", e)
    ax.plot(eps, ss(e * (eps - e0)), ":", color="tab:red", lw=1.0, label=f"fit: modulus {modulus.text(e)}")
    if fit.get("yield_stress"):
        ax.plot(eps + 0.002, ss(e * (eps - e0)), ":", color="0.5", lw=1.0, label="0.2% offset")
        ax.plot([fit["yield_strain"]], ss([fit["yield_stress"]]), "o", color="tab:red",
                label=f"yield {ss.text(fit['yield_stress'])}")


def _stress_strain_figure(h, fit, out, formats, written):
    """The three analyses' curves, with the fitted modulus and yield when the fit found them."""
    ss = UNITS.axis("engineering stress", "stress", [h["stress_1w"], h["stress_2w"], h["stress_3w"]])
    fig, ax = _figure("Specimen stress-strain")
    _line(ax, h["strain_1w"], ss(h["stress_1w"]), lw=1.2, label="1-wave: transmitted force, reflected strain")
    _line(ax, h["strain_3w"], ss(h["stress_2w"]), lw=1.2, label="2-wave: front-face force (3-wave strain)")
    _line(ax, h["strain_3w"], ss(h["stress_3w"]), "k", lw=1.6, label="3-wave: mean force, faces' velocities")
    if fit.get("modulus"):
        _fit_lines(ax, fit, np.nanmax(h["stress_3w"]), ss)
    ax.set_xlabel(UNITS.axis("engineering strain", "strain").label)
    ax.set_ylabel(ss.label)
    ax.set_xlim(left=min(0.0, np.nanmin(h["strain_3w"])))
    ax.set_ylim(bottom=min(0.0, np.nanmin(ss(h["stress_3w"]))))
    ax.legend(fontsize=8)
    _save(fig, out, "stress_strain", formats, written)


def _strain_rate_figure(h, out, formats, written):
    fig, ax = _figure("Specimen strain rate")
    _line(ax, h["strain_1w"], h["strain_rate_1w"], lw=1.2, label="1-wave: 2 c0 eps_r / L_s")
    _line(ax, h["strain_3w"], h["strain_rate_3w"], "k", lw=1.4, label="3-wave: c0 (eps_r + eps_t - eps_i) / L_s")
    ax.set_xlabel(UNITS.axis("engineering strain", "strain").label)
    ax.set_ylabel(UNITS.axis("strain rate", "strain_rate", sign="compression +").label)
    ax.legend(fontsize=8)
    _save(fig, out, "strain_rate", formats, written)


def _equilibrium_figure(h, s, out, formats, written):
    """The equilibrium measure against time, the two forces on a second axis
    (one legend for both axes)."""
    ts = UNITS.time(h["t"])
    fs = UNITS.axis("force on the specimen", "force", [h["force_front"], h["force_back"]])
    fig, ax = _figure("Specimen equilibrium (where both forces pass 5% of their peak)")
    _line(ax, ts(h["t"]), h["equilibrium"], "k", lw=1.2, label="2 (F_front - F_back) / (F_front + F_back)")
    ax.axhspan(-0.05, 0.05, color="tab:green", alpha=0.15, label="within 5%")
    if s.get("equilibrium_from") is not None:
        ax.axvline(ts(s["equilibrium_from"]), color="tab:green", lw=1.0, ls="--", label="from here to the peak stress")
    ax.set_ylim(-0.5, 0.5)
    ax.set_xlabel(ts.label)
    ax.set_ylabel("equilibrium ratio")
    ax2 = ax.twinx()
    _line(ax2, ts(h["t"]), fs(h["force_front"]), color="tab:blue", lw=0.8, alpha=0.6, label="front face force")
    _line(ax2, ts(h["t"]), fs(h["force_back"]), color="tab:orange", lw=0.8, alpha=0.6, label="back face force")
    ax2.set_ylabel(fs.label)
    lines = ax.get_legend_handles_labels()
    lines2 = ax2.get_legend_handles_labels()
    ax.legend(lines[0] + lines2[0], lines[1] + lines2[1], fontsize=8, loc="lower right")
    _save(fig, out, "equilibrium", formats, written)


def plot_hopkinson(directory, formats=("png", "svg")):
    """Draws the four figures into DIR/figures of the directory barimpact
    hopkinson fills or wrote (nowhere else); returns their paths."""
    d = study_directory(directory, "hopkinson")
    h, s = read_hopkinson(d)
    out = prepare_figures(d / "figures", FIGURES, formats)  # marked as barimpact's: a rerun replaces it
    written = []
    _waves_figure(h, out, formats, written)
    _stress_strain_figure(h, s.get("fit") or {}, out, formats, written)
    _strain_rate_figure(h, out, formats, written)
    _equilibrium_figure(h, s, out, formats, written)
    return written


def plot_hopkinson_into(staging, shown, formats=("png", "svg")):
    """plot_hopkinson into the staging directory of `shown`, the directory
    the results are moved to once whole (see draw_into)."""
    return draw_into(plot_hopkinson, staging, shown, formats)
