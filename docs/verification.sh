#!/usr/bin/env bash
# Regenerates docs/verification.md: every table below is the convergence.md
# that the `barimpact converge` command printed above it produced.
#   bash docs/verification.sh [build/release/barimpact]
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build/release/barimpact}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
doc=docs/verification.md
mkdir -p docs/figures

study() {  # name, then the converge arguments
  local name=$1
  shift
  "$bin" converge "$@" --out "$out/$name" > /dev/null 2> "$out/$name.err" || { cat "$out/$name.err"; exit 1; }
  sed "s|--out $out/$name|--out out/$name|" "$out/$name/convergence.md" >> "$doc"
  for f in convergence work_precision; do
    [ -f "$out/$name/$f.png" ] && cp "$out/$name/$f.png" "docs/figures/verification-$name-$f.png"
  done
  echo >> "$doc"
}

rigid="central-difference,paoli-schatzman,moreau-jean,mass-redistribution,characteristic"
penalty="paper,newmark,central-difference"

cat > "$doc" <<'TEXT'
# Verification

Every table is written by `barimpact converge` (the command above it; `bash
docs/verification.sh` runs them all again and rewrites this file). Errors:
max over the steps of |U - U_ref|, and the L1-in-time error of R against the
reference's mean over each step (R may be impulsive). "order" is the
observed order against the previous row (in h, or in the varied key).
"energy err" is the scheme's own budget at the end, |E_total(T) - E_total(0)| / E_total(0).
CPU seconds are per run on one core of the machine of docs/benchmarks.md.

TEXT
cat docs/verification-summary.md >> "$doc"

echo "## 1. Orders of every scheme on the exact solutions" >> "$doc"
echo >> "$doc"
echo "### Rigid obstacle, Example 1 (exact solution (a)), dt = h/2" >> "$doc"
study rigid-example1 examples/paper-example1-rigid.toml --schemes "$rigid" --levels 4 --set time.scheme=central-difference --set time.step=0.005
echo "### Rigid obstacle, the periodic clamped benchmark (exact solution (d)), 3 periods, dt = h/2" >> "$doc"
study rigid-clamped examples/clamped-periodic.toml --schemes "$rigid" --levels 4 --set time.scheme=central-difference --set time.step=0.005
echo "### Elastic obstacle k = 100, Example 1 (exact solution (c)), dt = h/2" >> "$doc"
study penalty-example1 examples/paper-example1.toml --schemes "$penalty" --levels 4 --set time.scheme=central-difference --set time.step=0.005

echo "## 2. Penalty to rigid: k grows with the mesh (k h = 1), against the rigid exact solution" >> "$doc"
echo >> "$doc"
echo "### Example 1 (reference: exact (a))" >> "$doc"
study k-example1 examples/paper-example1.toml --schemes "$penalty" --vary obstacle.stiffness=100,200,400,800 \
  --refine both --reference rigid --set time.step=0.005
echo "### Example 2 (reference: exact (b), until lift-off at t = 3)" >> "$doc"
study k-example2 examples/paper-example2.toml --schemes "$penalty" --vary obstacle.stiffness=100,200,400,800 \
  --refine both --reference rigid --set time.step=0.005

echo "## 3. Energy over 10 contact periods" >> "$doc"
echo >> "$doc"
echo "Example 1's bar leaves after one impact and never returns; contact recurs in the clamped benchmark" >> "$doc"
echo "(period 3), so 10 contact periods are t = 30 there. Rigid schemes against exact (d):" >> "$doc"
echo >> "$doc"
study energy-rigid examples/clamped-periodic.toml --schemes "$rigid" --levels 2 \
  --set time.scheme=central-difference --set time.step=0.005 --set time.end=30
echo "Penalty schemes, elastic obstacle k = 1000 (no exact solution: reference the finer run):" >> "$doc"
echo >> "$doc"
study energy-penalty examples/clamped-periodic.toml --schemes "$penalty" --levels 2 \
  --set time.scheme=central-difference --set obstacle.kind=elastic --set obstacle.stiffness=1000 \
  --set time.step=0.002 --set time.end=30

echo "## 4. Work-precision" >> "$doc"
echo >> "$doc"
echo "The CPU columns above against the errors, one line per scheme:" >> "$doc"
echo >> "$doc"
for name in rigid-example1 rigid-clamped penalty-example1; do
  echo "![work-precision, $name](figures/verification-$name-work_precision.png)" >> "$doc"
  echo >> "$doc"
done

echo "## 5. Elastic-plastic: von Karman's bar" >> "$doc"
echo >> "$doc"
echo "A bilinear bar driven at a constant velocity (examples/plastic/von-karman.toml): the struck end's" >> "$doc"
echo "force R against the closed form (U is prescribed). Its jump at t = 0 bounds the L1 order by 1:" >> "$doc"
echo >> "$doc"
study von-karman examples/plastic/von-karman.toml --schemes central-difference,paoli-schatzman --levels 5

echo "## 6. Pile driving: a blow's results under refinement" >> "$doc"
echo >> "$doc"
echo "examples/pile/steel-pipe-sand.toml without gravity (load.gravity = 0, time.end = 0.12, as Smith's" >> "$doc"
echo "model) under central differences at time.step = \"auto\" (0.9 of the" >> "$doc"
echo "stable step, so dt follows h), the pile's elements doubled: the set, ENTHRU and the largest" >> "$doc"
echo "compression, and the observed order from successive differences (no exact solution: the soil's" >> "$doc"
echo "and cushions' kinks and the backward-difference damping rate make them first order):" >> "$doc"
echo >> "$doc"
pile_dir=$(mktemp -d)
for m in 50 100 200 400 800 1600; do
  "$bin" run examples/pile/steel-pipe-sand.toml --out "$pile_dir/m$m" --set body.pile.elements=$m \
    --set load.gravity=0 --set time.end=0.12 --set output.every=1000 --set 'output.fields_at=[0.0]' > /dev/null
done
/usr/bin/python3 - "$pile_dir" >> "$doc" <<'PY'
import json, math, sys
ms = [50, 100, 200, 400, 800, 1600]
blows = [json.load(open(f"{sys.argv[1]}/m{m}/summary.json"))["blow"] for m in ms]
cols = {"set (mm)": [1e3 * b["set"] for b in blows], "ENTHRU (J)": [b["enthru"] for b in blows],
        "max compression (MPa)": [1e-6 * b["max_compression"]["value"] for b in blows]}
print("| elements | " + " | ".join(f"{k} | order" for k in cols) + " |")
print("|---|" + "---|---|" * len(cols))
for i, m in enumerate(ms):
    cells = []
    for v in cols.values():
        order = ""
        if i >= 2 and v[i] != v[i - 1] and v[i - 1] != v[i - 2]:
            order = f"{math.log2(abs(v[i - 1] - v[i - 2]) / abs(v[i] - v[i - 1])):.2f}"
        cells += [f"{v[i]:.6g}", order]
    print(f"| {m} | " + " | ".join(cells) + " |")
print()
PY
rm -rf "$pile_dir"
echo "Regenerated $doc"
