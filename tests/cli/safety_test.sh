#!/usr/bin/env bash
# The command line's promises about the user's data and the runs' health:
# the output-directory rule (nothing barimpact did not write is deleted),
# warnings and --strict, interruption by SIGINT / SIGTERM and resumption,
# exit 3 for studies with no result. Usage: safety_test.sh BARIMPACT EXAMPLES_DIR
set -u
. "$(dirname "${BASH_SOURCE[0]}")/preamble.sh"
check() {  # description, then a command that must succeed
  local what=$1
  shift
  if "$@"; then ok; else bad "$what"; fi
}
ex1="$examples/paper-example1.toml"
fast=(--set time.end=0.5 --set output.fields_at=[])

# A user's directory: three files and a subdirectory.
make_user_dir() {
  mkdir -p "$1/data" && echo "my notes" > "$1/notes.txt" && echo 1 > "$1/data/raw.csv" && echo x > "$1/.hidden"
}
user_dir_intact() {
  [ "$(cat "$1/notes.txt" 2> /dev/null)" = "my notes" ] && [ -f "$1/data/raw.csv" ] && [ -f "$1/.hidden" ]
}
# Exit 2, one line on stderr holding the text; the given directory unchanged.
# The command runs in the directory $in (default: the test's own).
in=.
expect_refusal() {  # text, listing-before file, directory, then the arguments
  local want=$1 before=$2 dir=$3
  shift 3
  (cd "$in" && "$bin" "$@") > "$work/out" 2> "$work/err"
  local code=$?
  [ $code -eq 2 ] || { bad "exit $code, not 2, for: $* ($(cat "$work/err"))"; return; }
  [ "$(wc -l < "$work/err")" -eq 1 ] || { bad "not one line for: $*: $(cat "$work/err")"; return; }
  grep -qF -- "$want" "$work/err" || { bad "'$want' not in: $(cat "$work/err")"; return; }
  [ "$(cd "$dir" && ls -lAR --time-style=+ . | md5sum)" = "$before" ] || { bad "$dir changed for: $*"; return; }
  ok
}
listing() { (cd "$1" && ls -lAR --time-style=+ . | md5sum); }

# 1. Output directories.
# A new path and an empty directory are written, with barimpact's marker.
check "new path" "$bin" run "$ex1" --out "$work/new" "${fast[@]}" > /dev/null
check "marker" test -f "$work/new/.barimpact"
mkdir "$work/empty"
check "empty directory" "$bin" run "$ex1" --out "$work/empty" "${fast[@]}" > /dev/null
check "empty directory written" test -f "$work/empty/history.csv"
# A directory barimpact wrote is replaced.
check "replace own" "$bin" run "$examples/paper-example2.toml" --out "$work/new" "${fast[@]}" > /dev/null
check "replaced" grep -q 'body_force = .-1.' "$work/new/case.toml"
# A new subdirectory of a user's directory is fine; the user's files stay.
make_user_dir "$work/mine"
check "subdirectory of a user's directory" "$bin" run "$ex1" --out "$work/mine/run1" "${fast[@]}" > /dev/null
check "user's files beside a new subdirectory" user_dir_intact "$work/mine"
# A user's non-empty directory: refused for every command, nothing touched.
make_user_dir "$work/theirs"
before=$(listing "$work/theirs")
expect_refusal "did not write" "$before" "$work/theirs" run "$ex1" --out "$work/theirs"
expect_refusal "--force" "$before" "$work/theirs" exact "$examples/clamped-periodic.toml" --out "$work/theirs"
expect_refusal "did not write" "$before" "$work/theirs" converge "$ex1" --out "$work/theirs" --levels 2
expect_refusal "did not write" "$before" "$work/theirs" sweep "$examples/sweeps/penalty-to-rigid.toml" \
  --out "$work/theirs"
