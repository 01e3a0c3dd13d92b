"""Properties of the command line over random valid small cases (hypothesis).

Every case is a TOML file run by `barimpact run CASE --out DIR` in a child
process. Whatever the case, the run either completes (exit 0, summary.json
"complete": true) or stops with exit 2 (refused: one line on stderr, nothing
written) or 3 (non-finite: one line, summary.json "complete": false); never a
signal, never exit 1, never a sanitizer report. For the configurations that
docs/methods.md proves to conserve energy, the budget holds (see
`energy_claim` and `check_energy` for the bounds and why).

Deterministic by default (derandomize, no example database): the "ci"
profile. HYPOTHESIS_PROFILE=explore draws fresh, many more examples.
"""
import json
import math
import os
import subprocess

import numpy as np
from hypothesis import HealthCheck, event, given, settings, strategies as st

from conftest import CLI

settings.register_profile("ci", max_examples=100, deadline=None, derandomize=True, database=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("explore", max_examples=2000, deadline=None, database=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))

SCHEMES = ["paper", "newmark", "central-difference", "characteristic", "mass-redistribution", "paoli-schatzman",
           "moreau-jean"]
# Which obstacles each scheme accepts (docs/methods.md); another pairing is refused (exit 2).
FITS = {
    "none": SCHEMES,
    "elastic": ["paper", "newmark", "central-difference"],
    "viscoelastic": ["paper", "newmark", "central-difference"],
    "rigid": ["central-difference", "characteristic", "mass-redistribution", "paoli-schatzman", "moreau-jean"],
}
ELASTIC_BAR_ONLY = {"characteristic", "mass-redistribution"}
# The schemes with an energy claim in contact (`energy_claim`) drawn most.
CONSERVING_FITS = {
    "none": SCHEMES,
    "elastic": ["paper"],
    "rigid": ["moreau-jean", "moreau-jean", "moreau-jean", "central-difference", "characteristic",
              "mass-redistribution", "paoli-schatzman"],
}

# Row 1 on, without contact (or through Moreau-Jean's impacts at theta = 1/2,
# e = 1), a conserving scheme keeps E_kin + E_strain + E_obstacle - W_ext +
# D_visc to round-off: docs/methods.md and tests/verification (1e-10 of the
# budget over 600 steps, 5e-10 over 10^4 for the paper's three-level form,
# which loses digits to cancellation every step). These runs take at most
# 300 steps, at Courant numbers down to 0.05 (more cancellation); measured
# over 1500 random conserving cases: at most 2.7e-11 of the budget
# (mass redistribution; the paper's scheme 1.4e-11). The claim: 1e-9.
ROUND_OFF = 1e-9
# The paper's scheme against an elastic obstacle splits the penalty into an
# implicit linear half and an explicit |.| half: they cancel, and the
# explicit half's work is returned, only as dt -> 0 (docs/methods.md: the
# budget's error falls at order about 2 in dt at fixed h and k; for
# k dt^2 / (rho h) well above 1 energy grows). So the claim is a bound in
# that number, on the budget's size (the largest |E_kin| + |E_strain| +
# |E_obstacle| + |W_ext| + |D_visc| of the run, not E(0): a load can pour in
# far more than the bar starts with). Measured with k dt^2 / (rho h) <= 0.01:
# at most 1.1 k dt^2 / (rho h) of the budget over 945 random cases, 2.3 in
# the worst case hypothesis found (2 elements, two contacts: chattering adds
# up). The claim: 5 k dt^2 / (rho h), i.e. at most 5% of the budget.
PENALTY_REGIME = 0.01
PENALTY_FACTOR = 5.0


def number(x):
    """A float as TOML (repr always has a '.' or an exponent)."""
    return repr(float(x))


