#!/usr/bin/env bash
# Node-steps per second per core of a sweep, with and without SIMD batches,
# and under mpirun -n 2 (one dispatcher, one worker), in one run:
#   bash bench/sweep_throughput.sh build/release/barimpact
set -euo pipefail
bin=${1:-build/release/barimpact}
examples=$(cd "$(dirname "$0")/../examples" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat > "$work/sweep.toml" <<TOML
# 16 cases of Example 1 at M = 1000, dt = 0.001, t = 0 .. 16: 2.6e8 node-steps.
case = "$examples/paper-example1.toml"
[set]
bar.elements = 1000
time.step = 0.001
output.every = 100
time.end = 16.0
output.fields_at = []
[[axis]]
key = "obstacle.stiffness"
from = 100.0
to = 1000.0
count = 16
TOML
node_steps=$((16 * 1001 * 16000))
measure() {  # label, then the command
  local label=$1
  shift
  rm -rf "$work/out"
  local start end
  start=$(date +%s.%N)
  "$@" > /dev/null
  end=$(date +%s.%N)
  awk -v l="$label" -v s="$start" -v e="$end" -v n="$node_steps" \
    'BEGIN { printf "| %s | %.2f | %.3g |\n", l, e - s, n / (e - s) }'
}
echo "| sweep (16 cases, M = 1000, 16000 steps each) | wall s | node-steps/s |"
echo "|---|---:|---:|"
measure "one core, each case alone (--no-batch --jobs 1)" "$bin" sweep "$work/sweep.toml" --out "$work/out" --no-batch --jobs 1
measure "one core, SIMD batches of 4 (--jobs 1)" "$bin" sweep "$work/sweep.toml" --out "$work/out" --jobs 1
measure "two cores, SIMD batches (--jobs 2)" "$bin" sweep "$work/sweep.toml" --out "$work/out" --jobs 2
if command -v mpiexec > /dev/null; then
  measure "mpirun -n 2 (1 dispatcher + 1 worker rank, chunks of 4 batched)" \
    env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpiexec -n 2 --oversubscribe \
    "$bin" sweep "$work/sweep.toml" --out "$work/out"
fi
