"""Your own case from a dict: a steel bar in SI units (L = 1 m, E A = 210 GPa x
3.14e-4 m^2, rho A = 7800 kg/m^3 x 3.14e-4 m^2) moving at 0.1 m/s towards a
stiff elastic stop 0.05 mm away.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/steel_bar.py out/steel
"""
import sys
from pathlib import Path

import barimpact

out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("steel")

area = 3.14e-4
case = barimpact.Case({
    "bar": {"length": 1.0, "density": 7800 * area, "stiffness": 210e9 * area, "elements": 200},
    "initial": {"velocity": "-0.1"},
    "obstacle": {"kind": "elastic", "stiffness": 1e9, "gap": 5e-5},
    "time": {"end": 2e-3, "step": 1e-6},
    "output": {"every": 2, "fields_at": [i * 2e-5 for i in range(101)]},
    "units": {"system": "SI"},
})
result = barimpact.run(case, progress=lambda p: print(f"  t = {p['t']:.2e} s", file=sys.stderr))
s = result.summary
c = s["contacts"][0]
print(f"contact from {c['start'] * 1e3:.3f} ms to {c['end'] * 1e3:.3f} ms, largest force {s['max_reaction'] / 1e3:.2f} kN, "
      f"rebound {c['rebound_velocity']:+.4f} m/s")
out.mkdir(parents=True, exist_ok=True)
result.write(str(out / "run"))
for path in barimpact.plot(result, out / "figures"):
    print(path)
