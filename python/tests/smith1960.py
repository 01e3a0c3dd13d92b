"""Smith's (1960) discrete wave-equation model of a blow, written apart from
barimpact as a test reference.

Smith lumps the pile into segments of length dl, each a point weight W_m at
its segment, joined by weightless springs K_m = E A / dl; ram and helmet are
weights, capblock and pile cushion springs with restitution. His recurrence,
displacements D positive down, t the step index:

    D_m(t) = D_m(t-1) + V_m(t-1) dt
    C_m(t) = D_m(t) - D_{m+1}(t)                  (spring m's compression)
    F_m(t) = K_m C_m(t)                           (a cushion: loads along K,
             unloads along K / e^2, never pulls)
    R_m(t) = (D_m(t) - D'_m(t)) K'_m (1 + J_m V_m(t-1))
    V_m(t) = V_m(t-1) + (F_{m-1}(t) - F_m(t) - R_m(t)) dt / m_m

with D'_m the soil's plastic displacement, kept within the quake Q of D_m
(both ways along the shaft; the toe only pushes), K'_m = R_u,m / Q. The
damping uses |R_s| (Smith's R_s (1 + J V) with the static force's magnitude)
or J R_u V (viscous), as barimpact's `damping_law`. Smith took dt about
half the segment's travel time dl / c.

`blow(case_file, segments, ratio)` reads an example's bodies, cushions and
soil (bars, masses, cushion joints, a smith toe and a uniform or triangular
shaft) and returns the set and the largest compression stress in the pile, as
barimpact's `blow` names them, and the time of the soil's last slip.
"""
import math
import tomllib

import numpy as np


def _line(case):
    """The weights and springs from the top (ram) down to the toe."""
    bodies = case["body"]
    joints = {tuple(j["between"]): j for j in case.get("joint", [])}
    masses, springs, pile = [], [], None  # springs[m]: between masses m and m + 1
    for k, b in enumerate(reversed(bodies)):  # the line's outermost body first
        if k > 0:
            upper = bodies[len(bodies) - k]["name"]
            j = joints[(b["name"], upper)]
            springs.append(("cushion", j["stiffness"], j.get("restitution", 1.0)))
        if b.get("kind") == "mass":
            masses.append(b["mass"])
            continue
        n, length, area = b["segments"], b["length"], b["area"]
        dl = length / n
        pile = (len(masses), n, b)
        for s in range(n):
            if s > 0:
                springs.append(("bar", b["modulus"] * area / dl, 1.0))
            masses.append(b["density"] * area * dl)
    return np.array(masses), springs, pile


def _soil(case, pile):
    """R_u, Q, J and the damping law of every weight (the shaft's share of
    each pile segment, the toe's on the last)."""
    first, n, b = pile
    count = first + n
    ru, quake, damp, viscous = (np.zeros(count) for _ in range(4))
    shaft = b.get("shaft")
    length = b["length"]
    dl = length / n
    if shaft:
        embedded = shaft.get("embedded", length)
        triangular = shaft.get("distribution", "uniform") == "triangular"
        for s in range(n):  # segment s from the head: x from length - (s+1) dl to length - s dl
            lo, hi = max(0.0, length - (s + 1) * dl), length - s * dl
            hi_in = min(hi, embedded)
            if hi_in <= lo:
                continue
            if triangular:  # density 2 R (embedded - x) / embedded^2, x up from the toe
                share = (2 / embedded**2) * (embedded * (hi_in - lo) - (hi_in**2 - lo**2) / 2)
            else:
                share = (hi_in - lo) / embedded
            m = first + s
            ru[m] = shaft["ultimate"] * share
            quake[m] = shaft.get("quake", 0.00254)
            damp[m] = shaft.get("damping", 0.164)
            viscous[m] = shaft.get("damping_law", "smith") == "viscous"
    toe = case["near_end"]
    return ru, quake, damp, viscous.astype(bool), (toe["ultimate"], toe.get("quake", 0.00254),
                                                   toe.get("damping", 0.492),
                                                   toe.get("damping_law", "smith") == "viscous")


