"""Figures of a run (matplotlib, PNG and SVG), from a `Result` or from a
directory written by `barimpact run`:

- displacement: U(t), with the exact rigid-obstacle solution when the case is
  the paper's Example 1 family (its Figure 3);
- reaction: R(t), likewise with the exact reaction;
- energy: the budget E_kin, E_strain, E_obstacle, W_ext, D_visc and the
  balance E_kin + E_strain + E_obstacle - W_ext + D_visc;
- stress_map: sigma(x, t) over the field snapshots, where the waves and their
  reflections show;
- snapshots: u(x) at up to eight snapshot times (the paper's Figure 2);
- impacts: U and R with every contact episode shaded (Example 2's second
  impact, the paper's Figure 4).
"""
import csv
import json
import os
import tomllib
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

COLUMNS = ("t", "U", "V", "R", "E_kin", "E_strain", "E_obstacle", "W_ext", "D_visc", "D_contact", "D_plastic")
FIGSIZE = (8.0, 4.5)  # inches; at DPI 120 a PNG of 960 x 540 pixels
DPI = 120


class RunData:
    """What the figures need: history columns, field snapshots, case, summary."""

    def __init__(self, history, x, field_t, u, sigma, case, summary, body=None, eps_p=None):
        self.history = history  # dict column -> 1-D array
        self.x, self.field_t, self.u, self.sigma = x, field_t, u, sigma
        self.case, self.summary = case, summary
        self.body = body  # the body of each field row (None: one bar)
        self.eps_p = eps_p  # plastic strain at each snapshot and row (None: not written)


def load(run_dir):
    """Read a directory written by `barimpact run`."""
    d = Path(run_dir)
    if not (d / "history.csv").is_file():
        raise ValueError(f"{run_dir}: no history.csv (not a directory written by barimpact run)")
    with open(d / "history.csv") as stream:
        names = stream.readline().strip().split(",")
    h = np.loadtxt(d / "history.csv", delimiter=",", skiprows=1, ndmin=2)
    history = {name: h[:, i] for i, name in enumerate(names)}
    x = field_t = u = sigma = np.empty(0)
    body = None
    eps_p = None
    if (d / "fields.csv").is_file():
        with open(d / "fields.csv") as stream:
            header = stream.readline().strip().split(",")
        numbers = [i for i, name in enumerate(header) if name != "body"]
        f = np.loadtxt(d / "fields.csv", delimiter=",", skiprows=1, ndmin=2, usecols=numbers)
        if f.size:
            col = {name: k for k, name in enumerate(header[i] for i in numbers)}
            field_t = np.unique(f[:, 0])
            nodes = f.shape[0] // field_t.size
            x = f[:nodes, 1]
            u = f[:, 2].reshape(field_t.size, nodes)
            sigma = f[:, 4].reshape(field_t.size, nodes)
            if "eps_p" in col:
                eps_p = f[:, col["eps_p"]].reshape(field_t.size, nodes)
            if "body" in header:
                body = np.loadtxt(d / "fields.csv", delimiter=",", skiprows=1, ndmin=1, usecols=header.index("body"),
                                  dtype=str)[:nodes]
    case = tomllib.loads((d / "case.toml").read_text())
    summary = json.loads((d / "summary.json").read_text())
    return RunData(history, x, field_t, u, sigma, case, summary, body, eps_p)


def _from_result(result):
    history = {name: np.asarray(result[name]) for name in result.history_columns}
    return RunData(history, np.asarray(result.x), np.asarray(result.field_t), np.asarray(result.u),
                   np.asarray(result.sigma), tomllib.loads(result.case.to_toml()), result.summary,
                   np.asarray(result.field_body), np.asarray(result.eps_p))