def _initial_and_load(draw, length, far_end):
    """[initial] and [load]. The bar moves towards the obstacle at 0.1 .. 2
    with a smooth shape on top (so E(0) > 0); a clamped end x = L must start
    at rest there."""
    speed = draw(st.floats(0.1, 2.0))
    shape = draw(st.sampled_from(["", "ramp", "sine"]))
    b = number(draw(st.floats(-0.5, 0.5)))
    L = number(length)
    velocity = {"": f"-{number(speed)}", "ramp": f"-{number(speed)} * (1 + {b} * x / {L})",
                "sine": f"-{number(speed)} + {b} * sin(_pi * x / {L})"}[shape]
    displacement = draw(st.sampled_from(["0", f"{number(draw(st.floats(-0.05, 0.05)))} * sin(_pi * x / {L})"]))
    if far_end == "clamped":
        velocity = f"({velocity}) * (1 - x / {L})"
        displacement = f"({displacement}) * (1 - x / {L})"
    f0 = number(draw(st.floats(-1.0, 1.0)))
    force = draw(st.sampled_from(["0", "0", f0, f"{f0} * sin(3 * t)", f"{f0} * cos(x) * t"]))
    return dict(velocity=f'"{velocity}"', displacement=f'"{displacement}"'), dict(body_force=f'"{force}"')


def _obstacle(draw, kind):
    """[obstacle]: a gap of 0 as often as not, a stiffness of 1 .. 1000."""
    obstacle = dict(kind=f'"{kind}"', gap=number(draw(st.sampled_from([0.0, draw(st.floats(0.0, 0.1))]))))
    obstacle["stiffness"] = number(10 ** draw(st.floats(0.0, 3.0)))
    if kind == "viscoelastic":
        obstacle["viscosity"] = number(draw(st.floats(0.0, 1.0)))
    return obstacle


def _scheme_parameters(draw, scheme, kind, conserving):
    """The scheme's own [time] keys: mostly the defaults, now and then any;
    `conserving`: the values `energy_claim` covers."""
    params = {}
    if scheme == "paper":
        alpha = draw(st.sampled_from([0.25, 0.25, 0.0, 0.5, draw(st.floats(0.0, 0.5))]))
        params["alpha"] = number(0.25 if conserving and kind == "elastic" else alpha)
        params["lambda"] = number(0.0 if conserving else draw(st.sampled_from([0.0, 0.0, draw(st.floats(0.0, 1.0))])))
    elif scheme == "newmark":
        if conserving or draw(st.booleans()):
            params["beta"], params["gamma"] = "0.25", "0.5"  # trapezoidal
        else:
            params["beta"], params["gamma"] = number(draw(st.floats(0.0, 0.5))), number(draw(st.floats(0.5, 1.0)))
    elif scheme == "moreau-jean":
        params["theta"] = number(0.5 if conserving else draw(st.sampled_from([0.5, 0.5, draw(st.floats(0.5, 1.0))])))
        params["restitution"] = number(1.0 if conserving
                                       else draw(st.sampled_from([1.0, 0.0, draw(st.floats(0.0, 1.0))])))
    elif scheme == "paoli-schatzman":
        params["restitution"] = number(draw(st.sampled_from([0.0, draw(st.floats(0.0, 1.0))])))
    return params


