#!/usr/bin/env bash
# Node-steps per second per core of a sweep, with and without SIMD batches,
# on two cores, and under mpirun -n 2 (both ranks run cases). The
# configurations alternate over five rounds (this machine is noisy) and
# each row is the median of its five wall times:
#   bash bench/sweep_throughput.sh build/release/barimpact
set -euo pipefail
bin=${1:-build/release/barimpact}
examples=$(cd "$(dirname "$0")/../examples" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat > "$work/sweep.toml" <<TOML
# 16 cases of Example 1 at M = 1000, dt = 0.001, t = 0 .. 32: 5.1e8 node-steps.
case = "$examples/paper-example1.toml"
[set]
bar.elements = 1000
time.step = 0.001
output.every = 100
time.end = 32.0
output.fields_at = []
[[axis]]
key = "obstacle.stiffness"
from = 100.0
to = 1000.0
count = 16
TOML
node_steps=$((16 * 1001 * 32000))
mpi=(env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpiexec -n 2 --oversubscribe)
labels=("one core, each case alone (--no-batch --jobs 1)" "one core, SIMD batches of 4 (--jobs 1)"
  "two cores, SIMD batches (--jobs 2)" "mpirun -n 2 (two ranks, chunks of 4 batched)")
run_config() {  # index
  case $1 in
    0) "$bin" sweep "$work/sweep.toml" --out "$work/out" --no-batch --jobs 1 ;;
    1) "$bin" sweep "$work/sweep.toml" --out "$work/out" --jobs 1 ;;
    2) "$bin" sweep "$work/sweep.toml" --out "$work/out" --jobs 2 ;;
    3) "${mpi[@]}" "$bin" sweep "$work/sweep.toml" --out "$work/out" ;;
  esac
}
configs=(0 1 2)
command -v mpiexec > /dev/null && configs+=(3)
declare -A times
for round in 1 2 3 4 5; do
  for i in "${configs[@]}"; do
    rm -rf "$work/out"
    start=$(date +%s.%N)
    run_config "$i" > /dev/null
    end=$(date +%s.%N)
    times[$i]+="$(awk -v s="$start" -v e="$end" 'BEGIN { print e - s }') "
  done
done
median() { tr ' ' '\n' <<< "$1" | grep . | sort -g | sed -n 3p; }
echo "| sweep (16 cases, M = 1000, 32000 steps each; median of 5) | wall s | node-steps/s |"
echo "|---|---:|---:|"
for i in "${configs[@]}"; do
  awk -v l="${labels[$i]}" -v t="$(median "${times[$i]}")" -v n="$node_steps" \
    'BEGIN { printf "| %s | %.2f | %.3g |\n", l, t, n / t }'
done
awk -v a="$(median "${times[0]}")" -v b="$(median "${times[1]}")" \
  'BEGIN { printf "\nSIMD batches of 4 on one core: %.1fx the node-steps per second of cases run alone.\n", a / b }'
