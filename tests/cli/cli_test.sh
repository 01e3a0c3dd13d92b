#!/usr/bin/env bash
# The command line's contract: files and columns, exit codes, one-line errors,
# nothing written on bad input. Usage: cli_test.sh BARIMPACT EXAMPLES_DIR
set -u
. "$(dirname "${BASH_SOURCE[0]}")/preamble.sh"

# A run writes the four files; history.csv starts with the contract's columns.
if "$bin" run "$examples/paper-example1.toml" --out "$work/ex1" > "$work/stdout" 2> "$work/stderr"; then ok; else bad "example 1 exit $?"; fi
for f in history.csv fields.csv case.toml summary.json; do
  [ -s "$work/ex1/$f" ] && ok || bad "missing $f"
done
[ "$(head -1 "$work/ex1/history.csv")" = "t,U,V,R,E_kin,E_strain,E_obstacle,W_ext,D_visc,D_contact,D_plastic" ] && ok || bad "history columns"
[ "$(head -1 "$work/ex1/fields.csv")" = "t,x,u,v,sigma,eps_p,body" ] && ok || bad "fields columns"
[ "$(wc -l < "$work/ex1/history.csv")" -eq 402 ] && ok || bad "history rows: $(wc -l < "$work/ex1/history.csv")"
[ "$(wc -l < "$work/ex1/fields.csv")" -eq $((101 * 101 + 1)) ] && ok || bad "fields rows"
grep -q '"complete": true' "$work/ex1/summary.json" && ok || bad "summary complete"
grep -q "contact 1" "$work/stdout" && ok || bad "stdout summary"
ls -a "$work" | grep -q partial && bad "staging left behind" || ok

# The resolved case.toml repeats the run exactly.
"$bin" run "$work/ex1/case.toml" --out "$work/again" > /dev/null && ok || bad "rerun from case.toml"
cmp -s "$work/ex1/history.csv" "$work/again/history.csv" && ok || bad "rerun differs"

# Rows at 0, N, 2N, ... and always the last step.
"$bin" run "$examples/paper-example1.toml" --out "$work/every" --set output.every=7 > /dev/null && ok || bad "every"
[ "$(tail -1 "$work/every/history.csv" | cut -d, -f1)" = "4" ] && ok || bad "last row at t = 4"
[ "$(wc -l < "$work/every/history.csv")" -eq $((400 / 7 + 1 + 1 + 1)) ] && ok || bad "every rows"

# Rerunning into an existing directory replaces it.
"$bin" run "$examples/paper-example2.toml" --out "$work/ex1" > /dev/null && ok || bad "replace"
grep -q 'body_force = .-1.' "$work/ex1/case.toml" && ok || bad "replaced case"

# output.format = "hdf5": results.h5 for history.csv and fields.csv, listed
# in the marker as barimpact's (a rerun replaces the directory).
"$bin" run "$examples/paper-example1.toml" --out "$work/h5" --set output.format=hdf5 > /dev/null && ok || bad "hdf5 run"
for f in results.h5 case.toml summary.json; do [ -s "$work/h5/$f" ] && ok || bad "hdf5 run: missing $f"; done
for f in history.csv fields.csv; do [ ! -e "$work/h5/$f" ] && ok || bad "hdf5 run wrote $f"; done
grep -q '"results.h5"' "$work/h5/.barimpact" && ok || bad "results.h5 not in the marker"
grep -q '^format = "hdf5"$' "$work/h5/case.toml" && ok || bad "output.format not in case.toml"
"$bin" run "$work/h5/case.toml" --out "$work/h5-rerun" > /dev/null && cmp -s "$work/h5/case.toml" "$work/h5-rerun/case.toml" &&
  [ -s "$work/h5-rerun/results.h5" ] && ok || bad "hdf5 rerun"
"$bin" run "$examples/paper-example1.toml" --out "$work/h5" > /dev/null && [ -s "$work/h5/history.csv" ] &&
  [ ! -e "$work/h5/results.h5" ] && ok || bad "a csv run does not replace an hdf5 one whole"

# Bad input: exit 2, one line on stderr naming the key or option, nothing written.
ex1="$examples/paper-example1.toml"
expect_refused "bar.stiffness" run "$ex1" --out "$work/refused" --set bar.stiffness=0
expect_refused "bar.density" run "$ex1" --out "$work/refused" --set bar.density=-1
expect_refused "bar.viscosity" run "$ex1" --out "$work/refused" --set bar.viscosity=-1
expect_refused "bar.length" run "$ex1" --out "$work/refused" --set bar.length=0
expect_refused "bar.elements" run "$ex1" --out "$work/refused" --set bar.elements=0
expect_refused "obstacle.stiffness" run "$ex1" --out "$work/refused" --set obstacle.stiffness=-1
expect_refused "time.step" run "$ex1" --out "$work/refused" --set time.step=0
expect_refused 'output.format must be "csv" or "hdf5" (got "netcdf")' run "$ex1" --out "$work/refused" --set output.format=netcdf
expect_refused "time.end" run "$ex1" --out "$work/refused" --set time.end=0.001
expect_refused "time.alpha" run "$ex1" --out "$work/refused" --set time.alpha=0.75
expect_refused "time.lambda" run "$ex1" --out "$work/refused" --set time.lambda=-0.5
expect_refused "output.every" run "$ex1" --out "$work/refused" --set output.every=0
expect_refused "unknown key bar.mass" run "$ex1" --out "$work/refused" --set bar.mass=1
expect_refused "must be a number" run "$ex1" --out "$work/refused" --set bar.length=long
expect_refused "initial.velocity" run "$ex1" --out "$work/refused" --set 'initial.velocity=-1 +* x'
expect_refused 'unknown name "z"' run "$ex1" --out "$work/refused" --set 'load.body_force=z'
expect_refused "finite" run "$ex1" --out "$work/refused" --set 'initial.displacement=log(x)'
expect_refused "no such case file" run "$work/nope.toml" --out "$work/refused"
# --out's missing parents are made when the results are written, and a
# refusal leaves none behind.
"$bin" run "$ex1" --out "$work/new/parents/ex1" > /dev/null 2>&1 && [ -s "$work/new/parents/ex1/history.csv" ] && ok || bad "run into new parents"
"$bin" run "$ex1" --out "$work/made/ex1" --set time.step=-1 > /dev/null 2>&1
[ $? -eq 2 ] && [ ! -e "$work/made" ] && ok || bad "a refused run left its --out parents"
"$bin" exact "$examples/clamped-periodic.toml" --out "$work/new/exact/e" > /dev/null 2>&1 && [ -s "$work/new/exact/e/history.csv" ] && ok || bad "exact into new parents"
"$bin" converge "$ex1" --out "$work/new/study/c" --levels 2 > /dev/null 2>&1 && [ -s "$work/new/study/c/convergence.csv" ] && ok || bad "converge into new parents"
if [ -f "$(dirname "$bin")/python/barimpact/__init__.py" ]; then  # a build with the Python package (figures)
  "$bin" plot "$work/new/parents/ex1" --out "$work/new/figs/f" > /dev/null 2>&1 && [ -s "$work/new/figs/f/displacement.png" ] && ok || bad "plot --out into new parents"
