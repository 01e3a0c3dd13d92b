"""The one style of every figure barimpact draws (run, exact, converge,
sweep, bearing, drive, hopkinson, pda, match): units, signs and words.

- Units: under a case's `[units] system = "SI"` each axis gets the
  engineering unit that keeps its numbers readable (kN or MN, MPa, mm, ms
  or µs, kJ), chosen per quantity from UNIT_SYSTEMS; under "US" the US
  customary ones (kip, ft, in, ksi, kip-ft, ft/s; time still in s, ms or
  µs) from the SI numbers the files hold; "none" (the default) leaves the
  numbers as they are and names no unit.
- Signs: one convention per quantity in every figure, said on the axis
  (SIGNS): forces, stresses and strains compression positive; displacements
  and velocities along x, which runs from the near end (a pile's toe) up
  the line; a penetration into the soil positive.
- Words: legends and titles name what a history column holds ("pile
  cushion force", "toe resistance"), from COLUMN_WORDS; docs/figures.md
  lists the table.

Axis labels read "words (sign) [unit]": "force (compression +) [kN]".
"""
import re

import numpy as np

# --- units ----------------------------------------------------------------------

# Per system, per quantity: the units an axis may take, as (name, size in the
# base unit, smallest reference value that picks it). The reference is the
# largest magnitude drawn, or for time the span; the largest unit it reaches
# is taken (0.12 s of time: ms; 2.5e6 N: MN).
UNIT_SYSTEMS = {
    "SI": {
        "time": (("µs", 1e-6, 0.0), ("ms", 1e-3, 1e-3), ("s", 1.0, 1.0)),  # a pile blow in ms, not 0.12 s
        "length": (("mm", 1e-3, 0.0), ("m", 1.0, 1.0)),
        "displacement": (("µm", 1e-6, 0.0), ("mm", 1e-3, 1e-3), ("m", 1.0, 1.0)),
        "opening": (("µm", 1e-6, 0.0), ("mm", 1e-3, 1e-3), ("m", 1.0, 1.0)),
        "velocity": (("m/s", 1.0, 0.0),),
        "acceleration": (("m/s²", 1.0, 0.0),),
        "force": (("N", 1.0, 0.0), ("kN", 1e3, 1e3), ("MN", 1e6, 1e6)),
        "stress": (("Pa", 1.0, 0.0), ("kPa", 1e3, 1e3), ("MPa", 1e6, 1e6), ("GPa", 1e9, 1e10)),
        "pressure": (("Pa", 1.0, 0.0), ("kPa", 1e3, 1e3), ("MPa", 1e6, 1e6)),
        "energy": (("J", 1.0, 0.0), ("kJ", 1e3, 1e3), ("MJ", 1e6, 1e6)),
        "strain": (("-", 1.0, 0.0),),
        "strain_rate": (("1/s", 1.0, 0.0),),
        "stiffness": (("N/m", 1.0, 0.0), ("kN/m", 1e3, 1e3), ("MN/m", 1e6, 1e6), ("GN/m", 1e9, 1e9)),
        "impedance": (("kN s/m", 1e3, 0.0),),
        "area": (("m²", 1.0, 0.0),),
        "mass": (("kg", 1.0, 0.0),),
        "density": (("kg/m³", 1.0, 0.0),),
        "line_density": (("kg/m", 1.0, 0.0),),
        "cpu_time": (("s", 1.0, 0.0),),
    },
}

