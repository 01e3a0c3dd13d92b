#!/usr/bin/env bash
# A full disk: every command that writes results, on a file system too
# small for them, ends with one error line naming the path and the system's
# reason (warnings may come before it), exits 2, leaves nothing staged
# behind and deletes nothing of the user's. Usage: full_disk_test.sh
# BARIMPACT EXAMPLES_DIR. It mounts small tmpfs file systems, which needs
# root: without, or when the mount fails, it says so and exits 77 (ctest's
# SKIP_RETURN_CODE: reported as skipped, never as passed).
set -u
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
examples=$(cd "$2" && pwd)
work=$(mktemp -d)
disk="$work/disk"
mkdir "$disk"
cleanup() {
  mountpoint -q "$disk" && umount "$disk"
  rm -rf "$work"
}
trap cleanup EXIT
skip() {
  echo "SKIPPED: $*"
  exit 77
}
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*"; }
ex1="$examples/paper-example1.toml"

[ "$(id -u)" -eq 0 ] || skip "not root: cannot mount a small tmpfs to fill"
# A new, empty file system of the given size on $disk.
fresh() {
  if mountpoint -q "$disk"; then umount "$disk" || skip "cannot unmount $disk"; fi
  mount -t tmpfs -o "size=$1" tmpfs "$disk" 2> "$work/mount" || skip "cannot mount a tmpfs: $(cat "$work/mount")"
}
listing() { (cd "$1" && ls -lAR --time-style=+ . | md5sum); }

# Runs barimpact with the arguments; it must exit 2 with one error line (the
# last, after warnings only) naming `path` and "No space left on device",
# and leave no staging directory or staged file anywhere on the disk.
expect_full() {  # path, then the arguments
  local path=$1
  shift
  "$bin" "$@" > "$work/out" 2> "$work/err"
  local code=$?
  [ $code -eq 2 ] || { bad "exit $code, not 2, for: $* ($(tail -3 "$work/err"))"; return; }
  local others
  others=$(grep -cv '^barimpact: warning: ' "$work/err")
  [ "$others" -eq 1 ] || { bad "not one error line for: $*: $(cat "$work/err")"; return; }
  local line
  line=$(tail -1 "$work/err")
  case "$line" in
    "barimpact: error: "*"$path"*"No space left on device"*) ;;
    *) bad "the error does not name $path and the reason, for: $*: $line"; return ;;
  esac
  local left
  left=$(find "$disk" \( -name '*.partial-*' -o -name '.barimpact.[0-9]*' -o -name '*.old-*' \) | head -3)
  [ -z "$left" ] || { bad "left behind for: $*: $left"; return; }
  ok
}

# run: CSV and HDF5, into a new path (its missing parents are removed again).
fresh 200k
expect_full "$disk/ex1" run "$ex1" --out "$disk/ex1"
[ ! -e "$disk/ex1" ] && ok || bad "a half-written ex1 is there"
expect_full "$disk/made/below/ex1" run "$ex1" --out "$disk/made/below/ex1"
[ ! -e "$disk/made" ] && ok || bad "the parents made for the run are left"
fresh 200k
expect_full "$disk/ex1-h5" run "$ex1" --out "$disk/ex1-h5" --set output.format=hdf5
[ -z "$(ls -A "$disk")" ] && ok || bad "the HDF5 run left: $(ls -A "$disk")"
# results.h5 filling the disk at its end (its history, and what HDF5 writes
# as it closes the file): the same one line, no crash at exit.
fresh 32k
expect_full "$disk/h5-end" run "$ex1" --out "$disk/h5-end" --set output.format=hdf5 --set output.fields_at=[]
[ -z "$(ls -A "$disk")" ] && ok || bad "the HDF5 run filling the disk at its end left: $(ls -A "$disk")"
fresh 100k
expect_full "$disk/exact" exact "$examples/clamped-periodic.toml" --out "$disk/exact"

# A run directory barimpact wrote, replaced by results that do not fit: the
# old results stay as they were.
fresh 200k
"$bin" run "$ex1" --out "$disk/old" --set time.end=0.5 --set output.fields_at=[] > /dev/null 2>&1 && ok ||
  bad "a small run does not fit"
before=$(listing "$disk/old")
expect_full "$disk/old" run "$ex1" --out "$disk/old"
[ "$(listing "$disk/old")" = "$before" ] && ok || bad "the results replaced in vain have changed"

# --force into the user's directory: their files stay, nothing is added.
fresh 200k
mkdir -p "$disk/mine/data" && echo "my notes" > "$disk/mine/notes.txt" && echo 1 > "$disk/mine/data/raw.csv"
before=$(listing "$disk/mine")
expect_full "$disk/mine" run "$ex1" --out "$disk/mine" --force
[ "$(listing "$disk/mine")" = "$before" ] && ok || bad "--force: the user's directory changed"
[ "$(cat "$disk/mine/notes.txt")" = "my notes" ] && ok || bad "--force: the user's file changed"

# sweep (runs written by worker threads) and converge: the runs written
# whole before the disk filled stay (a rerun resumes), each with its marker.
fresh 200k
expect_full "$disk/sweep" sweep "$examples/sweeps/penalty-to-rigid.toml" --out "$disk/sweep" --jobs 2
for run in "$disk"/sweep/runs/*; do
  [ -e "$run" ] || continue
  [ -f "$run/.barimpact" ] && [ -f "$run/summary.json" ] && ok || bad "a sweep run is not whole: $run"
done
fresh 64k
expect_full "$disk/converge" converge "$ex1" --out "$disk/converge" --levels 2

# hopkinson: the analysis of a run's gauges into a disk too small for it.
"$bin" run "$examples/hopkinson/shpb.toml" --out "$work/shpb" --set output.fields_at=[] > /dev/null 2>&1 && ok ||
  bad "shpb run"
cat > "$work/analyse.toml" << TOML
[specimen]
body = "specimen"
[incident]
run = "$work/shpb"
gauge = "incident"
[transmitted]
run = "$work/shpb"
gauge = "transmitted"
TOML
fresh 100k
expect_full "$disk/hk" hopkinson "$work/analyse.toml" --out "$disk/hk" --no-plot
# With its figures (a build with the Python package): hopkinson.csv fits, a
# figure does not; the figures' child says so in the one line.
if [ -f "$(dirname "$bin")/python/barimpact/__init__.py" ]; then
  fresh 360k
  expect_full "$disk/hk/figures/waves." hopkinson "$work/analyse.toml" --out "$disk/hk"
  [ -z "$(ls -A "$disk")" ] && ok || bad "hopkinson with figures left: $(ls -A "$disk")"
fi

echo "full_disk_test: $passed passed, $failed failed"
[ $failed -eq 0 ]