def _number(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return None


def exact_parameters(case):
    """(L, a, rho, v0) when the case is the paper's Example 1 family (one
    elastic bar, uniform v0 < 0, no load, no initial strain, an obstacle at
    x = 0 without gap), else None."""
    bodies, near = case.get("body", []), case.get("near_end", {})
    if len(bodies) != 1 or bodies[0].get("kind") != "bar" or case.get("joint"):
        return None
    bar = bodies[0]
    v0 = _number(bar["velocity"])
    if (near.get("law", "free") not in ("elastic", "viscoelastic", "rigid", "cushion") or near.get("gap", 0) != 0
            or bar["viscosity"] != 0 or _number(case["load"]["body_force"]) != 0
            or case["load"].get("gravity", 0) != 0 or _number(bar["displacement"]) != 0 or v0 is None or v0 >= 0):
        return None
    return bar["length"], bar["modulus"] * bar["area"], bar["density"] * bar["area"], v0


def _snapshots(data, field, title, ylabel, out, name, formats, written):
    """A field over x at up to eight snapshot times, one colour per time across the bodies."""
    fig, ax = _figure(title)
    chosen = np.unique(np.linspace(0, data.field_t.size - 1, min(8, data.field_t.size)).round().astype(int))
    for i in chosen:
        for n, rows in enumerate(_body_rows(data)):
            line, = ax.plot(data.x[rows], field[i, rows], lw=1.2,
                            label=f"t = {data.field_t[i]:.3g}" if n == 0 else None,
                            color=None if n == 0 else line.get_color())
    ax.set_xlabel("x")
    ax.set_ylabel(ylabel)
    ax.legend(fontsize=8, ncol=2)
    _save(fig, out, name, formats, written)


def _body_rows(data):
    """Index arrays of each bar body's rows in the field snapshots."""
    if data.body is None or len(data.body) == 0:
        return [np.arange(data.x.size)]
    names = list(dict.fromkeys(data.body))
    return [np.flatnonzero(data.body == name) for name in names]


def _line_figures(data, out, formats, written):
    """Joint and end forces, gauges, mass motions: the columns a line adds."""
    h, t = data.history, data.history["t"]
    groups = (("joint_forces", "Joint and end forces (compression > 0)", "force",
               [c for c in h if c.startswith("joint.") and c.endswith(".force") or c == "far_end.force"]),
              ("gauges", "Gauges: axial force (tension > 0)", "force",
               [c for c in h if c.startswith("gauge.") and c.endswith(".force")]),
              ("masses", "Mass displacements", "u", [c for c in h if c.startswith("body.") and c.endswith(".u")]))
    for name, title, ylabel, columns in groups:
        if not columns:
            continue
        fig, ax = _figure(title)
        for c in columns:
            ax.plot(t, h[c], lw=1.0, label=c)
        ax.set_xlabel("t")
        ax.set_ylabel(ylabel)
        ax.legend(fontsize=8)
        _save(fig, out, name, formats, written)


def _blow_figures(data, out, formats, written):
    """A blow's figures: force and Z v at the gauge (the analyser's plot,
    compression and downward velocity positive), the toe's resistance, and
    the stress envelopes along the pile."""
    blow = data.summary.get("blow")
    if not blow:
        return
    h, t = data.history, data.history["t"]
    gauge = blow.get("gauge")
    if gauge and f"gauge.{gauge}.force" in h and blow.get("impedance"):
        z = blow["impedance"]
        fig, ax = _figure(f"Pile head ({gauge}): force and Z v (compression, downward > 0)")
        ax.plot(t * 1e3, -h[f"gauge.{gauge}.force"] / 1e3, lw=1.1, label="F")
        ax.plot(t * 1e3, -z * h[f"gauge.{gauge}.velocity"] / 1e3, lw=1.1, label=f"Z v, Z = {z / 1e3:.4g} kN s/m")
        ax.set_xlabel("t (ms)")
        ax.set_ylabel("kN")
        ax.legend(fontsize=8)
        _save(fig, out, "blow_head", formats, written)
    if data.case.get("near_end", {}).get("law") == "smith":
        _toe_figure(data, blow, out, formats, written)
    env = blow.get("envelope")
    if env and env.get("x"):
        fig, ax = _figure(f"Stress envelopes along the pile ({blow.get('pile', '')})")
        x = np.asarray(env["x"])
        ax.plot(np.asarray(env["compression"]) / 1e6, x, lw=1.2, label="largest compression")
        ax.plot(np.asarray(env["tension"]) / 1e6, x, lw=1.2, label="largest tension")
        ax.set_xlabel("stress (MPa)")
        ax.set_ylabel("x (m, toe at 0)")
        ax.legend(fontsize=8)
        _save(fig, out, "blow_envelopes", formats, written)


def _toe_figure(data, blow, out, formats, written):
    h, t = data.history, data.history["t"]
    fig, ax = _figure("Toe resistance and penetration")
    ax.plot(t * 1e3, h["R"] / 1e3, lw=1.1, color="tab:brown", label="toe force")
    ax.set_xlabel("t (ms)")
    ax.set_ylabel("toe force (kN)")
    right = ax.twinx()
    right.plot(t * 1e3, -h["U"] * 1e3, lw=1.0, color="tab:blue", label="toe penetration")
    if blow.get("set", 0) > 0:
        right.axhline(blow["set"] * 1e3, color="tab:blue", lw=0.8, ls="--", label=f"set {blow['set'] * 1e3:.3g} mm")
    right.set_ylabel("penetration (mm)")
    lines = ax.get_legend_handles_labels(), right.get_legend_handles_labels()
    ax.legend(lines[0][0] + lines[1][0], lines[0][1] + lines[1][1], fontsize=8)
    _save(fig, out, "blow_toe", formats, written)


def _figure(title, grid=True):
    fig, ax = plt.subplots(figsize=FIGSIZE, dpi=DPI, layout="constrained")
    ax.set_title(title)
    if grid:
        ax.grid(True, alpha=0.3)
    return fig, ax


def _save(fig, out, name, formats, written):
    for fmt in formats:
        path = out / f"{name}.{fmt}"
        fig.savefig(path, dpi=DPI)
        written.append(path)
    plt.close(fig)


def _shade_contacts(ax, summary):
    for i, c in enumerate(summary.get("contacts", [])):
        ax.axvspan(c["start"], c["end"], color="tab:orange", alpha=0.15, lw=0, label="contact" if i == 0 else None)


def mark_figures(run_dir):
    """List figures/ in the run directory's marker (.barimpact), so that the
    figures count as barimpact's when the directory is replaced by a rerun."""
    marker = Path(run_dir) / ".barimpact"
    try:
        data = json.loads(marker.read_text())
    except (OSError, ValueError):
        return  # not a directory barimpact wrote: nothing to mark
    if data.get("written_by") != "barimpact" or "figures" in data.get("entries", []):
        return
    data["entries"] = sorted(data.get("entries", []) + ["figures"])
    staging = marker.with_name(f".barimpact.{os.getpid()}")
    staging.write_text(json.dumps(data, indent=2) + "\n")
    staging.replace(marker)


def mark_written(directory, names):
    """List `names` in `directory`'s marker (.barimpact), as the command does,
    when the directory is barimpact's: already marked, or holding nothing
    but these files. A directory of someone else's is left unmarked."""
    directory = Path(directory)
    marker = directory / ".barimpact"
    try:
        data = json.loads(marker.read_text())
        if data.get("written_by") != "barimpact":
            return
    except OSError:
        present = {p.name for p in directory.iterdir()}
        if not present <= set(names):
            return  # someone else's files are here: not ours to claim
        data = {"written_by": "barimpact", "command": "plot",
                "note": "barimpact replaces or resumes this directory; it never touches what is not listed in entries",
                "entries": []}
    except ValueError:
        return
    data["entries"] = sorted(set(data.get("entries", [])) | set(names))
    staging = marker.with_name(f".barimpact.{os.getpid()}")
    staging.write_text(json.dumps(data, indent=2) + "\n")
    staging.replace(marker)


def plot(source, out=None, formats=("png", "svg")):
    """Write the figures of `source` (a Result, a RunData or a run directory)
    into `out` (default: DIR/figures for a directory, else ./figures).
    Returns the paths written."""
    if isinstance(source, (str, Path)):
        data = load(source)
        if out is None:
            out = Path(source) / "figures"
            mark_figures(source)
        out = Path(out)
    else:
        data = source if isinstance(source, RunData) else _from_result(source)
        out = Path(out) if out is not None else Path("figures")
    out.mkdir(parents=True, exist_ok=True)
    h, written = data.history, []
    t = h["t"]
    exact = exact_parameters(data.case)
    if exact is not None:
        from . import exact_example1
        fine_t = np.linspace(t[0], t[-1], 2001)
        ref = exact_example1(0.0, fine_t, *exact)
        ref_U = ref["u"]
    scheme = data.case["time"]["scheme"]
    near = data.case.get("near_end", {})
    law = near.get("law", "free")
    label = f"{scheme}, k = {near['stiffness']:g}" if "stiffness" in near else f"{scheme}, {law} near end"

    fig, ax = _figure("End displacement U(t) = u(0, t)")
    ax.plot(t, h["U"], ".", ms=3, label=label)
    if exact is not None:
        ax.plot(fine_t, ref_U, "k-", lw=1.2, label="exact, rigid obstacle")
    if law in ("elastic", "viscoelastic", "rigid", "cushion"):
        ax.axhline(-near.get("gap", 0.0), color="gray", lw=0.8, ls="--", label="obstacle face")
    ax.set_xlabel("t")
    ax.set_ylabel("U")
    ax.legend()
    _save(fig, out, "displacement", formats, written)

    fig, ax = _figure("Reaction of the obstacle R(t)")
    ax.plot(t, h["R"], "-", lw=0.9, label=label)
    if exact is not None:
        ax.plot(fine_t, ref["R"], "k-", lw=1.2, label="exact, rigid obstacle")
    ax.set_xlabel("t")
    ax.set_ylabel("R")
    ax.legend()
    _save(fig, out, "reaction", formats, written)

    fig, ax = _figure("Energy budget")
    for name, label in (("E_kin", "kinetic"), ("E_strain", "strain"), ("E_obstacle", "obstacle"),
                        ("W_ext", "external work"), ("D_visc", "viscous dissipation"),
                        ("D_contact", "contact dissipation"), ("D_plastic", "plastic work")):
        if name in h and (name not in ("D_contact", "D_plastic") or np.any(h[name] != 0)):
            ax.plot(t, h[name], lw=1.0, label=label)
    balance = (h["E_kin"] + h["E_strain"] + h["E_obstacle"] - h["W_ext"] + h["D_visc"] + h.get("D_contact", 0.0) +
               h.get("D_plastic", 0.0))
    ax.plot(t, balance, "k-", lw=1.8, label="balance: kin + strain + obstacle - work + dissipation")
    ax.set_xlabel("t")
    ax.set_ylabel("energy")
    ax.legend(fontsize=8, loc="best")
    _save(fig, out, "energy", formats, written)

    if data.field_t.size >= 2:
        fig, ax = _figure("Stress sigma(x, t)", grid=False)
        limit = float(np.max(np.abs(data.sigma))) or 1.0
        for rows in _body_rows(data):  # one map per bar body: the gaps between them stay blank
            mesh = ax.pcolormesh(data.x[rows], data.field_t, data.sigma[:, rows], cmap="RdBu_r", vmin=-limit,
                                 vmax=limit, shading="nearest")
        fig.colorbar(mesh, ax=ax, label="sigma (tension > 0)")
        ax.set_xlabel("x")
        ax.set_ylabel("t")
        _save(fig, out, "stress_map", formats, written)

    eps_p = getattr(data, "eps_p", None)
    if data.field_t.size >= 2 and eps_p is not None and eps_p.size and np.any(eps_p != 0):
        fig, ax = _figure("Plastic strain eps_p(x, t)", grid=False)
        limit = float(np.max(np.abs(eps_p)))
        for rows in _body_rows(data):
            mesh = ax.pcolormesh(data.x[rows], data.field_t, eps_p[:, rows], cmap="PuOr_r", vmin=-limit, vmax=limit,
                                 shading="nearest")
        fig.colorbar(mesh, ax=ax, label="eps_p (tension > 0)")
        ax.set_xlabel("x")
        ax.set_ylabel("t")
        _save(fig, out, "plastic_map", formats, written)
        _snapshots(data, eps_p, "Plastic strain eps_p(x) at snapshot times", "eps_p", out, "plastic_snapshots",
                   formats, written)

    if data.field_t.size >= 1:
        _snapshots(data, data.u, "Displacement u(x) at snapshot times", "u", out, "snapshots", formats, written)

    contacts = data.summary.get("contacts", [])
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=FIGSIZE, dpi=DPI, layout="constrained")
    fig.suptitle(f"Impacts: {len(contacts)} contact episode{'s' if len(contacts) != 1 else ''}")
    top.plot(t, h["U"], lw=1.0)
    top.set_ylabel("U")
    bottom.plot(t, h["R"], lw=1.0, color="tab:red")
    bottom.set_ylabel("R")
    bottom.set_xlabel("t")
    for ax in (top, bottom):
        _shade_contacts(ax, data.summary)
        ax.grid(True, alpha=0.3)
    if contacts:
        top.legend(loc="best")
    _save(fig, out, "impacts", formats, written)
    _line_figures(data, out, formats, written)
    _blow_figures(data, out, formats, written)
    mark_written(out, [Path(p).name for p in written])
    return written