# US customary units, exact in SI (the international foot and pound, 1959).
FOOT, INCH, POUND = 0.3048, 0.0254, 0.45359237
POUND_FORCE = 4.4482216152605
KIP = 1000.0 * POUND_FORCE
UNIT_SYSTEMS["US"] = {
    "time": UNIT_SYSTEMS["SI"]["time"],
    "length": (("in", INCH, 0.0), ("ft", FOOT, 3 * FOOT)),  # a pile in ft, a specimen in in
    "displacement": (("in", INCH, 0.0),),  # a pile's set and penetration in inches
    "opening": (("in", INCH, 0.0),),
    "velocity": (("ft/s", FOOT, 0.0),),
    "acceleration": (("ft/s²", FOOT, 0.0),),
    "force": (("lbf", POUND_FORCE, 0.0), ("kip", KIP, KIP)),
    "stress": (("psi", POUND_FORCE / INCH**2, 0.0), ("ksi", KIP / INCH**2, KIP / INCH**2)),
    "pressure": (("psi", POUND_FORCE / INCH**2, 0.0), ("ksi", KIP / INCH**2, KIP / INCH**2)),
    "energy": (("ft-lb", POUND_FORCE * FOOT, 0.0), ("kip-ft", KIP * FOOT, KIP * FOOT)),
    "strain": UNIT_SYSTEMS["SI"]["strain"],
    "strain_rate": UNIT_SYSTEMS["SI"]["strain_rate"],
    "stiffness": (("kip/in", KIP / INCH, 0.0),),
    "impedance": (("kip s/ft", KIP / FOOT, 0.0),),
    "area": (("in²", INCH**2, 0.0),),
    "mass": (("lb", POUND, 0.0),),
    "density": (("lb/ft³", POUND / FOOT**3, 0.0),),
    "line_density": (("lb/ft", POUND / FOOT, 0.0),),
    "cpu_time": UNIT_SYSTEMS["SI"]["cpu_time"],
}

# A blow count's length, per system: blows per 250 mm (SI), per ft (US).
BLOW_COUNTS = {"SI": ("blows per 250 mm", 0.25), "US": ("blows/ft", FOOT)}

# What a value in a legend or title is written in: the SI unit of size 1;
# under US the unit its axis takes for a value that size (kip, ksi, kip/in).
BASE_UNITS = {quantity: next((name for name, size, _ in units if size == 1.0), None)
              for quantity, units in UNIT_SYSTEMS["SI"].items()}
BASE_UNITS["impedance"] = "N s/m"


def choose_unit(table, quantity, values, span=False):
    """(name, size) of the unit of `quantity` in a system's `table` for
    `values` (their largest magnitude, or with span=True their span);
    None when the system names no unit for it."""
    units = table.get(quantity)
    if not units:
        return None
    a = np.asarray([] if values is None else values, dtype=float).ravel()
    a = a[np.isfinite(a)]
    reference = float(np.ptp(a) if span else np.abs(a).max()) if a.size else 0.0
    if reference == 0.0 and span and a.size:
        reference = float(np.abs(a).max())
    if reference == 0.0:  # nothing to read a size from: the base unit
        base = BASE_UNITS.get(quantity)
        return next(((n, s) for n, s, _ in units if n == base), units[0][:2])
    chosen = units[0]
    for unit in units:
        if reference >= unit[2]:
            chosen = unit
    return chosen[:2]


# --- signs ----------------------------------------------------------------------

# The sign convention of each quantity, said on its axes. The data's own:
# history.csv's joint and end forces and R are compression positive, a
# gauge's force, fields.csv's sigma and eps_p and hopkinson.csv's gauge
# strains tension positive (the figures draw those negated); U, V and the
# masses' u and v are along x.
SIGNS = {"force": "compression +", "stress": "compression +", "strain": "compression +",
         "displacement": "along x +", "velocity": "along x +", "penetration": "down +", "opening": "open +",
         "pressure": "absolute"}
PILE_SIGNS = {"displacement": "up +", "velocity": "up +"}  # x runs from the toe up the pile

# The columns drawn negated so that every figure keeps SIGNS (tension positive in the files).
TENSION_POSITIVE = re.compile(r"^gauge\..+\.(force|strain)$|^(sigma|eps_p|incident|reflected|transmitted)$")


def drawn_sign(column):
    """-1 for a column written tension positive (the figures draw compression positive), else 1."""
    return -1.0 if TENSION_POSITIVE.match(column) else 1.0