# plot's --out follows the same rule.
"$bin" run "$ex1" --out "$work/for-plot" "${fast[@]}" > /dev/null || bad "run for plot"
expect_refusal "did not write" "$before" "$work/theirs" plot "$work/for-plot" --out "$work/theirs"
if [ -f "$(dirname "$bin")/python/barimpact/__init__.py" ]; then  # a build with the Python package (figures)
# plot DIR reads the run first, then makes figures/ and lists it in the run
# directory's marker (before drawing: a run directory whose figures failed
# stays barimpact's, and a rerun replaces it). Results it cannot read are
# refused with nothing made (issue 36: an unreadable results.h5 left a
# marked, empty figures/).
"$bin" plot "$work/for-plot" > /dev/null 2>&1 || bad "plot"
check "the marker lists figures after plot" grep -q '"figures"' "$work/for-plot/.barimpact"
"$bin" run "$ex1" --out "$work/bad-plot" "${fast[@]}" > /dev/null || bad "run for a failing plot"
echo "not,numbers" >> "$work/bad-plot/history.csv"
"$bin" plot "$work/bad-plot" > /dev/null 2>&1 && bad "plot of a broken history.csv succeeded"
check "no figures/ for a broken history.csv" test ! -e "$work/bad-plot/figures"
"$bin" run "$ex1" --out "$work/bad-h5" "${fast[@]}" --set output.fields_at=[] --set output.format=hdf5 > /dev/null ||
  bad "run for an unreadable results.h5"
echo "not HDF5" > "$work/bad-h5/results.h5"
expect_refusal "bad-h5/results.h5: cannot be read" "$(listing "$work/bad-h5")" "$work/bad-h5" plot "$work/bad-h5"
# --force reaches the figures: drawn beside the user's files, which stay.
make_user_dir "$work/plot-theirs"
check "plot --force beside a user's files" "$bin" plot "$work/for-plot" --out "$work/plot-theirs" --force > /dev/null
check "the figures beside them" test -s "$work/plot-theirs/energy.svg"
check "the user's files kept by plot --force" user_dir_intact "$work/plot-theirs"
fi
check "a run directory with figures/ is replaced" "$bin" run "$ex1" --out "$work/bad-plot" "${fast[@]}" > /dev/null
# A directory holding only empty directories is the user's, not empty (issue 36).
mkdir -p "$work/empties/a" "$work/empties/b/c"
expect_refusal "did not write" "$(listing "$work/empties")" "$work/empties" run "$ex1" --out "$work/empties"
# --force beside a directory named as one of barimpact's files (issue 36: a
# study wrote three files before it failed): refused before anything is written.
for entry in "summary.json run $ex1" "convergence.md converge $ex1 --levels 2" \
  "sweep.csv sweep $examples/sweeps/penalty-to-rigid.toml"; do
  set -- $entry
  rm -rf "$work/named" && make_user_dir "$work/named" && mkdir "$work/named/$1"
  name=$1
  shift
  expect_refusal "holds a directory $name where barimpact writes a file" "$(listing "$work/named")" "$work/named" \
    "$@" --out "$work/named" --force
done
# ... refused before the work, not after it: a run of minutes is refused at once.
rm -rf "$work/named" && make_user_dir "$work/named" && mkdir "$work/named/summary.json"
timeout 30 "$bin" run "$ex1" --out "$work/named" --force --set bar.elements=20000 --set time.step=1e-5 > /dev/null 2>&1
[ $? -eq 2 ] && ok || bad "a clash with summary.json/ not refused before the run"
for entry in "match.csv match" "pda.csv pda"; do
  set -- $entry
  rm -rf "$work/named" && make_user_dir "$work/named" && mkdir "$work/named/$1"
  expect_refusal "holds a directory $1 where barimpact writes a file" "$(listing "$work/named")" "$work/named" \
    "$2" "$examples/pda/steel-pipe.toml" --out "$work/named" --force
