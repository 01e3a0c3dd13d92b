"""Signal matching against noise and against a kinked distribution: the
numbers docs/pda.md quotes, regenerated.

    /usr/bin/python3 bench/match_noise.py build/release/barimpact [--seeds 10] [--smoothing 10]

Noise: examples/pda/steel-pipe.csv (generated: 600 kN on the shaft, 900 kN at
the toe) with white noise of 2% of each channel's peak on each of its four
channels (numpy's default_rng(seed), seeds 1..N) and the velocity channels
1% high, at the record's rate (42 kHz) and at every fourth sample (10.6 kHz).
Kink: the same pipe's blow with its 600 kN uniform over the lowest 9 m only,
matched at smoothing weights 0, 3 and 10. Prints markdown tables: the
capacity, shaft and toe in kN and their error, the match quality.
"""
import argparse
import csv
import json
import subprocess
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
PDA = ROOT / "examples" / "pda"
SHAFT, TOE = 600e3, 900e3


def match(barimpact, record_toml, out, smoothing):
    """barimpact match of `record_toml` (its [match] with `smoothing`): summary.json."""
    text = record_toml.read_text() + f"smoothing = {smoothing}\n"  # [match] is the file's last section
    record_toml.write_text(text)
    subprocess.run([barimpact, "match", str(record_toml), "--out", str(out), "--no-plot", "--force"],
                   check=True, capture_output=True)
    return json.loads((out / "summary.json").read_text())


def row(name, s):
    err = lambda v, truth: f"{1e-3 * v:.1f} ({100 * (v / truth - 1):+.1f}%)"
    return (f"| {name} | {err(s['capacity'], SHAFT + TOE)} | {err(s['shaft'], SHAFT)} | {err(s['toe'], TOE)} "
            f"| {100 * s['match_quality']:.2f}% |")


def noisy(barimpact, tmp, seed, stride, smoothing):
    lines = (PDA / "steel-pipe.csv").read_text().splitlines()
    data = np.array([[float(x) for x in line.split(",")] for line in lines[2:]])[::stride]
    rng = np.random.default_rng(seed)
    for c in range(1, 5):
        data[:, c] += 0.02 * np.abs(data[:, c]).max() * rng.standard_normal(len(data))
    data[:, 3:5] *= 1.01
    record = tmp / f"noisy-{seed}-{stride}.csv"
    with open(record, "w") as f:
        f.write(lines[1] + "\n")
        np.savetxt(f, data, delimiter=",", fmt="%.9g")
    toml = tmp / "noisy.toml"
    toml.write_text((PDA / "steel-pipe.toml").read_text().replace('file = "steel-pipe.csv"', f'file = "{record}"')
                    .replace("skip_rows = 1", "skip_rows = 0"))
    return match(barimpact, toml, tmp / "out", smoothing)


def kinked_record(barimpact, tmp):
    """The pipe's blow with the shaft over its lowest 9 m, as a record (2 ms of baseline)."""
    out = tmp / "kink-run"
    subprocess.run([barimpact, "run", str(ROOT / "examples" / "pile" / "steel-pipe-sand.toml"), "--out", str(out),
                    "--set", "near_end.damping=0.15", "--set", "time.end=0.05", "--set", "output.every=1",
                    "--set", "body.pile.shaft.embedded=9.0", "--set", "body.pile.shaft.distribution=uniform"],
                   check=True, capture_output=True)
    with open(out / "history.csv") as f:
        rows = list(csv.DictReader(f))
    t = [float(r["t"]) for r in rows]
    dt = t[1] - t[0]
    with open(tmp / "kink.csv", "w") as f:
        f.write("t,F,V\n")
        for k in range(int(0.002 / dt), 0, -1):
            f.write(f"{t[0] - k * dt},0,0\n")
        for r in rows:
            f.write(f"{r['t']},{-float(r['gauge.head.force'])},{-float(r['gauge.head.velocity'])}\n")
    toml = tmp / "kink.toml"
    return toml, ('[pile]\nlength = 19.2\narea = 0.0105\nmodulus = 210e9\ndensity = 7850.0\n[record]\n'
                  f'file = "{tmp / "kink.csv"}"\nforce = "F"\nvelocity = "V"\n[match]\n')


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("barimpact")
    p.add_argument("--seeds", type=int, default=10)
    p.add_argument("--smoothing", type=float, default=10.0)
    a = p.parse_args()
    head = "| record | capacity (kN) | shaft (kN) | toe (kN) | quality |\n|---|---|---|---|---|"
    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        for stride, rate in ((1, "42 kHz"), (4, "10.6 kHz")):
            print(f"\nNoise 2% per channel, velocities x 1.01, {rate}, smoothing {a.smoothing:g}:\n\n{head}")
            for seed in range(1, a.seeds + 1):
                print(row(f"seed {seed}", noisy(a.barimpact, tmp, seed, stride, a.smoothing)))
        toml, text = kinked_record(a.barimpact, tmp)
        print(f"\nThe shaft over the lowest 9 m only, matched over the whole pile:\n\n{head}")
        for w in (0, 3, 10):
            toml.write_text(text)
            print(row(f"smoothing {w}", match(a.barimpact, toml, tmp / "out", w)))


if __name__ == "__main__":
    main()