class Scale:
    """An axis' label and the factor its numbers are drawn with: scale(values) -> drawn values."""

    def __init__(self, label, factor=1.0, unit=""):
        self.label, self.factor, self.unit = label, factor, unit

    def __call__(self, values):
        if self.factor == 1.0:
            return values
        return values * self.factor if np.ma.isMaskedArray(values) else np.asarray(values, dtype=float) * self.factor

    def text(self, value, digits=4):
        """A value (in base units) as drawn, with the unit: "2.5 ms"."""
        number = f"{float(value) * self.factor:.{digits}g}"
        return f"{number} {self.unit}" if self.unit and self.unit != "-" else number


class Units:
    """Axis labels and scales in a unit system ("SI", or "none": no unit
    names, numbers as they are). `pile` says the signs in a pile's words
    (up the pile, the toe)."""

    def __init__(self, system="none", pile=False):
        self.system = str(system)
        self.table = UNIT_SYSTEMS.get(self.system.upper(), {})
        self.si = self.system.upper() == "SI"
        self.us = self.system.upper() == "US"
        self.pile = pile

    def sign(self, quantity):
        """The sign convention said on an axis of `quantity`, or None."""
        return (PILE_SIGNS.get(quantity) if self.pile else None) or SIGNS.get(quantity)

    def axis(self, name, quantity, values=None, sign=True, span=None):
        """The Scale of an axis showing `name`, a `quantity` of the tables,
        for `values` (None: the base unit; time takes its span). sign=False
        leaves the sign out (a magnitude); a text gives it."""
        said = self.sign(quantity) if sign is True else (sign or None)
        label = f"{name} ({said})" if said else name
        # No values: a label for numbers drawn as the files hold them, in SI's base units.
        table = UNIT_SYSTEMS["SI"] if values is None and self.us else self.table
        unit = choose_unit(table, quantity, values, quantity == "time" if span is None else span)
        if unit is None:
            return Scale(label)
        return Scale(f"{label} [{unit[0]}]", 1.0 / unit[1], unit[0])

    def time(self, *series):
        """The time axis of a figure: one unit from the span of every series drawn."""
        values = np.concatenate([np.asarray(s, dtype=float).ravel() for s in series]) if series else None
        return self.axis("time", "time", values)

    def value(self, number, quantity):
        """A number (SI) with its unit, for legends and titles: "100 N/m";
        under US converted ("5.709e+04 kip/in")."""
        if self.us and quantity and isinstance(number, (int, float)) and self.table.get(quantity):
            name, size = choose_unit(self.table, quantity, [number])
            return f"{number / size:.4g} {name}" if name != "-" else f"{number:.4g}"
        text = f"{number:.4g}" if isinstance(number, (int, float)) else str(number)
        unit = BASE_UNITS.get(quantity) if self.si and quantity else None
        return f"{text} {unit}" if unit and unit != "-" else text

    def blow_count(self):
        """(words, length in m) of a blow count: per 250 mm, or per ft under US."""
        return BLOW_COUNTS["US" if self.us else "SI"]


# --- words ----------------------------------------------------------------------

def is_pile(case):
    """True for a pile case (a `[blow]`, or a Smith near end): its near end is the toe."""
    case = case or {}
    return bool(case.get("blow")) or case.get("near_end", {}).get("law") == "smith"


def is_split_hopkinson(case):
    """True for a line with an incident and a transmitter bar (a split Hopkinson bar)."""
    names = {b.get("name") for b in (case or {}).get("body", [])}
    return {"incident", "transmitter"} <= names


BAR_WORDS = {"incident": "incident bar", "transmitter": "transmission bar", "striker": "striker bar"}


def spoken(name):
    """A name as words: "pile-cushion" -> "pile cushion"."""
    return re.sub(r"[-_]+", " ", str(name)).strip()


def _gauge_words(name, case):
    """A gauge by what engineers call it: a split Hopkinson bar's by its bar."""
    if is_split_hopkinson(case):
        body = next((g.get("body") for g in case.get("gauge", []) if g.get("name") == name), None)
        if body in BAR_WORDS:
            return f"{BAR_WORDS[body]} gauge"
    return f"{spoken(name)} gauge"