done
# --force writes beside the user's files and deletes none of them.
check "--force beside a user's files" "$bin" run "$ex1" --out "$work/theirs" --force "${fast[@]}" > /dev/null
check "user's files kept under --force" user_dir_intact "$work/theirs"
check "results written under --force" test -s "$work/theirs/history.csv"
# A later run in the other format replaces barimpact's results there, not only adds to them.
check "--force in HDF5 after CSV" "$bin" run "$ex1" --out "$work/theirs" --force "${fast[@]}" --set output.format=hdf5 > /dev/null
check "no stale history.csv beside results.h5" test ! -e "$work/theirs/history.csv" -a ! -e "$work/theirs/fields.csv" -a -s "$work/theirs/results.h5"
check "user's files kept after the format changed" user_dir_intact "$work/theirs"
check "marker lists results.h5, not the CSV files" bash -c "grep -q results.h5 '$work/theirs/.barimpact' && ! grep -q history.csv '$work/theirs/.barimpact'"
check "--force back to CSV" "$bin" run "$ex1" --out "$work/theirs" --force "${fast[@]}" > /dev/null
check "no stale results.h5 beside history.csv" test ! -e "$work/theirs/results.h5" -a -s "$work/theirs/history.csv"
# ... and the directory stays the user's: without --force it is still refused.
before=$(listing "$work/theirs")
expect_refusal "did not write" "$before" "$work/theirs" run "$ex1" --out "$work/theirs"
# A user's file put into a run directory makes it the user's too.
echo "mine" > "$work/new/notes.txt"
before=$(listing "$work/new")
expect_refusal "notes.txt" "$before" "$work/new" run "$ex1" --out "$work/new"
check "--force keeps the note" "$bin" run "$ex1" --out "$work/new" --force "${fast[@]}" > /dev/null
check "note kept" grep -q mine "$work/new/notes.txt"
# A user's file inside one of barimpact's subdirectories (a sweep's runs/) makes it the user's.
"$bin" sweep "$examples/sweeps/penalty-to-rigid.toml" --out "$work/nested" > /dev/null 2>&1 || bad "sweep nested"
echo mine > "$work/nested/runs/notes.txt"
before=$(listing "$work/nested")
expect_refusal "runs/notes.txt" "$before" "$work/nested" run "$ex1" --out "$work/nested"
# A link given as --out is written through, never replaced.
mkdir "$work/linked" && ln -s "$work/linked" "$work/link"
check "--out a link" "$bin" run "$ex1" --out "$work/link" "${fast[@]}" > /dev/null
check "the link stays a link" test -L "$work/link"
check "written through the link" test -s "$work/linked/history.csv"
# A .barimpact of the user's is never taken for a marker, nor replaced by one.
mkdir "$work/fake" && echo "my notes" > "$work/fake/.barimpact"
before=$(listing "$work/fake")
expect_refusal ".barimpact" "$before" "$work/fake" run "$ex1" --out "$work/fake" --force
# converge --force beside a user's runs/: the user's own run stays.
mkdir -p "$work/study/runs"
"$bin" run "$ex1" --out "$work/study/runs/baseline" "${fast[@]}" > /dev/null || bad "baseline run"
"$bin" converge "$ex1" --out "$work/study" --force --levels 2 "${fast[@]}" > /dev/null 2>&1 || bad "converge --force"
check "the user's run kept by converge" test -s "$work/study/runs/baseline/history.csv"
# A misspelled --vary key is bad input: exit 2, nothing written.
"$bin" converge "$ex1" --out "$work/vary-typo" --vary nosuch.key=1,2 > /dev/null 2> "$work/err"
[ $? -eq 2 ] && [ ! -e "$work/vary-typo" ] && grep -q -- "--vary" "$work/err" && ok || bad "--vary typo: $(cat "$work/err")"
# The working directory: refused; with --force, written beside.
make_user_dir "$work/cwd"
before=$(listing "$work/cwd")
in="$work/cwd" expect_refusal "working directory" "$before" "$work/cwd" run "$ex1" --out .
(cd "$work/cwd" && "$bin" run "$ex1" --out . --force "${fast[@]}" > /dev/null) && ok || bad "--out . --force"
check "cwd files kept" user_dir_intact "$work/cwd"
check "cwd results" test -s "$work/cwd/summary.json"
# "/", the home directory and the working directory's parents: refused even with --force.
mkdir -p "$work/home/me/project/deep"
make_user_dir "$work/home/me"
home_before=$(listing "$work/home")
deep="$work/home/me/project/deep"
for force in "" --force; do
  HOME="$work/home/me" in=$deep expect_refusal "home directory" "$home_before" "$work/home" \
    run "$ex1" --out "$work/home/me" $force
  HOME="$work/home/me/" in=$deep expect_refusal "home directory" "$home_before" "$work/home" \
    run "$ex1" --out "$work/home/me/project/.." $force
  in=$deep expect_refusal "parent of the working directory" "$home_before" "$work/home" run "$ex1" --out .. $force
  in=$deep expect_refusal "parent of the working directory" "$home_before" "$work/home" \
    run "$ex1" --out "$work/home/me/project" $force
  in=$deep expect_refusal "parent of the working directory" "$home_before" "$work/home" \
    sweep "$examples/sweeps/penalty-to-rigid.toml" --out ../.. $force
  in=$deep expect_refusal "parent of the working directory" "$home_before" "$work/home" \
    converge "$ex1" --out ../../.. $force
  "$bin" run "$ex1" --out / $force > /dev/null 2> "$work/err"
  [ $? -eq 2 ] && grep -q "root directory" "$work/err" && ok || bad "--out / $force: $(cat "$work/err")"