@st.composite
def cases(draw, conserving=False):
    """A valid small case; `conserving`: one of the configurations of
    `energy_claim` (elastic bar, no shift, the conserving parameters)."""
    c = {}
    length = draw(st.floats(0.5, 2.0))
    density = draw(st.floats(0.5, 2.0))
    stiffness = draw(st.floats(0.5, 2.0))
    elements = draw(st.integers(2, 60))
    far_end = draw(st.sampled_from(["free", "free", "clamped"]))
    kind = draw(st.sampled_from(["none", "elastic", "rigid"] + ([] if conserving else ["viscoelastic"])))
    # Mostly a scheme that fits the obstacle; now and then any (refused: exit 2).
    if conserving:
        scheme = draw(st.sampled_from(CONSERVING_FITS[kind]))
    else:
        scheme = draw(st.sampled_from(FITS[kind] if draw(st.integers(0, 9)) else SCHEMES))
    viscous = not conserving and scheme not in ELASTIC_BAR_ONLY and draw(st.integers(0, 3)) == 0
    c["bar"] = dict(length=number(length), density=number(density), stiffness=number(stiffness),
                    viscosity=number(draw(st.floats(0.001, 0.1)) if viscous else 0.0), elements=str(elements),
                    far_end=f'"{far_end}"')

    c["initial"], c["load"] = _initial_and_load(draw, length, far_end)
    c["obstacle"] = _obstacle(draw, kind)

    h = length / elements
    wave = math.sqrt(stiffness / density)
    steps = draw(st.integers(5, 300))
    time = dict(scheme=f'"{scheme}"')
    if scheme == "characteristic":
        time["end"] = number(steps * h / wave)  # the scheme sets dt = h/c
    else:
        if kind == "elastic" and (conserving or draw(st.booleans())):
            # k dt^2 / (rho h) in 1e-4 .. 0.01, where the penalty's energy error is claimed.
            dt = math.sqrt(10 ** draw(st.floats(-4.0, -2.0)) * density * h / float(c["obstacle"]["stiffness"]))
        else:
            dt = draw(st.floats(0.05, 1.0 if conserving else 2.0)) * h / wave  # Courant number
        time["step"] = number(dt)
        time["end"] = number(steps * dt)
    time.update(_scheme_parameters(draw, scheme, kind, conserving))
    c["time"] = time
    c["output"] = dict(every="1", fields_at=draw(st.sampled_from(["[]", f"[{time['end']}]"])))
    return c


def to_toml(c):
    return "".join(f"[{section}]\n" + "".join(f"{k} = {v}\n" for k, v in keys.items()) + "\n"
                   for section, keys in c.items())


def value(c, section, key, default):
    v = c[section].get(key)
    return default if v is None else float(v)


def energy_claim(c, summary):
    """What docs/methods.md guarantees for this run's budget: "exact" (round-off
    from row 1 on), "penalty" (the paper's O(dt^2) penalty error), or None."""
    scheme = c["time"]["scheme"].strip('"')
    kind = c["obstacle"]["kind"].strip('"')
    if float(c["bar"]["viscosity"]) > 0 or kind == "viscoelastic" or value(c, "time", "lambda", 0.0) != 0:
        return None
    theta, e = value(c, "time", "theta", 0.5), value(c, "time", "restitution", 0.0)
    conserving = {
        "paper": True,  # every alpha (the alpha term is in E_strain)
        "newmark": c["time"].get("beta") == "0.25" and c["time"].get("gamma") == "0.5",
        "central-difference": True,  # exit 0: within the enforced stable limit
        "paoli-schatzman": True,
        "moreau-jean": theta == 0.5,
        "mass-redistribution": True,  # while the contact status holds
        "characteristic": True,
    }[scheme]
    if not conserving:
        return None
    if scheme == "paper" and kind == "elastic":
        # The split penalty acts before any contact too: its implicit and
        # explicit halves cancel only to O(dt^2) (docs/methods.md).
        h = float(c["bar"]["length"]) / int(c["bar"]["elements"])
        ratio = float(c["obstacle"]["stiffness"]) * float(c["time"]["step"]) ** 2 / (float(c["bar"]["density"]) * h)
        if value(c, "time", "alpha", 0.25) == 0.25 and ratio <= PENALTY_REGIME:
            return ("penalty", ratio)
        return None
    if summary["contact_count"] == 0:
        return "exact"
    if scheme == "moreau-jean" and kind == "rigid" and e == 1.0:
        return "exact"  # each impact changes E by p (V^n + V^{n+1}) / 2 = 0 when V^{n+1} = -V^n
    return None


