#!/usr/bin/env bash
# Installs a build to a fresh prefix, builds tests/consumer against it, then
# moves the build tree away and runs the installed command (every
# subcommand, plot included) and the installed Python package from
# elsewhere: nothing may reach back into the build or source tree.
#   bash tests/install/install_test.sh BUILD_DIR
set -u
build=$(cd "$1" && pwd)
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
python=${BARIMPACT_PYTHON:-/usr/bin/python3}
work=$(mktemp -d)
prefix="$work/prefix"
moved="$build.moved-$$"
passed=0 failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*"; }
restore() { [ -d "$moved" ] && mv "$moved" "$build"; rm -rf "$work"; }
trap restore EXIT

cmake --install "$build" --prefix "$prefix" > "$work/install.log" 2>&1 && ok || bad "cmake --install: $(tail -3 "$work/install.log")"
for f in bin/barimpact lib/libbarimpact.a include/barimpact/case/case.hpp lib/cmake/barimpact/barimpactConfig.cmake \
  lib/cmake/barimpact/barimpactConfigVersion.cmake share/barimpact/examples/paper-example1.toml; do
  [ -e "$prefix/$f" ] && ok || bad "not installed: $f"
done
site=$(ls -d "$prefix"/lib/python3*/site-packages)
[ -f "$site/barimpact/__init__.py" ] && ls "$site"/barimpact/_core*.so > /dev/null 2>&1 && ok || bad "Python package not installed"
# The modules the library loads when a process needs them: results.h5's (HDF5) and signal matching's (Ceres).
for module in hdf5 fit; do
  ls "$site"/barimpact/libbarimpact_$module.so.* > /dev/null 2>&1 && ok || bad "the $module module not installed"
done

# A consumer project: find_package(barimpact), the paper's Example 1.
cmake -S "$source_dir/tests/consumer" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$prefix" > "$work/consumer.log" 2>&1 &&
  cmake --build "$work/consumer" >> "$work/consumer.log" 2>&1 && ok || bad "consumer build: $(tail -5 "$work/consumer.log")"

# The build tree gone: the installed command and package on their own.
mv "$build" "$moved"
examples="$prefix/share/barimpact/examples"
bin="$prefix/bin/barimpact"
mkdir -p "$work/user" && cd "$work/user"
"$work/consumer/example1" && ok || bad "consumer example 1"
# Installed away from its configured prefix: the program names the package's directory for the fitting module.
BARIMPACT_MODULE_DIR="$site/barimpact" "$work/consumer/match" "$examples/pda/steel-pipe.toml" > /dev/null &&
  ok || bad "consumer match (the fitting module from BARIMPACT_MODULE_DIR)"
"$bin" check "$examples/paper-example1.toml" > /dev/null && ok || bad "installed check"
"$bin" run "$examples/paper-example1.toml" --out runs/ex1 > /dev/null && ok || bad "installed run"
"$bin" plot runs/ex1 > /dev/null && [ -s runs/ex1/figures/displacement.png ] && ok || bad "installed plot"
"$bin" run "$examples/paper-example1.toml" --out runs/ex1-h5 --set output.format=hdf5 > /dev/null &&
  "$bin" plot runs/ex1-h5 > /dev/null && [ -s runs/ex1-h5/figures/displacement.png ] && ok || bad "installed run and plot of results.h5"
"$bin" exact "$examples/clamped-periodic.toml" --out runs/exact > /dev/null && ok || bad "installed exact"
"$bin" converge "$examples/paper-example1-rigid.toml" --out runs/study --levels 2 --schemes central-difference,moreau-jean \
  > /dev/null && [ -s runs/study/convergence.png ] && ok || bad "installed converge (with its plots)"
"$bin" sweep "$examples/sweeps/penalty-to-rigid.toml" --out runs/sweep > /dev/null 2>&1 && ok || bad "installed sweep"
"$bin" bearing "$examples/pile/steel-pipe-sand.toml" --out runs/bearing --capacity 1e6:2e6:2 > /dev/null &&
  [ -s runs/bearing/bearing.png ] && ok || bad "installed bearing"
"$bin" run "$examples/lines/hopkinson.toml" --out out/hopkinson > /dev/null && ok || bad "installed run of a line"
printf '[bar]\nmodulus = 200e9\ndensity = 7850\ndiameter = 0.02\n[specimen]\nbody = "specimen"\n[incident]\nrun = "out/hopkinson"\ngauge = "incident"\n[transmitted]\nrun = "out/hopkinson"\ngauge = "transmitted"\n' > setup.toml
"$bin" hopkinson setup.toml --out runs/analysis > /dev/null 2>&1 && [ -s runs/analysis/hopkinson.csv ] && ok ||
  bad "installed hopkinson: $("$bin" hopkinson setup.toml --out runs/analysis2 2>&1 | tail -1)"
"$bin" pda "$examples/pda/steel-pipe.toml" --out runs/pda > /dev/null 2>&1 && [ -s runs/pda/pda.csv ] &&
  [ -s runs/pda/waves.png ] && ok || bad "installed pda (with its figures)"
"$bin" match "$examples/pda/steel-pipe.toml" --out runs/match > /dev/null 2>&1 && [ -s runs/match/soil.csv ] &&
  [ -s runs/match/resistance.png ] && ok || bad "installed match (with its figures)"
PYTHONPATH="$site" MPLBACKEND=Agg "$python" -c "
import barimpact
r = barimpact.run('$examples/paper-example1.toml')
assert abs(r.summary['contacts'][0]['rebound_velocity'] - 0.9949) < 1e-3, r.summary['contacts']
barimpact.plot(r, 'py-figures')
m = barimpact.match('$examples/pda/steel-pipe.toml', out='py-match')
assert abs(m.summary['capacity'] - 1.5e6) < 3e4 and m.soil.segment[-1] == 'toe', m.summary['capacity']
" && [ -s py-figures/displacement.png ] && [ -s py-match/static_test.png ] && ok || bad "installed Python package"
grep -rl "$build" "$prefix" > "$work/refs" 2>/dev/null
[ ! -s "$work/refs" ] && ok || bad "installed files name the build tree: $(head -3 "$work/refs")"

echo "install: $passed passed, $failed failed"
[ $failed -eq 0 ]
