"""barimpact: a visco-elastic bar hitting obstacles (Do, Raupp & Feijoo 1979).

    import barimpact
    case = barimpact.Case("examples/paper-example1.toml", set={"time.lambda": 0.25})
    result = barimpact.run(case)
    result.t, result.U, result.R          # numpy views of the history, no copy
    result.u                              # field snapshots, shape (snapshots, nodes)
    result.summary                        # the summary.json dict
    barimpact.plot(result, "figures")     # PNG and SVG

Every number comes from the C++ library (barimpact._core): the same code as
the `barimpact` command line, so the same case gives the same bits.
"""
import json

import numpy as np

from ._core import Case, InputError, Result
from ._core import exact as _exact
from ._core import run as _run

__all__ = ["Case", "Result", "InputError", "run", "exact", "exact_example1", "bearing", "hopkinson", "plot", "load"]


def run(case, progress=None):
    """Run a case: a `Case`, or anything `Case` accepts (a path, TOML text, a
    dict). The GIL is released while it runs. `progress`, if given, is called
    about twice a second with a dict (step, steps, t, t_end, elapsed);
    returning False stops the run (the result is then marked incomplete)."""
    if not isinstance(case, Case):
        case = Case(case)
    return _run(case, progress)


def exact(case):
    """The exact solution the case admits, tabulated on its grid like a run
    (`barimpact exact`): rigid impact with gap, with a constant load, elastic
    obstacle, or the clamped periodic benchmark. InputError if none."""
    if not isinstance(case, Case):
        case = Case(case)
    return _exact(case)


def bearing(case, out, capacity, toe_share=None, jobs=0, plot=True, force=False):
    """The bearing graph (`barimpact bearing CASE --out OUT --capacity FROM:TO:COUNT`):
    `case` a case file with Smith's soil, `capacity` (from, to, count) in N,
    `toe_share` R_toe / capacity (None: the case's). Runs every capacity on
    `jobs` threads (0: all cores; resumes a bearing directory), writes
    bearing.csv (and bearing.png unless plot=False) and returns its columns as
    a dict of numpy arrays (blow counts inf where the hammer cannot move the pile)."""
    import os
    from ._core import _bearing
    lo, hi, count = capacity
    _bearing(os.fspath(case), os.fspath(out), float(lo), float(hi), int(count), toe_share, int(jobs), force)
    from .bearing import plot_bearing, read_bearing
    rows = read_bearing(out)
    if plot:
        plot_bearing(out)
    columns = {}
    for key in rows[0] if rows else []:
        values = [r[key] for r in rows]
        columns[key] = np.array(values) if not isinstance(values[0], str) else values
    return columns


class HopkinsonTable(dict):
    """hopkinson.csv's columns by name (numpy arrays, nan where missing), and
    `summary`, summary.json as a dict."""

    summary = None


def hopkinson(setup):
    """The split Hopkinson bar analysis (`barimpact hopkinson SETUP --out DIR`)
    without writing anything: `setup` a setup file's path, or the same as a
    dict of sections ({"bar": {...}, "incident": {...}, ...}; relative paths
    then from the working directory). Returns hopkinson.csv's table as a dict
    of numpy arrays (t, strain_1w, strain_rate_1w, stress_1w, strain_3w,
    strain_rate_3w, stress_2w, stress_3w, force_front, force_back,
    equilibrium, incident, reflected, transmitted) with `.summary`.
    InputError (one line) for a signal it cannot analyse."""
    import os
    from ._core import _hopkinson
    table, summary = _hopkinson(setup if isinstance(setup, dict) else os.fspath(setup))
    out = HopkinsonTable(table)
    out.summary = json.loads(summary)
    return out


Result.summary = property(lambda self: json.loads(self.summary_json), doc="summary.json as a dict")


def exact_example1(x, t, length=1.0, stiffness=1.0, density=1.0, v0=-1.0):
    """The paper's Example 1 with a rigid obstacle (exact): a bar at rest,
    undeformed, moving at v0 < 0 towards x = 0. Returns a dict of arrays u, v,
    strain, R, broadcast over x and t."""
    xb, tb = np.broadcast_arrays(np.asarray(x, dtype=float), np.asarray(t, dtype=float))
    u, v, strain, R = _core_exact(xb.ravel(), tb.ravel(), length, stiffness, density, v0)
    shape = xb.shape
    return {"u": u.reshape(shape), "v": v.reshape(shape), "strain": strain.reshape(shape), "R": R.reshape(shape)}


from ._core import _exact_example1 as _core_exact  # noqa: E402
from .plot import load, plot  # noqa: E402