done
# A staging directory left by a killed process is cleaned up; none is left behind.
mkdir "$work/stale" && mkdir "$work/.kept.partial-999999999" && touch "$work/.kept.partial-999999999/.barimpact-staging"
echo mine > "$work/.results.old-1999"  # a user's file that looks like staging stays
check "run beside stale staging" "$bin" run "$ex1" --out "$work/kept" "${fast[@]}" > /dev/null
ls -a "$work" | grep -q partial && bad "stale staging left" || ok
check "a user's look-alike file kept" grep -q mine "$work/.results.old-1999"
# What a command reads is never written over, --force or not. The case run
# into its own directory with --force: the user's case.toml stays as it is
# (comments and all), the resolved case goes to case.resolved.toml, which
# what reads the run back takes.
mkdir "$work/proj" && { echo "# my comments"; cat "$ex1"; } > "$work/proj/case.toml"
cp "$work/proj/case.toml" "$work/case-before.toml"
check "run into the case's directory" "$bin" run "$work/proj/case.toml" --out "$work/proj" --force "${fast[@]}" > /dev/null
check "the user's case.toml kept" cmp -s "$work/proj/case.toml" "$work/case-before.toml"
check "the resolved case beside it" grep -q '^end = 0.5' "$work/proj/case.resolved.toml"
check "exact into the case's directory" "$bin" exact "$work/proj/case.toml" --out "$work/proj" --force \
  --set time.end=0.25 --set output.fields_at=[] > /dev/null
check "the user's case.toml kept by exact" cmp -s "$work/proj/case.toml" "$work/case-before.toml"
check "exact's resolved case" grep -q '^end = 0.25' "$work/proj/case.resolved.toml"
(cd "$work/proj" && "$bin" run case.toml --out . --force "${fast[@]}" > /dev/null) && ok || bad "run case.toml --out ."
check "the user's case.toml kept from its directory" cmp -s "$work/proj/case.toml" "$work/case-before.toml"
# A case read from a directory barimpact would replace: refused, --force or not.
"$bin" run "$ex1" --out "$work/rerun" "${fast[@]}" > /dev/null || bad "run for a rerun"
before=$(listing "$work/rerun")
for force in "" --force; do
  expect_refusal "--out $work/rerun: holds $work/rerun/case.toml, which this command reads" "$before" "$work/rerun" \
    run "$work/rerun/case.toml" --out "$work/rerun" $force
  expect_refusal "which this command reads" "$before" "$work/rerun" converge "$work/rerun/case.toml" \
    --out "$work/rerun" --levels 2 $force
done
expect_refusal "is the file this command reads" "$before" "$work/rerun" \
  run "$work/rerun/case.toml" --out "$work/rerun/case.toml" --force
# A sweep's file and its case beside a sweep run into their directory stay.
mkdir "$work/sweep-here" && cp "$ex1" "$work/sweep-here/case.toml"
printf '%b' 'case = "case.toml"\n[set]\ntime.end = 0.5\noutput.fields_at = []\n[[axis]]\nkey = "bar.elements"\nvalues = [50, 100]\n' \
  > "$work/sweep-here/sweep.toml"
