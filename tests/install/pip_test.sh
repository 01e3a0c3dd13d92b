#!/usr/bin/env bash
# The Python package as a Python user installs it, offline, from Debian's
# packages: a virtual environment that sees the system's numpy and
# matplotlib, `pip install --no-build-isolation --no-index .` (setup.py
# drives CMake), a wheel from `python3 -m build --no-isolation`, and then
# the Python tests and the tutorial's first lines against the installed
# package, from a directory outside the source tree.
#   bash tests/install/pip_test.sh [BUILD_DIR]
# With BUILD_DIR (a Release build tree of this source, e.g. build/ci), the
# `pip install .` packages that tree's module and command
# (BARIMPACT_CMAKE_BUILD_DIR, setup.py) instead of compiling them again.
# The wheel is always built from the sdist as a user's would be: the one
# full compile, which also proves the sdist holds all a build needs.
set -u
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:+$(cd "$1" && pwd)}
python=${BARIMPACT_PYTHON:-/usr/bin/python3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
passed=0 failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*"; }

cd "$source_dir"
"$python" -m venv --system-site-packages "$work/venv" && ok || bad "python3 -m venv"
BARIMPACT_CMAKE_BUILD_DIR=$build "$work/venv/bin/pip" install --no-build-isolation --no-index . > "$work/pip.log" 2>&1 && ok ||
  bad "pip install: $(grep -i error "$work/pip.log" | head -5)"
# As the README gives it: an sdist, then a wheel built from that sdist.
env -u BARIMPACT_CMAKE_BUILD_DIR "$python" -m build --no-isolation --outdir "$work/dist" . > "$work/build.log" 2>&1 && ok ||
  bad "python3 -m build: $(grep -i error "$work/build.log" | head -5)"
ls "$work"/dist/barimpact-*.tar.gz > /dev/null 2>&1 && ok || bad "python3 -m build made no sdist"
"$python" -m venv --system-site-packages "$work/wheel-venv" &&
  "$work/wheel-venv/bin/pip" install --no-index "$work"/dist/barimpact-*.whl > "$work/wheel.log" 2>&1 && ok ||
  bad "pip install of the wheel: $(tail -3 "$work/wheel.log")"

if [ -n "$build" ]; then
  # The README's command, nothing set: the source tree's Release build (build/release or build/ci)
  # is packaged, not compiled again (a build of its own took 12.5 minutes).
  "$python" -m venv --system-site-packages "$work/auto-venv" &&
    env -u BARIMPACT_CMAKE_BUILD_DIR "$work/auto-venv/bin/pip" install -v --no-build-isolation --no-index . \
      > "$work/auto.log" 2>&1 && grep -q "barimpact: packaging the existing build $source_dir/build/" "$work/auto.log" &&
    ok || bad "pip install . did not package the existing build: $(grep -i "error\|packaging" "$work/auto.log" | head -3)"
  # Packaged from the build tree, the installed files must not lead back into it.
  grep -rlF "$build" "$work/venv/bin/barimpact" "$work"/venv/lib/python3*/site-packages/barimpact > "$work/refs"
  [ ! -s "$work/refs" ] && ok || bad "installed files name the build tree: $(head -3 "$work/refs")"
fi

mkdir -p "$work/user" && cd "$work/user"
for venv in venv wheel-venv; do
  v="$work/$venv"
  [ -x "$v/bin/barimpact" ] && ok || bad "$venv: no barimpact command in bin/"
  for module in hdf5 fit; do
    ls "$v"/lib/python3*/site-packages/barimpact/libbarimpact_$module.so.* > /dev/null 2>&1 && ok ||
      bad "$venv: the $module module not installed"
  done
  "$v/bin/python" -c "import barimpact, os; assert barimpact.__file__.startswith('$v'), barimpact.__file__" && ok ||
    bad "$venv: import barimpact does not find the installed package"
  "$v/bin/barimpact" run "$source_dir/examples/paper-example1.toml" --out "$venv-run" > /dev/null &&
    "$v/bin/barimpact" plot "$venv-run" > /dev/null && [ -s "$venv-run/figures/displacement.png" ] && ok ||
    bad "$venv: the installed command's run and plot"
done
# The Python tests against the installed package (the wheel's), outside the source tree.
BARIMPACT_CLI="$work/wheel-venv/bin/barimpact" BARIMPACT_ROOT="$source_dir" MPLBACKEND=Agg \
  "$work/wheel-venv/bin/python" -m pytest -q -p no:cacheprovider "$source_dir/python/tests" > "$work/pytest.log" 2>&1 && ok ||
  bad "Python tests against the installed package: $(tail -15 "$work/pytest.log")"
tail -1 "$work/pytest.log"

echo "pip: $passed passed, $failed failed"
[ $failed -eq 0 ]
