"""The figures of a `barimpact hopkinson` directory (hopkinson.csv, summary.json):
the aligned waves, the stress-strain curves of the three analyses, the strain
rate against strain, and the specimen's equilibrium against time."""
import numpy as np

from .plot import _figure, _save, draw_into, read_table_summary, study_directory


def read_hopkinson(directory):
    """hopkinson.csv as a dict of numpy arrays (nan where a cell is missing), and summary.json."""
    return read_table_summary(directory, "hopkinson.csv")


def _waves_figure(h, out, formats, written):
    """The three waves at the specimen's faces, and the front face's sum."""
    t = h["t"]
    fig, ax = _figure("The three waves, moved to the specimen's faces")
    for name, label in (("incident", "incident"), ("reflected", "reflected"), ("transmitted", "transmitted")):
        if name in h:
            ax.plot(t, h[name], lw=1.2, label=label)
    if "incident" in h and "reflected" in h:
        ax.plot(t, h["incident"] + h["reflected"], "k--", lw=0.9, label="incident + reflected (front face)")
    ax.axhline(0, color="0.6", lw=0.6)
    ax.set_xlabel("t (0: the incident foot at the specimen)")
    ax.set_ylabel("gauge strain (tension > 0)")
    ax.legend(fontsize=8)
    _save(fig, out, "waves", formats, written)


def _stress_strain_figure(h, fit, out, formats, written):
    """The three analyses' curves, with the fitted modulus and yield when the fit found them."""
    fig, ax = _figure("Specimen stress-strain")
    ax.plot(h["strain_1w"], h["stress_1w"], lw=1.2, label="1-wave: transmitted force, reflected strain")
    ax.plot(h["strain_3w"], h["stress_2w"], lw=1.2, label="2-wave: front-face force (3-wave strain)")
    ax.plot(h["strain_3w"], h["stress_3w"], "k", lw=1.6, label="3-wave: mean force, faces' velocities")
    if fit.get("modulus"):
        e, e0 = fit["modulus"], fit["strain_intercept"]
        top = np.nanmax(h["stress_3w"])
        eps = np.array([e0, e0 + top / e])
        ax.plot(eps, e * (eps - e0), ":", color="tab:red", lw=1.0, label=f"fit: modulus {e:.4g}")
        if fit.get("yield_stress"):
            ax.plot(eps + 0.002, e * (eps - e0), ":", color="0.5", lw=1.0, label="0.2% offset")
            ax.plot([fit["yield_strain"]], [fit["yield_stress"]], "o", color="tab:red",
                    label=f"yield {fit['yield_stress']:.4g}")
    ax.set_xlabel("engineering strain (compression > 0)")
    ax.set_ylabel("engineering stress (compression > 0)")
    ax.set_xlim(left=min(0.0, np.nanmin(h["strain_3w"])))
    ax.set_ylim(bottom=min(0.0, np.nanmin(h["stress_3w"])))
    ax.legend(fontsize=8)
    _save(fig, out, "stress_strain", formats, written)


def _strain_rate_figure(h, out, formats, written):
    fig, ax = _figure("Strain rate")
    ax.plot(h["strain_1w"], h["strain_rate_1w"], lw=1.2, label="1-wave: 2 c0 eps_r / L_s")
    ax.plot(h["strain_3w"], h["strain_rate_3w"], "k", lw=1.4, label="3-wave: c0 (eps_r + eps_t - eps_i) / L_s")
    ax.set_xlabel("engineering strain (compression > 0)")
    ax.set_ylabel("strain rate")
    ax.legend(fontsize=8)
    _save(fig, out, "strain_rate", formats, written)


def _equilibrium_figure(h, s, out, formats, written):
    """The equilibrium measure against time, the two forces on a second axis
    (one legend for both axes)."""
    t = h["t"]
    fig, ax = _figure("Specimen equilibrium (where both forces pass 5% of their peak)")
    ax.plot(t, h["equilibrium"], "k", lw=1.2, label="2 (F_front - F_back) / (F_front + F_back)")
    ax.axhspan(-0.05, 0.05, color="tab:green", alpha=0.15, label="within 5%")
    if s.get("equilibrium_from") is not None:
        ax.axvline(s["equilibrium_from"], color="tab:green", lw=1.0, ls="--", label="from here to the peak stress")
    ax.set_ylim(-0.5, 0.5)
    ax.set_xlabel("t")
    ax.set_ylabel("equilibrium")
    ax2 = ax.twinx()
    ax2.plot(t, h["force_front"], color="tab:blue", lw=0.8, alpha=0.6, label="force front")
    ax2.plot(t, h["force_back"], color="tab:orange", lw=0.8, alpha=0.6, label="force back")
    ax2.set_ylabel("force (compression > 0)")
    lines = ax.get_legend_handles_labels()
    lines2 = ax2.get_legend_handles_labels()
    ax.legend(lines[0] + lines2[0], lines[1] + lines2[1], fontsize=8, loc="lower right")
    _save(fig, out, "equilibrium", formats, written)


def plot_hopkinson(directory, formats=("png", "svg")):
    """Draws the four figures into the directory barimpact hopkinson fills
    or wrote (nowhere else); returns their paths."""
    out = study_directory(directory, "hopkinson")
    h, s = read_hopkinson(out)
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