def _initial_velocities(case, count):
    """The weights' velocities at t = 0, down positive: the masses' given ones."""
    v = np.zeros(count)
    for k_body, body in enumerate(reversed(case["body"])):
        if body.get("kind") == "mass" and "velocity" in body:
            v[k_body] = -float(body["velocity"])
    return v


def _spring_forces(k, restitution, cushion, c, c_max):
    """F_m from the compressions C_m: a cushion loads along K, unloads along
    K / e^2 from its largest compression and never pulls."""
    f = k * c
    e2 = restitution**2
    unloading = k / e2 * (c - (1 - e2) * c_max)
    return np.where(cushion, np.clip(np.minimum(f, unloading), 0.0, None), f)


def _shaft(d, v, plastic, ru, quake, damp, viscous, stiff):
    """The shaft: D' within Q of D both ways, R = K'(D - D') plus damping.
    Returns the new D' and R."""
    plastic = np.where(ru > 0, np.clip(plastic, d - quake, d + quake), 0.0)  # weights without soil never slip
    rs = stiff * (d - plastic)
    r = rs + np.where(viscous, damp * ru * v, damp * np.abs(rs) * v)
    return plastic, np.where(ru > 0, r, 0.0)


def _toe_resistance(w, v, toe, slip):
    """The toe: compression only, past its slip (max - Q)^+."""
    toe_ru, toe_q, toe_j, toe_viscous = toe
    toe_k = toe_ru / toe_q
    toe_r = 0.0
    if w > slip:
        rs_toe = min(toe_ru, toe_k * (w - slip))
        toe_r = max(0.0, rs_toe + (toe_j * toe_ru * v if toe_viscous else toe_j * rs_toe * v))
    return toe_r


def blow(case_file, segments, ratio=0.5, end=None):
    """Smith's model of the case's blow with the pile in `segments` segments and
    dt = ratio dl / c. Returns a dict: set, max_compression, last_slip, dt, steps."""
    with open(case_file, "rb") as f:
        case = tomllib.load(f)
    pile_body = next(b for b in case["body"] if b.get("kind", "bar") != "mass")
    pile_body["segments"] = segments
    masses, springs, pile = _line(case)
    ru, quake, damp, viscous, toe = _soil(case, pile)
    first, n, b = pile
    count = len(masses)
    k = np.array([s[1] for s in springs])
    restitution = np.array([s[2] for s in springs])
    cushion = np.array([s[0] == "cushion" for s in springs])
    pile_spring = np.arange(len(springs)) >= first  # springs inside the pile
    c0 = math.sqrt(b["modulus"] / b["density"])
    dt = ratio * (b["length"] / n) / c0
    t_end = end if end is not None else case["time"]["end"]
    steps = int(round(t_end / dt))

    d = np.zeros(count)
    v = _initial_velocities(case, count)
    c_max = np.zeros(len(springs))
    plastic = np.zeros(count)  # D' of the shaft
    toe_q = toe[1]
    toe_max = 0.0  # the toe's largest penetration (its D' = (max - Q)^+)
    stiff = np.where(ru > 0, ru / np.where(quake > 0, quake, 1.0), 0.0)
    area = b["area"]
    most_compression, last_move, v_impact = 0.0, 0.0, abs(v).max()
    for step in range(1, steps + 1):
        d += v * dt
        c = d[:-1] - d[1:]
        c_max = np.maximum(c_max, c)
        f = _spring_forces(k, restitution, cushion, c, c_max)
        before = plastic.copy()
        plastic, r = _shaft(d, v, plastic, ru, quake, damp, viscous, stiff)
        w = d[-1]
        toe_max_before = toe_max
        toe_max = max(toe_max, w)
        r[-1] += _toe_resistance(w, v[-1], toe, max(0.0, toe_max - toe_q))
        net = np.zeros(count)
        net[:-1] -= f
        net[1:] += f
        v += (net - r) * dt / masses
        most_compression = max(most_compression, float(f[pile_spring].max()) / area)
        if np.any(plastic != before) or toe_max > toe_max_before:
            last_move = step * dt
    return {"set": max(0.0, toe_max - toe_q), "max_compression": most_compression, "last_slip": last_move,
            "dt": dt, "steps": steps}