fi
: > "$work/plainfile"
expect_refused "is not a directory" run "$ex1" --out "$work/plainfile/dir"
expect_refused "--out" run "$ex1" --out "$ex1"
expect_refused "--out" run "$ex1" --out /proc/barimpact-cannot-write-here
expect_refused "--set" run "$ex1" --out "$work/refused" --set nodot
expect_refused "--out" run "$ex1"
expect_refused "run" bogus
printf '[bar]\nlength = 1\n[time]\nstep = "0.1"\n' > "$work/typed.toml"
expect_refused "typed.toml:4" run "$work/typed.toml" --out "$work/refused"
printf '[bar]\nlength = 1\n[extra]\n' > "$work/section.toml"
expect_refused "unknown section [extra]" run "$work/section.toml" --out "$work/refused"
printf '[bar\n' > "$work/broken.toml"
expect_refused "broken.toml:1" run "$work/broken.toml" --out "$work/refused"
chmod 000 "$work/typed.toml"
if [ "$(id -u)" -ne 0 ]; then expect_refused "cannot read" run "$work/typed.toml" --out "$work/refused"; fi
ro="$work/readonly"
mkdir "$ro" && chmod 555 "$ro"
if [ "$(id -u)" -ne 0 ]; then expect_refused "--out" run "$ex1" --out "$ro/x"; fi

# A run that blows up: exit 3, the step named, rows so far kept, marked incomplete.
"$bin" run "$ex1" --out "$work/blow" --set time.alpha=0 --set time.step=0.1 --set time.end=400 \
  > /dev/null 2> "$work/err"
code=$?
[ $code -eq 3 ] && ok || bad "non-finite exit $code"
grep -q "step" "$work/err" && ok || bad "non-finite message: $(cat "$work/err")"
grep -q '"complete": false' "$work/blow/summary.json" && ok || bad "incomplete mark"
[ "$(wc -l < "$work/blow/history.csv")" -gt 2 ] && ok || bad "rows kept"

# Every scheme runs every example it fits; the others are refused with the
# schemes that can named. The characteristic relations carry no body force.
rigid_schemes="central-difference paoli-schatzman moreau-jean mass-redistribution characteristic"
penalty_schemes="paper newmark central-difference paoli-schatzman"
for ex in "$examples"/*.toml; do
  name=$(basename "$ex" .toml)
  kind=$(grep -E '^kind' "$ex" | head -1 | sed 's/.*"\(.*\)".*/\1/')
  grep -qE '^body_force = "-1"' "$ex" && rigid_schemes_here=${rigid_schemes% characteristic} || rigid_schemes_here=$rigid_schemes
  small=0.002
  [ "$name" = steel-bar ] && small=1e-6
  for scheme in paper newmark central-difference paoli-schatzman moreau-jean mass-redistribution characteristic; do
    args=(run "$ex" --out "$work/scheme-run" --set "time.scheme=$scheme" --set output.fields_at=[])
    case $scheme in
      characteristic) ;;
      paper | newmark | moreau-jean | mass-redistribution) [ "$name" = steel-bar ] && args+=(--set "time.step=$small") ;;
      *) args+=(--set "time.step=$small") ;;
    esac
    fits=no
    if [ "$kind" = rigid ]; then
      case " $rigid_schemes_here " in *" $scheme "*) fits=yes ;; esac
    else
      case " $penalty_schemes " in *" $scheme "*) fits=yes ;; esac
    fi
    "$bin" "${args[@]}" > /dev/null 2> "$work/err"
    code=$?
    if [ $fits = yes ]; then
      [ $code -eq 0 ] && ok || bad "$scheme on $name: exit $code: $(cat "$work/err")"
    else
      [ $code -eq 2 ] && grep -q "schemes that can" "$work/err" && ok || bad "$scheme on $name not refused: $code $(cat "$work/err")"
    fi
  done
done
expect_refused "stable limit" run "$ex1" --out "$work/refused" --set time.scheme=central-difference
expect_refused "conflicts with characteristic" run "$examples/clamped-periodic.toml" --out "$work/refused" --set time.step=0.02
expect_refused 'viscous body "bar"' run "$examples/clamped-periodic.toml" --out "$work/refused" --set bar.viscosity=0.1
expect_refused "time.restitution" run "$ex1" --out "$work/refused" --set time.restitution=2
expect_refused "bar.far_end" run "$ex1" --out "$work/refused" --set bar.far_end=pinned
expect_refused "vanish at the clamped end" run "$ex1" --out "$work/refused" --set bar.far_end=clamped

# barimpact exact: the same files for a case that admits an exact solution, exit 2 otherwise.
"$bin" exact "$examples/clamped-periodic.toml" --out "$work/exact" > /dev/null && ok || bad "exact clamped"
[ "$(head -1 "$work/exact/history.csv")" = "t,U,V,R,E_kin,E_strain,E_obstacle,W_ext,D_visc,D_contact,D_plastic,far_end.force,far_end.opening" ] && ok || bad "exact columns"
expect_refused "admits no exact solution" exact "$examples/paper-example2.toml" --out "$work/refused"

# barimpact converge: files, bad options refused, a failing run reported and not fatal.
"$bin" converge "$examples/paper-example1-rigid.toml" --out "$work/conv" --levels 2 \
  --schemes central-difference,characteristic > "$work/out" 2> "$work/err" && ok || bad "converge: $(cat "$work/err")"
for f in convergence.csv convergence.md; do [ -s "$work/conv/$f" ] && ok || bad "converge $f"; done
grep -q "Reference: exact solution" "$work/conv/convergence.md" && ok || bad "converge reference"
[ "$(grep -c '^central-difference,\|^characteristic,' "$work/conv/convergence.csv")" -eq 4 ] && ok || bad "converge rows"
"$bin" converge "$ex1" --out "$work/conv-fail" --set time.step=0.1 --set time.end=40 --set output.fields_at=[] \
  --vary time.alpha=0,0.25 > /dev/null 2> "$work/err" && ok || bad "converge with a failing run exit $?"
