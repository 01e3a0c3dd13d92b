#!/usr/bin/env bash
# A bounded fuzzing run of the input layer, for CI: each target starts from
# its tracked corpus and past findings, fuzzes for SECONDS, and fails on any
# finding (crash, sanitizer report, leak, timeout, out of memory). New inputs
# go to a scratch directory, never into the tracked corpus.
#
# Inputs may be as long as 512 KiB: the corpus's long line (4096 bodies,
# edge-long-line.*, 300 KB) must be read whole, not cut to libFuzzer's size.
#
# Usage: run.sh BUILD_DIR SECONDS_PER_TARGET TARGET...   (e.g. run.sh build/fuzz 55 case overrides sweep)
set -euo pipefail
build=$1
seconds=$2
shift 2
here=$(cd "$(dirname "$0")" && pwd)
scratch=$(mktemp -d "${TMPDIR:-/tmp}/barimpact-fuzz.XXXXXX")
keep=0
trap '[ $keep = 1 ] || rm -rf "$scratch"' EXIT
failed=()
for target in "$@"; do
  fuzzer=$build/tests/fuzz/barimpact_fuzz_$target
  mkdir -p "$scratch/$target/new" "$scratch/$target/findings"
  echo "== fuzz $target: ${seconds} s"
  # stdin from /dev/null: a sweep input may name /dev/stdin as its case file.
  if ! "$fuzzer" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=524288 \
      -dict="$here/barimpact.dict" -artifact_prefix="$scratch/$target/findings/" -print_final_stats=1 \
      "$scratch/$target/new" "$here/corpus/$target" "$here/regressions/$target" \
      < /dev/null > "$scratch/$target/log" 2>&1; then
    failed+=("$target")
    keep=1
    tail -n 60 "$scratch/$target/log"
    for f in "$scratch/$target/findings"/*; do
      [ -e "$f" ] || continue
      echo "-- finding $f (base64; save it under tests/fuzz/regressions/$target/ once fixed):"
      base64 -w 0 "$f"
      echo
    done
  else
    grep -E "^(stat::number_of_executed_units|stat::peak_rss_mb|#[0-9]+ +DONE)" "$scratch/$target/log" || true
    echo "   $(ls "$scratch/$target/new" | wc -l) new inputs (not kept)"
  fi
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: findings in ${failed[*]}; logs and inputs in $scratch"
  exit 1
fi
echo "fuzz: no findings"
