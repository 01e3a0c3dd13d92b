"""The penalty towards the rigid obstacle: Example 1 for growing k.

The explicit half of the penalty wants k dt^2 / (rho h / 3) below about 1,
so dt shrinks with k. Lift-off should tend to 2 and the rebound to +1. A
stiff penalty makes the end chatter: several short contact episodes at
impact; the last one ends with the final lift-off. At k = 10^4 the
penalty's time constant Z/k falls below the step, and the run says so with
a HealthWarning (penalty-unresolved), as it should: the study shows where.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/penalty_study.py out/penalty
"""
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import barimpact  # noqa: E402

examples = Path(__file__).resolve().parent.parent
out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("penalty")
out.mkdir(parents=True, exist_ok=True)

h, rho = 0.01, 1.0
fig, ax = plt.subplots(figsize=(8, 4.5), dpi=120, layout="constrained")
print("|     k |       dt | episodes | lift-off | rebound | max penetration | energy error |")
print("|------:|---------:|---------:|---------:|--------:|----------------:|-------------:|")
for k in (10, 100, 1000, 10000):
    dt = min(0.01, 0.5 * (rho * h / 3 / k) ** 0.5)
    r = barimpact.run(barimpact.Case(examples / "paper-example1.toml", set={
        "obstacle.stiffness": float(k), "time.step": dt, "output.fields_at": [], "output.every": 10}))
    s = r.summary
    c = s["contacts"][-1]
    print(f"| {k:5d} | {dt:.2e} | {len(s['contacts']):8d} | {c['end']:8.4f} | {c['rebound_velocity']:+7.4f} | "
          f"{s['max_penetration']:15.3e} | {s['energy_error_relative']:12.2e} |")
    ax.plot(r.t, r.U, lw=1, label=f"k = {k}")
ax.plot([0, 2, 4], [0, 0, 2], "k--", lw=1, label="rigid, exact")
ax.set_xlabel("t")
ax.set_ylabel("U")
ax.set_title("Example 1: penalty obstacle towards the rigid one")
ax.legend()
fig.savefig(out / "penalty_study.png")
print(out / "penalty_study.png")