grep -q "did not complete" "$work/err" && ok || bad "failing run not reported: $(cat "$work/err")"
grep -q "non-finite" "$work/conv-fail/convergence.csv" && ok || bad "failing run row"
expect_refused "--levels" converge "$ex1" --out "$work/refused" --levels 1
expect_refused "--refine" converge "$ex1" --out "$work/refused" --refine sideways
expect_refused "--vary" converge "$ex1" --out "$work/refused" --vary stiffness=1,2
expect_refused "--schemes" converge "$ex1" --out "$work/refused" --schemes paper,euler
expect_refused "--refine none" converge "$ex1" --out "$work/refused" --refine none
expect_refused "--ratio: must be 2 .. 16" converge "$ex1" --out "$work/refused" --ratio 17
expect_refused "--levels: must be 2 .. 12" converge "$ex1" --out "$work/refused" --levels 13
expect_refused "--jobs: must be 1 .. 1024" converge "$ex1" --out "$work/refused" --jobs 1025
# --vary time.step varies the step on the case's mesh (the study's own step
# does not override it), and is refused where --refine refines the step too.
rigid="$examples/paper-example1-rigid.toml"
"$bin" converge "$rigid" --out "$work/conv-step" --vary time.step=0.01,0.005,0.0025 --set time.end=2.5 \
  --set output.fields_at=[] --schemes central-difference > /dev/null 2> "$work/err" && ok || bad "converge --vary time.step: $(cat "$work/err")"
[ "$(tail -n +2 "$work/conv-step/convergence.csv" | cut -d, -f4,6 | tr '\n' ' ')" = "100,0.01 100,0.005 100,0.0025 " ] && ok ||
  bad "--vary time.step rows: $(cut -d, -f1-8 "$work/conv-step/convergence.csv")"
expect_refused "--vary time.step: --refine both refines the step too" converge "$rigid" --out "$work/refused" \
  --vary time.step=0.01,0.005 --refine both --schemes central-difference
expect_refused "--vary bar.elements: --refine h refines the elements too" converge "$ex1" --out "$work/refused" \
  --vary bar.elements=100,200 --refine h
expect_refused "--vary time.step: the characteristic scheme sets dt = h/c" converge "$rigid" --out "$work/refused" \
  --vary time.step=0.01,0.005

# barimpact sweep: one row and one complete run directory per case; resume; failures recorded.
sweeps="$examples/sweeps"
expect_refused "--jobs: must be 1 .. 1024" sweep "$sweeps/penalty-to-rigid.toml" --out "$work/refused" --jobs 2000
"$bin" sweep "$sweeps/penalty-to-rigid.toml" --out "$work/sweep" --jobs 2 > "$work/out" && ok || bad "sweep"
[ "$(ls "$work/sweep/runs" | wc -l)" -eq 12 ] && ok || bad "sweep run directories"
[ "$(tail -n +2 "$work/sweep/sweep.csv" | wc -l)" -eq 12 ] && ok || bad "sweep rows"
[ "$(grep -c ',complete,' "$work/sweep/sweep.csv")" -eq 12 ] && ok || bad "sweep statuses"
for f in history.csv fields.csv case.toml summary.json; do [ -s "$work/sweep/runs/0005/$f" ] && ok || bad "run file $f"; done
# The run directory of a case equals barimpact run on that case's resolved file.
"$bin" run "$work/sweep/runs/0005/case.toml" --out "$work/single" > /dev/null
cmp -s "$work/single/history.csv" "$work/sweep/runs/0005/history.csv" && ok || bad "sweep case differs from run"
cut -d, -f1-14 "$work/sweep/sweep.csv" > "$work/first.csv"
# Resume: a removed case is redone, a half-written one (staging) ignored, the others skipped.
rm -rf "$work/sweep/runs/0007"
mkdir -p "$work/sweep/runs/.0008.partial-1" && rm -rf "$work/sweep/runs/0008" && touch "$work/sweep/runs/.0008.partial-1/history.csv" "$work/sweep/runs/.0008.partial-1/.barimpact-staging"
"$bin" sweep "$sweeps/penalty-to-rigid.toml" --out "$work/sweep" > "$work/out" && ok || bad "resume"
grep -q "12 cases: 2 run (.*), 10 resumed" "$work/out" && ok || bad "resume counts: $(cat "$work/out")"
cmp -s <(cut -d, -f1-14 "$work/sweep/sweep.csv") "$work/first.csv" && ok || bad "resumed sweep.csv differs"
# SIMD batches change nothing: the same bits with and without them.
"$bin" sweep "$sweeps/penalty-to-rigid.toml" --out "$work/sweep-nobatch" --no-batch > "$work/out" && ok || bad "no-batch"
grep -q "(0 in SIMD batches)" "$work/out" && ok || bad "no-batch still batched"
cmp -s <(cut -d, -f1-14 "$work/sweep-nobatch/sweep.csv") "$work/first.csv" && ok || bad "batched and unbatched rows differ"
cmp -s "$work/sweep-nobatch/runs/0009/history.csv" "$work/sweep/runs/0009/history.csv" && ok || bad "batched history differs"
# Every SIMD path this processor runs, forced by BARIMPACT_SIMD: the same bits.
for path in $("$bin" --version | sed -n 's/.*this processor runs: \([a-z0-9, ]*\);.*/\1/p' | tr -d ,); do
  BARIMPACT_SIMD=$path "$bin" sweep "$sweeps/penalty-to-rigid.toml" --out "$work/sweep-$path" > "$work/out" && ok || bad "sweep on $path"
  grep -q "in SIMD batches, $path)" "$work/out" && ok || bad "$path not taken: $(cat "$work/out")"
  cmp -s <(cut -d, -f1-14 "$work/sweep-$path/sweep.csv") "$work/first.csv" && ok || bad "$path rows differ"
  cmp -s "$work/sweep-$path/runs/0009/history.csv" "$work/sweep/runs/0009/history.csv" && ok || bad "$path history differs"
done
"$bin" --version | grep -q "this processor runs: scalar, sse2" && ok || bad "--version names the SIMD paths: $("$bin" --version)"
BARIMPACT_SIMD=avx9 "$bin" sweep "$sweeps/penalty-to-rigid.toml" --out "$work/refused" > /dev/null 2> "$work/err"
[ $? -eq 2 ] && [ ! -e "$work/refused" ] && [ "$(wc -l < "$work/err")" -eq 1 ] && grep -q "BARIMPACT_SIMD=avx9" "$work/err" && ok ||
  bad "bad BARIMPACT_SIMD: $(cat "$work/err")"
# A sweep writing results.h5 resumes from them.
printf 'case = "%s"\n[set]\noutput.format = "hdf5"\n[[axis]]\nkey = "obstacle.stiffness"\nvalues = [100.0, 200.0, 400.0]\n' \
  "$(cd "$examples" && pwd)/paper-example1.toml" > "$work/h5sweep.toml"
