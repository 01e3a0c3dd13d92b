#!/usr/bin/env python3
"""The honest baseline a user would write today: the paper's scheme (6.3) for
Example 1 scaled to M elements, in NumPy/SciPy, with the matrix factored once
(scipy.linalg.cholesky_banded) and each step a banded stencil right-hand side
plus scipy.linalg.cho_solve_banded. Timed in the same process as barimpact's
Python module running the same case; prints seconds per step for both.

    PYTHONPATH=build/release/python /usr/bin/python3 bench/scipy_baseline.py 1000 10000
"""
import sys
import time

import numpy as np
from scipy.linalg import cho_solve_banded, cholesky_banded

import barimpact


def scipy_steps(M, steps, k=100.0, alpha=0.25):
    h, dt, rho, a = 1.0 / M, 1.0 / M, 1.0, 1.0
    n = M + 1
    md, mo = np.full(n, 2 * rho * h / 3), rho * h / 6
    md[0] = md[-1] = rho * h / 3
    kd, ko = np.full(n, 2 * a / h), -a / h
    kd[0] = kd[-1] = a / h
    sd = kd.copy()
    sd[0] += k / 2
    A_d, A_o = md / dt**2 + alpha * sd, mo / dt**2 + alpha * ko
    B1_d, B1_o = 2 * md / dt**2 - (1 - 2 * alpha) * sd, 2 * mo / dt**2 - (1 - 2 * alpha) * ko
    B0_d, B0_o = -md / dt**2 - alpha * sd, -mo / dt**2 - alpha * ko
    ab = np.zeros((2, n))
    ab[0, 1:] = A_o
    ab[1, :] = A_d
    factor = cholesky_banded(ab, lower=False)
    zo = np.zeros(n)
    zc = -dt * np.ones(n)
    rhs = np.empty(n)
    start = time.perf_counter()
    for _ in range(steps):
        rhs[:] = B1_d * zc + B0_d * zo
        rhs[1:] += B1_o * zc[:-1] + B0_o * zo[:-1]
        rhs[:-1] += B1_o * zc[1:] + B0_o * zo[1:]
        rhs[0] += 0.5 * k * abs(zc[0])
        zo, zc = zc, cho_solve_banded((factor, False), rhs, overwrite_b=False)
    return (time.perf_counter() - start) / steps


def barimpact_steps(M, steps):
    case = barimpact.Case({"bar": {"elements": M}, "initial": {"velocity": "-1"},
                           "time": {"step": 1.0 / M, "end": steps / M},
                           "output": {"every": steps, "fields_at": []}})
    r = barimpact.run(case)
    return r.summary["run_seconds"] / r.summary["steps_done"]


def main():
    print("| M | SciPy (us/step) | barimpact (us/step) | ratio |")
    print("|---:|---:|---:|---:|")
    for M in [int(x) for x in sys.argv[1:]] or [1000, 10000]:
        steps = max(200, 2_000_000 // M)
        s = scipy_steps(M, steps)
        b = barimpact_steps(M, steps * 10)
        print(f"| {M:,} | {s * 1e6:.1f} | {b * 1e6:.2f} | {s / b:.0f}x |")


if __name__ == "__main__":
    main()