cp -r "$work/sweep-here" "$work/sweep-before"
check "sweep into its own directory" "$bin" sweep "$work/sweep-here/sweep.toml" --out "$work/sweep-here" --force > /dev/null
check "the sweep's inputs kept" diff -q "$work/sweep-here/sweep.toml" "$work/sweep-before/sweep.toml"
check "the sweep's case kept" diff -q "$work/sweep-here/case.toml" "$work/sweep-before/case.toml"
# A sweep whose case lies in a directory barimpact would resume in: refused.
printf 'case = "%s"\n[[axis]]\nkey = "bar.elements"\nvalues = [50, 100]\n' "$work/rerun/case.toml" > "$work/sweep-rerun.toml"
expect_refusal "which this command reads" "$before" "$work/rerun" sweep "$work/sweep-rerun.toml" --out "$work/rerun" --force
# hopkinson: a signal file of the name of one of its results is refused, not replaced.
"$bin" run "$examples/hopkinson/shpb.toml" --out "$work/shpb" > /dev/null 2>&1 || bad "shpb run"
mkdir "$work/signals"
for g in incident transmitted; do
  awk -F, -v g="gauge.$g.strain" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == g) c = i; print "t,strain"; next }
    { print $1 "," $c }' "$work/shpb/history.csv" > "$work/signals/$g.csv"
done
mv "$work/signals/incident.csv" "$work/signals/hopkinson.csv"
printf '[bar]\nmodulus = 200e9\ndensity = 7850.0\ndiameter = 0.020\n[specimen]\nlength = 0.006\ndiameter = 0.010\n%b\n%b\n' \
  '[incident]\nsignal = "hopkinson.csv"\ngauge_to_specimen = 0.75' \
  '[transmitted]\nsignal = "transmitted.csv"\ngauge_to_specimen = 0.75' > "$work/signals/setup.toml"
before=$(listing "$work/signals")
expect_refusal "would write hopkinson.csv over" "$before" "$work/signals" hopkinson "$work/signals/setup.toml" \
  --out "$work/signals" --force --no-plot
# The directory a command reads, or a parent of it: refused even with --force
# (hopkinson analysing a run into that run's directory replaced it).
sed "s|run = .*|run = \"$work/shpb\"|" "$examples/hopkinson/analyse-run.toml" > "$work/analyse-shpb.toml"
before=$(listing "$work/shpb")
for force in "" --force; do
  expect_refusal "--out $work/shpb: is the directory this command reads" "$before" "$work/shpb" \
    hopkinson "$work/analyse-shpb.toml" --out "$work/shpb" --no-plot $force
  expect_refusal "--out $work/shpb: is the directory this command reads" "$before" "$work/shpb" \
    plot "$work/shpb" --out "$work/shpb" $force
done
mkdir -p "$work/outer/inner"
"$bin" run "$examples/hopkinson/shpb.toml" --out "$work/outer/inner/run" > /dev/null 2>&1 || bad "run for a parent"
sed "s|run = .*|run = \"$work/outer/inner/run\"|" "$examples/hopkinson/analyse-run.toml" > "$work/analyse-inner.toml"
before=$(listing "$work/outer")
expect_refusal "is a parent of $work/outer/inner/run, a directory this command reads" "$before" "$work/outer" \
  plot "$work/outer/inner/run" --out "$work/outer" --force
expect_refusal "a directory this command reads" "$before" "$work/outer" \
  hopkinson "$work/analyse-inner.toml" --out "$work/outer/inner" --force
check "the analysed run kept" test -s "$work/shpb/history.csv"

# 2. Warnings and --strict.
"$bin" run "$ex1" --out "$work/stiff" --set obstacle.stiffness=1e4 --set time.step=0.001 --set output.fields_at=[] \
  > /dev/null 2> "$work/err"
code=$?
[ $code -eq 0 ] && ok || bad "unresolved run exit $code"
grep -q "^barimpact: warning: energy-balance" "$work/err" && ok || bad "energy warning: $(cat "$work/err")"
grep -q "^barimpact: warning: penalty-unresolved" "$work/err" && ok || bad "penalty warning: $(cat "$work/err")"
/usr/bin/python3 -c "import json,sys; w=json.load(open(sys.argv[1]))['warnings']; sys.exit(0 if {x.split(':')[0] for x in w} == {'energy-balance', 'penalty-unresolved', 'contact-chatter'} else 1)" \
  "$work/stiff/summary.json" && ok || bad "summary warnings"
