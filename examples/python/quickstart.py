"""The paper's Example 1 from Python: run, compare with the exact solution, draw.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/quickstart.py out/quickstart
"""
import sys
from pathlib import Path

import numpy as np

import barimpact

examples = Path(__file__).resolve().parent.parent
out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("quickstart")

result = barimpact.run(examples / "paper-example1.toml")
contact = result.summary["contacts"][0]
print(f"leaves the obstacle at t = {contact['end']:.3f} (exact, rigid: 2) "
      f"with mean velocity {contact['rebound_velocity']:+.3f} (exact: +1)")

exact = barimpact.exact_example1(0.0, result.t)
print(f"max |U - U_exact| = {np.max(np.abs(result.U - exact['u'])):.4f} (penalty k = 100, h = dt = 0.01)")

for path in barimpact.plot(result, out):
    print(path)
