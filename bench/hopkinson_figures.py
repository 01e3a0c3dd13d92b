"""Times the figures of a Hopkinson analysis of long records: two gauge
records of SAMPLES samples (10^6 by default, 1 ns apart), analysed by
`barimpact hopkinson`, then drawn again by `barimpact plot DIR`.
  python3 bench/hopkinson_figures.py BUILD_DIR [SAMPLES]"""
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np


def pulse(tau):
    """A pulse of unit height: 5% just after 0, 1 from 19 us to 100 us, 0 at 121 us."""
    up = np.minimum(0.05 + tau / 20e-6, 1.0)
    down = (121e-6 - tau) / 21e-6
    return np.where((tau <= 0.05e-6) | (tau >= 121e-6), 0.0, np.where(tau < 100e-6, up, down))


def records(d, samples):
    """The incident (incident and reflected waves) and transmitted gauges' records, and a setup reading them."""
    t = np.arange(samples) * (1e-3 / samples)
    foot = 100e-6
    noise = np.random.default_rng(1).normal(0.0, 2e-6, (2, samples))  # a real record's noise
    incident = -1e-3 * pulse(t - foot) + 6e-4 * pulse(t - foot - 400e-6 - 3e-6) + noise[0]
    transmitted = -4e-4 * pulse(t - foot - 300e-6 - 1e-6) + noise[1]
    for name, strain in (("inc", incident), ("tr", transmitted)):
        np.savetxt(d / f"{name}.csv", np.column_stack([t, strain]), delimiter=",", header="t,strain", comments="",
                   fmt="%.9g")
    (d / "setup.toml").write_text(
        '[bar]\nmodulus = 200e9\ndensity = 8000.0\narea = 3e-4\n[specimen]\nlength = 0.005\narea = 1e-4\n'
        '[incident]\nsignal = "inc.csv"\ngauge_to_specimen = 1.0\n'
        '[transmitted]\nsignal = "tr.csv"\ngauge_to_specimen = 0.5\n')


def timed(*args):
    start = time.perf_counter()
    subprocess.run(args, check=True, capture_output=True)
    return time.perf_counter() - start


def main():
    build = Path(sys.argv[1])
    samples = int(float(sys.argv[2])) if len(sys.argv) > 2 else 10**6
    with tempfile.TemporaryDirectory() as d:
        d = Path(d)
        records(d, samples)
        bin = str(build / "barimpact")
        analysis = timed(bin, "hopkinson", str(d / "setup.toml"), "--out", str(d / "hk"), "--no-plot")
        rows = sum(1 for _ in open(d / "hk" / "hopkinson.csv")) - 1
        drawing = timed(bin, "plot", str(d / "hk"))
        imports = timed(sys.executable, "-c", "import matplotlib.pyplot")
        print(f"{samples} samples a record, {rows} rows in hopkinson.csv: analysis {analysis:.2f} s, "
              f"figures (barimpact plot) {drawing:.2f} s; python3 -c 'import matplotlib.pyplot' {imports:.2f} s")


if __name__ == "__main__":
    main()