"$bin" run "$ex1" --out "$work/stiff" --strict --set obstacle.stiffness=1e4 --set time.step=0.001 \
  --set output.fields_at=[] > /dev/null 2>&1
[ $? -eq 4 ] && ok || bad "--strict exit"
check "--strict keeps the results" test -s "$work/stiff/history.csv"
"$bin" run "$ex1" --out "$work/healthy" --strict > /dev/null 2> "$work/err" && ok || bad "healthy --strict"
[ ! -s "$work/err" ] && ok || bad "healthy run warned: $(cat "$work/err")"
grep -q '"warnings": \[\]' "$work/healthy/summary.json" && ok || bad "empty warnings list"

# 3. Studies with no result: the report is written, orders are nan, exit 3.
blow=(--set time.alpha=0 --set time.step=0.1 --set time.end=40)
"$bin" converge "$ex1" --out "$work/conv-blow" --levels 3 "${blow[@]}" > /dev/null 2> "$work/err"
[ $? -eq 3 ] && ok || bad "converge with no result: exit $?"
check "converge report written" test -s "$work/conv-blow/convergence.csv"
/usr/bin/python3 - "$work/conv-blow/convergence.csv" << 'EOF' && ok || bad "converge orders of failed runs"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert rows and all(r["status"] == "non-finite" for r in rows), rows
assert all(r["order_U"] == "nan" and r["error_U_max"] == "nan" for r in rows), rows
EOF
grep -q "partial" "$work/conv-blow/convergence.md" && bad "converge names staging paths" || ok
printf 'case = "%s"\n[set]\ntime.alpha = 0.0\ntime.step = 0.1\ntime.end = 40.0\n[[axis]]\nkey = "bar.elements"\nvalues = [100, 200]\n' \
  "$ex1" > "$work/blow-sweep.toml"
"$bin" sweep "$work/blow-sweep.toml" --out "$work/sweep-blow" > /dev/null 2>&1
[ $? -eq 3 ] && ok || bad "sweep with no result: exit $?"
check "sweep report written" test -s "$work/sweep-blow/sweep.csv"

# 4. Interruption: the step under way ends, what was done is written, exit 128 + signal.
long=(--set bar.elements=1000 --set time.step=0.001 --set time.end=100000 --set output.every=1000
  --set output.fields_at=[])
for signal in INT TERM; do
  "$bin" run "$ex1" --out "$work/stop-$signal" "${long[@]}" > /dev/null 2> "$work/err" &
  pid=$!
  sleep 1
  kill -s $signal $pid
  wait $pid 2> /dev/null
  code=$?
  want=$([ $signal = INT ] && echo 130 || echo 143)
  [ $code -eq "$want" ] && ok || bad "SIG$signal: exit $code, not $want"
  grep -q '"status": "interrupted"' "$work/stop-$signal/summary.json" && ok || bad "SIG$signal: status"
  grep -q '"complete": false' "$work/stop-$signal/summary.json" && ok || bad "SIG$signal: complete"
  [ "$(wc -l < "$work/stop-$signal/history.csv")" -gt 2 ] && ok || bad "SIG$signal: rows kept"
  ls -a "$work" | grep -q partial && bad "SIG$signal: staging left" || ok
done

# exact is interrupted the same way.
"$bin" exact "$examples/clamped-periodic.toml" --out "$work/stop-exact" "${long[@]}" > /dev/null 2>&1 &
pid=$!
sleep 1
kill -s INT $pid
wait $pid
[ $? -eq 130 ] && ok || bad "exact SIGINT"
grep -q '"status": "interrupted"' "$work/stop-exact/summary.json" && ok || bad "exact: status"

# A sweep or converge interrupted (SIGINT, SIGTERM or SIGKILL) and rerun ends as an uninterrupted one.
printf 'case = "%s"\n[set]\ntime.end = 10.0\ntime.step = 1e-4\noutput.fields_at = []\noutput.every = 100\n[[axis]]\nkey = "bar.elements"\nvalues = [400, 500, 600, 700, 800, 900]\n[[axis]]\nkey = "obstacle.stiffness"\nvalues = [100.0, 200.0]\n' \
  "$ex1" > "$work/slow-sweep.toml"