def check_energy(c, out, summary):
    claim = energy_claim(c, summary)
    event(f"energy claim: {claim if claim is None or isinstance(claim, str) else claim[0]}")
    if claim is None:
        return
    h = np.loadtxt(out / "history.csv", delimiter=",", skiprows=1, ndmin=2)
    kin, strain, obst, work, diss = h[:, 4], h[:, 5], h[:, 6], h[:, 7], h[:, 8] + h[:, 9]
    total = kin + strain + obst - work + diss
    size = np.max(np.abs(kin) + np.abs(strain) + np.abs(obst) + np.abs(work) + np.abs(diss))
    e0 = abs(total[0])
    assert e0 > 0  # the bar starts moving
    # summary.json's number is the history's max |E(t_n) - E(0)| / |E(0)|.
    measured = np.max(np.abs(total - total[0])) / e0
    assert math.isclose(summary["energy_error_relative"], measured, rel_tol=1e-9, abs_tol=1e-15)
    # Row 0 -> row 1 carries the start's error: a three-level scheme's first
    # level, mass redistribution's modified mass, the characteristic scheme's
    # nodal start (docs/methods.md, "the step from row 0 to row 1 carries the
    # start's O(dt) error"); the claims below are about the rows after it.
    start = abs(total[1] - total[0]) / e0 if len(total) > 1 else 0.0
    if claim == "exact":
        drift = np.max(np.abs(total[1:] - total[1])) if len(total) > 1 else 0.0
        assert drift <= ROUND_OFF * size, f"energy drift {drift:.3e} of a budget of size {size:.3e}"
        assert summary["energy_error_relative"] <= start + ROUND_OFF * size / e0
    else:
        _, ratio = claim
        assert summary["energy_error_relative"] <= start + PENALTY_FACTOR * ratio * size / e0, \
            f"penalty energy error {summary['energy_error_relative']:.3e} with k dt^2/(rho h) = {ratio:.3e}"


def run_cli(c, work):
    """Runs the case; checks what every run promises; returns (exit status, summary or None)."""
    case, out = work / "case.toml", work / "out"
    case.write_text(to_toml(c))
    p = subprocess.run([CLI, "run", str(case), "--out", str(out)], capture_output=True, text=True, timeout=120)
    event(f"exit {p.returncode}")
    described = f"exit {p.returncode}\n--- case\n{case.read_text()}--- stderr\n{p.stderr}"
    assert p.returncode in (0, 2, 3), described  # negative: killed by a signal; 1: an internal error
    assert "Sanitizer" not in p.stderr and "runtime error" not in p.stderr, described
    # Health warnings (one line each, also in summary.json) may stand before the failure's line.
    warnings = [w for w in p.stderr.splitlines() if w.startswith("barimpact: warning: ")]
    if p.returncode == 0:
        summary = json.loads((out / "summary.json").read_text())
        assert summary["complete"] is True, described
        assert len(warnings) == len(summary["warnings"]), described
        return 0, summary
    lines = [x for x in p.stderr.strip().splitlines() if not x.startswith("barimpact: warning: ")]
    assert len(lines) == 1 and lines[0].startswith("barimpact: "), described
    if p.returncode == 2:
        assert lines[0].startswith("barimpact: error: ") and not out.exists(), described
    else:
        assert json.loads((out / "summary.json").read_text())["complete"] is False, described
    return p.returncode, None


@given(cases())
def test_every_small_case_completes_or_is_refused_cleanly(tmp_path_factory, c):
    work = tmp_path_factory.mktemp("case")
    status, summary = run_cli(c, work)
    if status == 0:
        check_energy(c, work / "out", summary)


@given(cases(conserving=True))
def test_conserving_configurations_keep_the_energy_budget(tmp_path_factory, c):
    work = tmp_path_factory.mktemp("case")
    status, summary = run_cli(c, work)
    if status == 0:
        check_energy(c, work / "out", summary)