"$bin" sweep "$work/h5sweep.toml" --out "$work/sweep-h5" > /dev/null && ok || bad "hdf5 sweep"
[ -s "$work/sweep-h5/runs/0001/results.h5" ] && [ ! -e "$work/sweep-h5/runs/0001/history.csv" ] && ok || bad "hdf5 sweep run files"
cp "$work/sweep-h5/sweep.csv" "$work/h5sweep-first.csv"
rm -rf "$work/sweep-h5/runs/0001"
"$bin" sweep "$work/h5sweep.toml" --out "$work/sweep-h5" > "$work/out" && ok || bad "hdf5 sweep resume"
grep -q "3 cases: 1 run (.*), 2 resumed" "$work/out" && ok || bad "hdf5 resume counts: $(cat "$work/out")"
cmp -s <(cut -d, -f1-12 "$work/sweep-h5/sweep.csv") <(cut -d, -f1-12 "$work/h5sweep-first.csv") && ok || bad "hdf5 resumed sweep.csv differs"
# A mesh too large for a batch to pay is run case by case.
printf 'case = "%s"\n[set]\nbar.elements = 300000\ntime.step = 0.0001\ntime.end = 0.0002\noutput.fields_at = []\n[[axis]]\nkey = "obstacle.stiffness"\nvalues = [100.0, 200.0]\n' \
  "$(cd "$examples" && pwd)/paper-example1.toml" > "$work/bigsweep.toml"
"$bin" sweep "$work/bigsweep.toml" --out "$work/sweep-big" > "$work/out" && ok || bad "large-mesh sweep"
grep -q "2 run (0 in SIMD batches)" "$work/out" && ok || bad "large meshes batched: $(cat "$work/out")"
# Failures: recorded in their rows, the others run.
"$bin" sweep "$sweeps/with-failures.toml" --out "$work/sweep-fail" > "$work/out" && ok || bad "sweep with failures"
grep -q "^0000,.*,non-finite," "$work/sweep-fail/sweep.csv" && ok || bad "non-finite row"
grep -q "^0001,.*,refused,.*time.alpha" "$work/sweep-fail/sweep.csv" && ok || bad "refused row"
[ "$(grep -c ',complete,' "$work/sweep-fail/sweep.csv")" -eq 2 ] && ok || bad "complete rows"
printf 'case = "nope.toml"\n[[axis]]\nkey = "bar.length"\nvalues = [1]\n' > "$work/badsweep.toml"
expect_refused "no such case file" sweep "$work/badsweep.toml" --out "$work/refused"
printf 'case = "%s"\n[[axis]]\nkey = "bar.lenght"\nvalues = [1]\n' "$(cd "$examples" && pwd)/paper-example1.toml" > "$work/badsweep.toml"
expect_refused "unknown key bar.lenght" sweep "$work/badsweep.toml" --out "$work/refused"
# Under MPI (when built with it): two ranks give the same sweep.csv but for run times.
if [ -n "${BARIMPACT_MPIEXEC:-}" ]; then
  OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 timeout 300 "$BARIMPACT_MPIEXEC" -n 2 --oversubscribe \
    "$bin" sweep "$sweeps/penalty-to-rigid.toml" --out "$work/sweep-mpi" > "$work/out" 2> "$work/err" && ok || bad "mpi sweep: $(cat "$work/err")"
  grep -q "on 2 ranks" "$work/out" && ok || bad "mpi sweep did not run distributed: $(cat "$work/out")"
  cmp -s <(cut -d, -f1-14 "$work/sweep-mpi/sweep.csv") "$work/first.csv" && ok || bad "mpi sweep.csv differs"
  # --out refused on rank 0: every rank ends (exit 2), none waits, the user's file stays.
  mkdir -p "$work/mpi-theirs" && echo keep > "$work/mpi-theirs/notes.txt"
  OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 timeout 60 "$BARIMPACT_MPIEXEC" -n 2 --oversubscribe \
    "$bin" sweep "$sweeps/penalty-to-rigid.toml" --out "$work/mpi-theirs" > /dev/null 2> "$work/err"
  status=$?
  [ $status -ne 124 ] && [ $status -ne 0 ] && grep -q "holds files barimpact did not write" "$work/err" &&
    [ "$(ls "$work/mpi-theirs")" = "notes.txt" ] && ok || bad "mpi --out refusal (exit $status): $(cat "$work/err")"
fi

# Lines of bodies: the four examples run, their columns, the line's rules refused with the key.
lines="$examples/lines"
for ex in saint-venant drop-mass hopkinson pile-hammer; do
  "$bin" run "$lines/$ex.toml" --out "$work/line-$ex" > /dev/null 2> "$work/err" && ok || bad "line $ex: $(cat "$work/err")"
done
[ "$(head -1 "$work/line-saint-venant/history.csv")" = "t,U,V,R,E_kin,E_strain,E_obstacle,W_ext,D_visc,D_contact,D_plastic,joint.short-long.force,joint.short-long.opening,gauge.mid.strain,gauge.mid.velocity,gauge.mid.force" ] && ok || bad "saint-venant columns"
[ "$(head -1 "$work/line-pile-hammer/history.csv")" = "t,U,V,R,E_kin,E_strain,E_obstacle,W_ext,D_visc,D_contact,D_plastic,joint.capblock.force,joint.capblock.opening,body.ram.u,body.ram.v,gauge.head.strain,gauge.head.velocity,gauge.head.force" ] && ok || bad "pile-hammer columns"
[ "$(cut -d, -f7 "$work/line-saint-venant/fields.csv" | sort -u | tr '\n' ' ')" = "body long short " ] && ok || bad "fields body column"
"$bin" run "$work/line-saint-venant/case.toml" --out "$work/line-again" > /dev/null && ok || bad "resolved line case"
cmp -s "$work/line-saint-venant/history.csv" "$work/line-again/history.csv" && ok || bad "resolved line case differs"
"$bin" exact "$lines/saint-venant.toml" --out "$work/line-exact" > /dev/null && ok || bad "line exact"
# A line's figures (joint forces, gauges, masses) are barimpact's: the run can be replaced after plotting.
if "$bin" plot "$work/line-pile-hammer" > /dev/null 2>&1; then
  [ -f "$work/line-pile-hammer/figures/masses.png" ] && ok || bad "line figures"
  "$bin" run "$lines/pile-hammer.toml" --out "$work/line-pile-hammer" > /dev/null 2> "$work/err" && ok || bad "rerun after plot: $(cat "$work/err")"
fi
expect_refused "joint.short-long.gap must be >= 0" run "$lines/saint-venant.toml" --out "$work/refused" --set joint.short-long.gap=-1
expect_refused "no body named" run "$lines/saint-venant.toml" --out "$work/refused" --set body.nope.length=1
for scheme in paper newmark; do
  expect_refused "time.scheme = \"$scheme\" cannot run the rigid link \"joint.short-long\" (penalty laws only; schemes that can: central-difference, mass-redistribution, paoli-schatzman, moreau-jean, characteristic)" run "$lines/saint-venant.toml" --out "$work/refused" --set time.scheme=$scheme