def _joint_words(name, case):
    """A joint by its name, or by the bodies it joins when its name is theirs."""
    joint = next((j for j in (case or {}).get("joint", []) if j.get("name") == name), {})
    between = joint.get("between") or []
    if len(between) == 2 and name == f"{between[0]}-{between[1]}":
        return f"{spoken(between[0])}–{spoken(between[1])} joint"
    return spoken(name)


def _near_words(case):
    if is_pile(case):
        return "toe", "toe resistance", "soil energy at the toe"
    if (case or {}).get("near_end", {}).get("law", "free") == "free":
        return "near-end", "near-end force", "obstacle energy"
    return "near-end", "obstacle reaction", "obstacle energy"


# Each history column as (pattern, words, quantity): {name} is the column's
# name part, {near}, {reaction}, {obstacle} the near end's words, {gauge}
# and {joint} the gauge's and joint's words.
COLUMN_WORDS = (
    (r"t", "time", "time"),
    (r"U", "{near} displacement", "displacement"),
    (r"V", "{near} velocity", "velocity"),
    (r"R", "{reaction}", "force"),
    (r"E_kin", "kinetic energy", "energy"),
    (r"E_strain", "strain energy", "energy"),
    (r"E_obstacle", "{obstacle}", "energy"),
    (r"W_ext", "external work", "energy"),
    (r"D_visc", "viscous dissipation", "energy"),
    (r"D_contact", "contact dissipation", "energy"),
    (r"D_plastic", "plastic work", "energy"),
    (r"joint\.(?P<name>.+)\.force", "{joint} force", "force"),
    (r"joint\.(?P<name>.+)\.opening", "{joint} opening", "opening"),
    (r"joint\.(?P<name>.+)\.pressure", "{joint} gas pressure", "pressure"),
    (r"hammer\.(?P<name>.+)\.force", "hammer {name} force", "force"),
    (r"hammer\.(?P<name>.+)\.opening", "hammer {name} opening", "opening"),
    (r"hammer\.(?P<name>.+)\.pressure", "hammer {name} pressure", "pressure"),
    (r"far_end\.force", "far-end force", "force"),
    (r"far_end\.opening", "far-end opening", "opening"),
    (r"body\.(?P<name>.+)\.u", "{name} displacement", "displacement"),
    (r"body\.(?P<name>.+)\.v", "{name} velocity", "velocity"),
    (r"gauge\.(?P<name>.+)\.strain", "{gauge} strain", "strain"),
    (r"gauge\.(?P<name>.+)\.velocity", "{gauge} velocity", "velocity"),
    (r"gauge\.(?P<name>.+)\.force", "{gauge} force", "force"),
)


def column_words(column, case=None):
    """(words, quantity) of a history column in the case's words
    ("joint.pile-cushion.force" -> ("pile cushion force", "force")), None
    for a column the table does not know."""
    near, reaction, obstacle = _near_words(case)
    for pattern, words, quantity in COLUMN_WORDS:
        m = re.fullmatch(pattern, column)
        if m:
            name = m.groupdict().get("name", "")
            return words.format(near=near, reaction=reaction, obstacle=obstacle, name=spoken(name),
                                gauge=_gauge_words(name, case), joint=_joint_words(name, case)), quantity
    return None


def words_of(column, case=None):
    """A column's words, or the column itself spoken when the table does not know it."""
    found = column_words(column, case)
    return found[0] if found else spoken(column.replace(".", " "))


def key_words(key):
    """A case key in words: "near_end.stiffness" -> "near-end stiffness",
    "body.pile.elements" -> "pile elements"."""
    parts = key.split(".")
    if parts[0] in ("body", "joint", "gauge") and len(parts) > 2:
        parts = parts[1:]
    return " ".join(spoken(p) for p in parts).replace("near end", "near-end").replace("far end", "far-end")
