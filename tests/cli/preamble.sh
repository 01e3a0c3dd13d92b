# What every CLI test script starts with, sourced with its two arguments
# (BARIMPACT EXAMPLES_DIR): both as absolute paths, a scratch directory
# $work removed on exit, and the tally that ok and bad keep.
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
examples=$(cd "$2" && pwd)
work=$(mktemp -d)
trap 'chmod -R u+w "$work"; rm -rf "$work"' EXIT
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*"; }