done
# The implicit schemes run a cushion on a mass, gravity and an elastic near end.
for scheme in paper newmark; do
  "$bin" run "$lines/pile-hammer.toml" --out "$work/line-pile-$scheme" --set time.scheme=$scheme > /dev/null 2> "$work/err" && ok || bad "pile-hammer $scheme: $(cat "$work/err")"
done
expect_refused "joint.capblock.viscosity is not used by law" run "$lines/pile-hammer.toml" --out "$work/refused" --set joint.capblock.viscosity=1
expect_refused "restitution must be in (0, 1]" run "$lines/pile-hammer.toml" --out "$work/refused" --set joint.capblock.restitution=0
expect_refused "gauge.head.at must lie in the body" run "$lines/pile-hammer.toml" --out "$work/refused" --set gauge.head.at=11
expect_refused "body.ram.mass must be > 0" run "$lines/pile-hammer.toml" --out "$work/refused" --set body.ram.mass=0
printf '[[body]]\nname = "a"\n[[body]]\nname = "b"\n[[body]]\nname = "c"\n[[joint]]\nbetween = ["a", "c"]\nlaw = "rigid"\n' > "$work/badline.toml"
expect_refused "consecutive" run "$work/badline.toml" --out "$work/refused"
printf '[[body]]\nname = "a"\n[[body]]\nname = "a"\n' > "$work/badline.toml"
expect_refused "repeats the body name" run "$work/badline.toml" --out "$work/refused"
# Elastic-plastic bars: the three examples run and close their budgets; the columns; exact; the rules.
plastic="$examples/plastic"
for ex in taylor-bar paper-example1-yielding pipe-whip von-karman cyclic; do
  "$bin" run "$plastic/$ex.toml" --out "$work/plastic-$ex" > /dev/null 2> "$work/err" && ok || bad "plastic $ex: $(cat "$work/err")"
done
head -1 "$work/plastic-taylor-bar/history.csv" | grep -q "^t,U,V,R,E_kin,E_strain,E_obstacle,W_ext,D_visc,D_contact,D_plastic,gauge.mid" && ok || bad "plastic history columns"
[ "$(head -1 "$work/plastic-taylor-bar/fields.csv")" = "t,x,u,v,sigma,eps_p,body" ] && ok || bad "plastic fields columns"
/usr/bin/python3 - "$work/plastic-taylor-bar" <<'PY' && ok || bad "plastic summary"
import json, sys
s = json.load(open(sys.argv[1] + "/summary.json"))
p = s["plastic"]
assert p["largest_strain"] < 0 and p["body"] == "bar" and p["work"]["bar"] > 0, p
assert s["energy_error_relative"] < 1e-9, s["energy_error_relative"]
PY
"$bin" run "$work/plastic-paper-example1-yielding/case.toml" --out "$work/plastic-again" > /dev/null && ok || bad "resolved plastic case"
cmp -s "$work/plastic-paper-example1-yielding/history.csv" "$work/plastic-again/history.csv" && ok || bad "resolved plastic case differs"
printf '[[body]]\nname = "rod"\nelements = 100\nmaterial = "plastic"\nyield_stress = 0.1\nhardening_modulus = 0.25\n[near_end]\nlaw = "velocity"\nvalue = "0.3"\n[time]\nscheme = "central-difference"\nstep = 0.005\nend = 0.8\n' > "$work/von-karman.toml"
"$bin" exact "$work/von-karman.toml" --out "$work/von-karman-exact" > "$work/out" 2>&1 && grep -q "von Karman" "$work/out" && ok || bad "von karman exact: $(cat "$work/out")"
"$bin" exact "$work/von-karman.toml" --set time.end=1.5 --out "$work/von-karman-horizon" > "$work/out" 2>&1 && grep -q "exact-horizon: the exact solution is known up to t = 1 only" "$work/out" && ok || bad "von karman exact past its horizon: $(cat "$work/out")"
# The implicit schemes' Newton iteration from the command: the same plastic work as central differences' to 1%.
for scheme in moreau-jean mass-redistribution; do
  "$bin" run "$plastic/taylor-bar.toml" --set time.scheme=$scheme --out "$work/plastic-taylor-$scheme" > /dev/null && ok || bad "taylor bar under $scheme"
  /usr/bin/python3 - "$work/plastic-taylor-bar" "$work/plastic-taylor-$scheme" <<'PY' && ok || bad "taylor bar under $scheme: plastic work"
import json, sys
a, b = (json.load(open(d + "/summary.json"))["plastic"]["work"]["bar"] for d in sys.argv[1:])
assert abs(a - b) < 0.01 * a, (a, b)
PY
done
# paper's iteration from the command, on an elastic obstacle (it runs penalty links only): the plastic work of
# newmark's to 1% (measured 0.7%; both approach central differences' at first order in h with this obstacle).
"$bin" run "$plastic/paper-example1-yielding.toml" --set time.scheme=paper --out "$work/plastic-ex1-paper" > /dev/null && ok || bad "yielding example 1 under paper"
"$bin" run "$plastic/paper-example1-yielding.toml" --set time.scheme=newmark --out "$work/plastic-ex1-newmark" > /dev/null && ok || bad "yielding example 1 under newmark"
/usr/bin/python3 - "$work/plastic-ex1-newmark" "$work/plastic-ex1-paper" <<'PY' && ok || bad "yielding example 1 under paper: plastic work"
import json, sys
a, b = (json.load(open(d + "/summary.json"))["plastic"]["work"]["bar"] for d in sys.argv[1:])
assert abs(a - b) < 0.01 * a, (a, b)
PY
expect_refused "body.bar.yield_stress must be > 0" run "$plastic/taylor-bar.toml" --out "$work/refused" --set body.bar.yield_stress=0
expect_refused "body.bar.hardening_modulus must be below modulus" run "$plastic/taylor-bar.toml" --out "$work/refused" --set body.bar.hardening_modulus=3e11
expect_refused "time.scheme = \"characteristic\" cannot run the elastic-plastic body \"bar\"" run "$plastic/taylor-bar.toml" --out "$work/refused" --set time.scheme=characteristic
expect_refused "bar.yield_stress is used by material = \"plastic\" only" run "$ex1" --out "$work/refused" --set bar.yield_stress=1
printf '[bar]\n[[body]]\nname = "a"\n' > "$work/badline.toml"
expect_refused "cannot be combined with [[body]]" run "$work/badline.toml" --out "$work/refused"

