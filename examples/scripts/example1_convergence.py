#!/usr/bin/env python3
"""Example 1 against the exact rigid-obstacle solution, refining h, dt and
1/k together (k h and dt/h fixed), with the command line only.

    python3 examples/scripts/example1_convergence.py build/release/barimpact

Prints a Markdown table: max and L1-in-time errors of U, the energy balance
error, the impulse of R (exact: 2), and observed orders between levels.
"""
import csv
import math
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent.parent


def exact_U(t):  # Section 8: U = 0 on (0, 2), then t - 2
    return max(0.0, t - 2.0)


def level(binary, M, dt, k, out):
    subprocess.run([binary, "run", str(HERE / "paper-example1.toml"), "--out", out,
                    "--set", f"bar.elements={M}", "--set", f"time.step={dt}",
                    "--set", f"obstacle.stiffness={k}", "--set", "output.fields_at=[]"],
                   check=True, capture_output=True)
    rows = list(csv.DictReader(open(Path(out) / "history.csv")))
    err = [abs(float(r["U"]) - exact_U(float(r["t"]))) for r in rows]
    total = [float(r["E_kin"]) + float(r["E_strain"]) + float(r["E_obstacle"]) for r in rows]
    return (max(err), sum(err) * dt, max(abs(e - total[0]) for e in total),
            sum(float(r["R"]) for r in rows) * dt)


def main():
    binary = sys.argv[1] if len(sys.argv) > 1 else "build/release/barimpact"
    print("| M | dt | k | max U err | order | L1 U err | order | energy err | impulse |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    prev = None
    with tempfile.TemporaryDirectory() as tmp:
        for i in range(6):
            M, dt, k = 50 * 2**i, 0.02 / 2**i, 50 * 2**i
            e = level(binary, M, dt, k, str(Path(tmp) / str(i)))
            o = ["", ""] if prev is None else [f"{math.log2(prev[j] / e[j]):.2f}" for j in (0, 1)]
            print(f"| {M} | {dt:g} | {k} | {e[0]:.3e} | {o[0]} | {e[1]:.3e} | {o[1]} | {e[2]:.2e} | {e[3]:.5f} |")
            prev = e


if __name__ == "__main__":
    main()