"$bin" sweep "$work/slow-sweep.toml" --out "$work/sweep-whole" --jobs 2 > /dev/null 2>&1 || bad "whole sweep"
without_timing() {  # sweep.csv or convergence.csv less its timing column
  /usr/bin/python3 -c "
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
for r in rows:
    r.pop('run_seconds', None); r.pop('cpu_seconds', None)
print(rows)" "$1"
}
# Signals a background command once its first run is kept (the rest still to do).
signal_after_first_run() {  # signal, pid, runs directory
  local i
  for i in $(seq 1 2000); do
    ls "$3"/*/summary.json > /dev/null 2>&1 && break
    sleep 0.01
  done
  kill -0 "$2" 2> /dev/null || bad "the command ended before SIG$1 reached it"
  kill -s "$1" "$2"
}
for signal in INT TERM KILL; do
  "$bin" sweep "$work/slow-sweep.toml" --out "$work/sweep-$signal" --jobs 2 > /dev/null 2>&1 &
  pid=$!
  signal_after_first_run $signal $pid "$work/sweep-$signal/runs"
  wait $pid 2> /dev/null
  code=$?
  case $signal in INT) want=130 ;; TERM) want=143 ;; KILL) want=137 ;; esac
  [ $code -eq $want ] && ok || bad "sweep SIG$signal: exit $code"
  "$bin" sweep "$work/slow-sweep.toml" --out "$work/sweep-$signal" --jobs 2 > /dev/null 2>&1 && ok ||
    bad "sweep rerun after SIG$signal"
  [ "$(without_timing "$work/sweep-$signal/sweep.csv")" = "$(without_timing "$work/sweep-whole/sweep.csv")" ] &&
    ok || bad "sweep after SIG$signal differs from the uninterrupted one"
  find "$work/sweep-$signal" -name '*partial*' | grep -q . && bad "sweep SIG$signal: leftovers" || ok
done
# A sweep killed while it replaced sweep.csv leaves its staged copy: the rerun takes it as its own (a live
# writer's stays; a dead one's goes), never as someone else's file to refuse.
sleep 0 & wait $!; dead=$!
printf 'x\n' > "$work/sweep-whole/.sweep.csv.partial-$dead"
printf 'x\n' > "$work/sweep-whole/.sweep.csv.partial-$$"
"$bin" sweep "$work/slow-sweep.toml" --out "$work/sweep-whole" --jobs 2 > /dev/null 2>&1 && ok || bad "sweep rerun beside a staged sweep.csv"
[ ! -e "$work/sweep-whole/.sweep.csv.partial-$dead" ] && ok || bad "a killed writer's staged sweep.csv stays"
[ -e "$work/sweep-whole/.sweep.csv.partial-$$" ] && ok || bad "a live writer's staged sweep.csv was removed"
rm -f "$work/sweep-whole/.sweep.csv.partial-$$"
study=(converge "$ex1" --levels 3 --refine both --set time.end=4 --set bar.elements=1000 --set time.step=5e-4 --jobs 2)
"$bin" "${study[@]}" --out "$work/conv-whole" > /dev/null 2>&1 || bad "whole converge"
for signal in INT KILL; do
  "$bin" "${study[@]}" --out "$work/conv-$signal" > /dev/null 2>&1 &
  pid=$!
  signal_after_first_run $signal $pid "$work/conv-$signal/runs"
  wait $pid 2> /dev/null
  code=$?
  [ $code -eq $([ $signal = INT ] && echo 130 || echo 137) ] && ok || bad "converge SIG$signal: exit $code"
  "$bin" "${study[@]}" --out "$work/conv-$signal" > /dev/null 2>&1 && ok || bad "converge rerun after SIG$signal"
  [ "$(without_timing "$work/conv-$signal/convergence.csv")" = "$(without_timing "$work/conv-whole/convergence.csv")" ] &&
    ok || bad "converge after SIG$signal differs from the uninterrupted one"
  find "$work/conv-$signal" -name '*partial*' | grep -q . && bad "converge SIG$signal: leftovers" || ok
done

echo "safety: $passed passed, $failed failed"
[ $failed -eq 0 ]