# Pile driving: a blow's results, the bearing graph (columns, inf for a
# refusal, resumable), and Smith's soil's bad input.
pipe="$examples/pile/steel-pipe-sand.toml"
"$bin" run "$pipe" --out "$work/pipe" > /dev/null && ok || bad "pile example"  # at rest from 0.39 s, the ram back at 0.394 s
/usr/bin/python3 - "$work/pipe/summary.json" <<'PY' && ok || bad "summary.json blow"
import json, sys
b = json.load(open(sys.argv[1]))["blow"]
for key in ("set", "blows_per_m", "blows_per_250mm", "enthru", "hammer_energy", "transfer_ratio", "finished"):
    assert key in b, key
for key in ("max_compression", "max_tension"):
    assert set(b[key]) >= {"value", "body", "x", "t"} and b[key]["value"] >= 0 and b[key]["body"] == "pile", b[key]
assert b["set"] > 0 and abs(b["blows_per_250mm"] - 0.25 / b["set"]) < 1e-9 * b["blows_per_250mm"], b
assert 0 < b["transfer_ratio"] < 1 and b["finished"] is True, b
assert 0.3 < b["restrike_time"] < 0.45 and b["strikes"] == 1 and b["last_slip_time"] < b["rest_time"], b
PY
# Under gravity a soil that cannot carry the pile's weight has no static rest: refused, naming the key.
expect_refused "near_end.ultimate = 900: the soil's static capacity" run "$pipe" --out "$work/refused" \
  --set near_end.ultimate=900 --set body.pile.shaft.ultimate=600
"$bin" bearing "$pipe" --out "$work/bearing" --capacity 1e6:5e7:3 --no-plot > /dev/null && ok || bad "bearing exit"
[ "$(head -1 "$work/bearing/bearing.csv" | cut -d, -f1-8)" = "capacity,set,blows_per_250mm,blows_per_m,max_compression,max_tension,enthru,finished" ] && ok || bad "bearing columns"
[ "$(wc -l < "$work/bearing/bearing.csv")" -eq 4 ] && ok || bad "bearing rows"
[ "$(tail -1 "$work/bearing/bearing.csv" | cut -d, -f2-4)" = "0,inf,inf" ] && ok || bad "refusal row: $(tail -1 "$work/bearing/bearing.csv")"
cp "$work/bearing/bearing.csv" "$work/bearing-first.csv"
"$bin" bearing "$pipe" --out "$work/bearing" --capacity 1e6:5e7:3 --no-plot > /dev/null && ok || bad "bearing rerun"
cut -d, -f1-11 "$work/bearing/bearing.csv" | cmp -s - <(cut -d, -f1-11 "$work/bearing-first.csv") && ok || bad "bearing resumed differs"
expect_refused "--capacity" bearing "$pipe" --out "$work/refused" --capacity 1e6:2e6
expect_refused "--toe-share" bearing "$pipe" --out "$work/refused" --capacity 1e6:2e6:3 --toe-share 2
# bearing --set reaches every capacity's case (the blow-unfinished advice: raise time.end).
"$bin" bearing "$pipe" --out "$work/bearing-set" --capacity 1e6:2e6:2 --set time.end=0.05 --no-plot > /dev/null && ok || bad "bearing --set exit"
grep -q '^end = 0.05$' "$work/bearing-set/runs/0001/case.toml" && ok || bad "bearing --set not in the runs' cases"
expect_refused "--set time.nope=1" bearing "$pipe" --out "$work/refused" --capacity 1e6:2e6:2 --set time.nope=1
expect_refused "--toe-share must be in [0, 1]" bearing "$pipe" --out "$work/refused" --capacity 1e6:2e6:3 --toe-share -0.5
expect_refused "--jobs: must be 1 .. 1024" bearing "$pipe" --out "$work/refused" --capacity 1e6:2e6:3 --jobs -1
# A diesel hammer's blow on a rigid stop: the gas's pressure in the
# history, the rebound in the blow; refused by a scheme that cannot run it.
diesel="$examples/pile/diesel-rigid-stop.toml"
"$bin" run "$diesel" --out "$work/diesel" > /dev/null 2>&1 && ok || bad "diesel example"
head -1 "$work/diesel/history.csv" | grep -q 'joint.gas.force,joint.gas.opening,joint.gas.pressure' && ok || bad "diesel columns"
/usr/bin/python3 - "$work/diesel/summary.json" <<'PY' && ok || bad "summary.json diesel blow"
import json, sys
b = json.load(open(sys.argv[1]))["blow"]
w = 1000 * 9.81
assert abs(b["next_stroke"] - (0.64 * (2 - b["compression_work"] / w) + b["expansion_work"] / w)) < 0.01, b
PY
expect_refused 'joint.gas.law = "diesel" runs on the schemes central-difference, paoli-schatzman only' run "$diesel" --out "$work/refused" --set 'time.scheme="newmark"'
# A pile's numbers in another unit: a modulus in MPa refused, a capacity in kN warned (exit 4 under --strict).
expect_refused "body.pile.modulus = 210000: MPa?" run "$pipe" --out "$work/refused" --set body.pile.modulus=210000
"$bin" run "$pipe" --out "$work/pipe-kn" --strict --set near_end.ultimate=900 --set time.end=0.002 --set "output.fields_at=[]" > /dev/null 2> "$work/err"
[ $? -eq 4 ] && grep -qF "pile-capacity: near_end.ultimate = 900: kN?" "$work/err" && ok || bad "capacity in kN: $(cat "$work/err")"
grep -qF "pile-capacity: near_end.ultimate = 900: kN?" "$work/pipe-kn/summary.json" && ok || bad "capacity warning not in summary.json"
expect_refused "no Smith soil" bearing "$ex1" --out "$work/refused" --capacity 1e6:2e6:3
expect_refused "far_end.law = \"smith\" is a near-end law only" run "$pipe" --out "$work/refused" --set far_end.law=smith
expect_refused "time.scheme = \"moreau-jean\" cannot run Smith's soil" run "$pipe" --out "$work/refused" --set time.scheme=moreau-jean --set time.step=1e-5

# Drivability: drive.csv's contract columns, summary.json's totals, a rerun
# resumes; `run` of a [drive] case analyses its deepest depth; the hammers.
drv="$examples/pile/drive-pipe-drop.toml"
"$bin" drive "$drv" --out "$work/drive" --no-plot --set drive.depths=[3.0,8.0] > /dev/null 2>&1 && ok || bad "drive exit"
[ "$(head -1 "$work/drive/drive.csv" | cut -d, -f1-14)" = "depth,shaft,toe,capacity,long_term_capacity,set,blows_per_250mm,blows_per_m,max_compression,max_tension,enthru,stroke,cumulative_blows,finished" ] && ok || bad "drive columns"
[ "$(wc -l < "$work/drive/drive.csv")" -eq 3 ] && ok || bad "drive rows"
grep -q '"total_blows"' "$work/drive/summary.json" && grep -q '"refusal_depth"' "$work/drive/summary.json" && ok || bad "drive summary"
"$bin" drive "$drv" --out "$work/drive" --no-plot --set drive.depths=[3.0,8.0] > /dev/null 2>&1 && ok || bad "drive rerun"
"$bin" run "$drv" --out "$work/drive-run" --set drive.depths=[3.0,8.0] --set time.end=0.02 > /dev/null 2>&1 && ok || bad "run of a drive case"
grep -q '^\[\[body.shaft.profile\]\]$' "$work/drive-run/case.toml" && ok || bad "the run's case.toml spells the profile"
"$bin" hammers | grep -q "Vulcan 010" && ok || bad "hammers lists the table"
# Residual stresses: blows follow one another from the last one's rest.
"$bin" run "$drv" --out "$work/residual" --set drive.blows=4 --set drive.depth=8 --set time.end=0.3 > /dev/null 2>&1 && ok || bad "residual run"
grep -q '"residual_toe_force"' "$work/residual/summary.json" && grep -q '"blows_run"' "$work/residual/summary.json" && ok || bad "residual summary"
expect_refused "runs on central-difference only" run "$drv" --out "$work/refused" --set drive.blows=3 --set time.scheme=newmark --set time.step=1e-5
# A diesel hammer from the table: the stroke found at each depth, the gas's columns.
"$bin" drive "$examples/pile/drive-concrete-diesel.toml" --out "$work/drive-diesel" --no-plot --set "drive.depths=[6.0,12.0]" > /dev/null 2>&1 && ok || bad "diesel drive exit"
awk -F, 'NR > 1 && !($12 > 0.5) { bad = 1 } END { exit bad }' "$work/drive-diesel/drive.csv" && ok || bad "diesel strokes: $(cut -d, -f1,12 "$work/drive-diesel/drive.csv")"
head -1 "$work/drive-diesel/runs/0000/history.csv" | grep -q "hammer.gas.pressure" && ok || bad "the gas's columns"
"$bin" inspector "$drv" --out "$work/inspector" --stroke 0.5:1.0:2 --depth 6 --no-plot --set time.end=0.02 > /dev/null 2>&1 && ok || bad "inspector exit"
[ "$(head -1 "$work/inspector/inspector.csv" | cut -d, -f1-8)" = "stroke,energy,set,blows_per_250mm,blows_per_m,max_compression,max_tension,enthru" ] && ok || bad "inspector columns"
# --no-plot, then plot DIR: each study's figures drawn where the command draws them.
if [ -f "$(dirname "$bin")/python/barimpact/__init__.py" ]; then
  for study in bearing:bearing drive:drive inspector:inspector; do
    dir=${study%%:*} figure=${study##*:}
    [ ! -e "$work/$dir/$figure.png" ] && "$bin" plot "$work/$dir" > /dev/null 2>&1 && [ -s "$work/$dir/$figure.png" ] &&
      ok || bad "plot $dir after --no-plot"
  done
  rm "$work/conv/convergence.png" && "$bin" plot "$work/conv" > /dev/null 2>&1 && [ -s "$work/conv/convergence.png" ] &&
    ok || bad "plot of a converge directory"
  "$bin" plot "$work/bearing" --out "$work/elsewhere" > /dev/null 2>&1; [ $? -eq 2 ] && [ ! -e "$work/elsewhere" ] &&
    ok || bad "plot of a bearing directory with --out"
fi
expect_refused "--depth is required" inspector "$drv" --out "$work/refused" --stroke 0.5:1.0:2
expect_refused "diesel hammer, whose stroke follows the soil" inspector "$examples/pile/drive-concrete-diesel.toml" --out "$work/refused" --stroke 1.5:3.0:2 --depth 8
expect_refused "no [hammer]" inspector "$pipe" --out "$work/refused" --stroke 0.5:1.0:2
expect_refused "no [drive] section" drive "$pipe" --out "$work/refused"
expect_refused "layer[1].top" drive "$drv" --out "$work/refused" --set layer.layer1.top=1.0
expect_refused "nearest: \"Vulcan 010\"" run "$drv" --out "$work/refused" --set "hammer.model=Vulkan 010"

# The Hopkinson bar: simulate, analyse the run's gauges (the contract's
# columns first), analyse measured files; a signal that cannot be analysed
# writes nothing.
"$bin" run "$examples/hopkinson/shpb.toml" --out "$work/shpb" > /dev/null 2>&1 && ok || bad "shpb run"
cat > "$work/analyse.toml" <<'TOML'
[specimen]
body = "specimen"
[incident]
run = "shpb"
gauge = "incident"
[transmitted]
run = "shpb"
gauge = "transmitted"
[fit]
elastic = [50e6, 200e6]
TOML
"$bin" hopkinson "$work/analyse.toml" --out "$work/hk" --no-plot > "$work/stdout" 2> /dev/null && ok || bad "hopkinson exit"
[ "$(head -1 "$work/hk/hopkinson.csv" | cut -d, -f1-11)" = "t,strain_1w,strain_rate_1w,stress_1w,strain_3w,strain_rate_3w,stress_2w,stress_3w,force_front,force_back,equilibrium" ] && ok || bad "hopkinson columns"
[ "$(sed -n 2p "$work/hk/hopkinson.csv" | cut -d, -f1-2)" = "0,0" ] && ok || bad "first row at t = 0, strain 0"
for key in '"alignment"' '"baseline"' '"peak_stress"' '"peak_strain_rate"' '"equilibrium_from"' '"modulus"' '"yield_stress"' '"hardening_modulus"'; do
  grep -q "$key" "$work/hk/summary.json" && ok || bad "summary.json has no $key"
done
grep -q "yield stress (0.2% offset)" "$work/stdout" && ok || bad "hopkinson stdout"
# A run named from the working directory when nothing of that name is beside the setup.
mkdir -p "$work/setups" && cp "$work/analyse.toml" "$work/setups/"
abs_bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")
(cd "$work" && "$abs_bin" hopkinson setups/analyse.toml --out hk-cwd --no-plot > /dev/null 2>&1) && ok || bad "run relative to the working directory"
cmp -s "$work/hk/hopkinson.csv" "$work/hk-cwd/hopkinson.csv" && ok || bad "the same analysis from the working directory"
# A run that wrote results.h5 gives the same analysis.
"$bin" run "$examples/hopkinson/shpb.toml" --out "$work/shpb-h5" --set output.format=hdf5 > /dev/null 2>&1 && ok || bad "shpb hdf5 run"
sed 's/"shpb"/"shpb-h5"/' "$work/analyse.toml" > "$work/analyse-h5.toml"
"$bin" hopkinson "$work/analyse-h5.toml" --out "$work/hk-h5" --no-plot > /dev/null 2>&1 && ok || bad "hopkinson of an hdf5 run"
cmp -s "$work/hk/hopkinson.csv" "$work/hk-h5/hopkinson.csv" && ok || bad "the hdf5 run's analysis differs"
# The same gauges as measured files: a file without a header, volts.
awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "gauge.incident.strain") c = i; next } { print $1 "," $c }' "$work/shpb/history.csv" > "$work/inc.csv"
awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "gauge.transmitted.strain") c = i; next } { print $1 "," $c * 1000 }' "$work/shpb/history.csv" > "$work/tr.csv"
cat > "$work/measured.toml" <<'TOML'
[bar]
modulus = 200e9
density = 7850.0
diameter = 0.020
[specimen]
length = 0.006
diameter = 0.010
[incident]
signal = "inc.csv"
header = false
time = "1"
strain = "2"
gauge_to_specimen = 0.75
[transmitted]
signal = "tr.csv"
header = false
time = "1"
volts = "2"
bridge = "full"
gauge_factor = 2.0
excitation = 5.0
gain = 100
gauge_to_specimen = 0.75
TOML
"$bin" hopkinson "$work/measured.toml" --out "$work/hk-measured" --no-plot > /dev/null 2>&1 && ok || bad "measured exit"
# volts x 1000 through a full bridge: eps = V / (100 x 5 x 2) = the strain x 1000 / 1000.
cmp -s <(cut -d, -f1-11 "$work/hk/hopkinson.csv" | sed -n 2,50p | cut -c1-12) <(cut -d, -f1-11 "$work/hk-measured/hopkinson.csv" | sed -n 2,50p | cut -c1-12) && ok || bad "measured files differ from the run's gauges"
sed 's/strain = "2"/strain = "3"/' "$work/measured.toml" > "$work/m1.toml"
expect_refused "no column \"3\"" hopkinson "$work/m1.toml" --out "$work/refused"
cp "$work/measured.toml" "$work/m2.toml" && sed -i 's/inc.csv/nothing.csv/' "$work/m2.toml"
expect_refused "nothing.csv" hopkinson "$work/m2.toml" --out "$work/refused"
cp "$work/measured.toml" "$work/m3.toml" && sed -i 's/gauge_to_specimen = 0.75/gauge_to_specimen = 0.3/' "$work/m3.toml"
expect_refused "pulses too close" hopkinson "$work/m3.toml" --out "$work/refused"
cp "$work/measured.toml" "$work/m4.toml" && sed -i 's/^gain = 100/gain = 100\nfull_scale = 0.5/' "$work/m4.toml"
expect_refused "clips" hopkinson "$work/m4.toml" --out "$work/refused"
# A result that is not finite is refused: a gauge distance in mm, a transmitted window outside the record.
sed '0,/gauge_to_specimen = 0.75/s//gauge_to_specimen = 750/' "$work/measured.toml" > "$work/m5.toml"
expect_refused "incident.gauge_to_specimen = 750" hopkinson "$work/m5.toml" --out "$work/refused"
{ cat "$work/measured.toml"; printf 'start = 1.0\nend = 2.0\n'; } > "$work/m6.toml"  # in [transmitted], the last section
expect_refused "transmitted.start = 1, transmitted.end = 2" hopkinson "$work/m6.toml" --out "$work/refused"
# A unit slip names the key and the unit it was probably meant in: GPa, mm, a time column in us.
sed 's/modulus = 200e9/modulus = 200/' "$work/measured.toml" > "$work/m7.toml"
expect_refused "bar.modulus = 200: GPa?" hopkinson "$work/m7.toml" --out "$work/refused"
sed 's/length = 0.006/length = 6/' "$work/measured.toml" > "$work/m8.toml"
expect_refused "specimen.length = 6: mm?" hopkinson "$work/m8.toml" --out "$work/refused"
awk -F, '{ print $1 * 1e6 "," $2 }' "$work/inc.csv" > "$work/inc-us.csv"
sed 's/"inc.csv"/"inc-us.csv"/' "$work/measured.toml" > "$work/m9.toml"
expect_refused "incident.time: the samples are" hopkinson "$work/m9.toml" --out "$work/refused"
grep -q "us?" "$work/err" && ok || bad "no us? in: $(cat "$work/err")"
expect_refused "unknown key window.trigge" hopkinson <(printf '[window]\ntrigge = 0.1\n') --out "$work/refused"

# barimpact check: validates without running or writing, prints what to know first.
mkdir -p "$work/check-cwd"
absolute() { echo "$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"; }
abs_bin=$(absolute "$bin") abs_ex1=$(absolute "$ex1")
(cd "$work/check-cwd" && "$abs_bin" check "$abs_ex1" > "$work/check.out" 2> "$work/check.err") && ok || bad "check exit $?"
[ -z "$(ls -A "$work/check-cwd")" ] && ok || bad "check wrote files"
grep -qx "steps: 400 (dt = 0.01 to t = 4, 101 nodes)" "$work/check.out" && ok || bad "check steps: $(cat "$work/check.out")"
grep -qx "penalty: tau = 0.01, dt/tau = 1 (obstacle, Z/k)" "$work/check.out" && ok || bad "check penalty: $(cat "$work/check.out")"
grep -q "^time estimate: " "$work/check.out" && ok || bad "check time estimate"
"$bin" check "$ex1" --set obstacle.stiffness=1e4 --set time.step=0.001 | grep -qx "penalty: tau = 0.0001, dt/tau = 10 not resolved (obstacle, Z/k)" && ok || bad "check: not resolved"
"$bin" check "$examples/paper-example1-rigid.toml" --set time.scheme=central-difference --set time.step=0.005 | grep -qx "stable step: 0.01 (lumped mass); dt is 0.5 of it" && ok || bad "check: stable step"
"$bin" check "$examples/paper-example1-rigid.toml" --set time.scheme=paoli-schatzman --set time.step=0.005 | grep -q "^stable step: 0.005774 (consistent mass)" && ok || bad "check: consistent mass"
"$bin" check "$examples/lines/hopkinson.toml" | grep -q "^penalty: tau = 9.936e-08, dt/tau = 0.503 (joint.transmitter-specimen, Z1 Z2/((Z1 + Z2) k))" && ok || bad "check: two bars"
"$bin" check "$ex1" --set time.alpha=0.1 > /dev/null 2>&1; [ $? -eq 3 ] && ok || bad "check of a run that blows up: not exit 3"
expect_refused "time.step" check "$ex1" --set time.step=0
expect_refused "no such case file" check "$work/nope.toml"
expect_refused "unknown section [extra]" check "$work/section.toml"
# A rebound velocity the exact solution does not give reads "not measured", never "+nan".
"$bin" exact "$ex1" --out "$work/console-numbers" > "$work/out" 2>&1
! grep -q "nan" "$work/out" && grep -q "leaves with mean velocity not measured" "$work/out" && ok || bad "nan on the console: $(cat "$work/out")"

echo "$passed passed, $failed failed"
[ $failed -eq 0 ]
