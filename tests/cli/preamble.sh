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
# The command refuses: exit 2, one line on stderr holding the expected
# substring, nothing written to $work/refused, no staging left.
expect_refused() {  # expected-substring, then the arguments
  local want=$1
  shift
  "$bin" "$@" > "$work/out" 2> "$work/err"
  local code=$?
  if [ $code -ne 2 ]; then bad "exit $code, not 2, for: $*"; return; fi
  if [ "$(wc -l < "$work/err")" -ne 1 ]; then bad "not one line for: $*: $(cat "$work/err")"; return; fi
  grep -qF -- "$want" "$work/err" || { bad "'$want' not in: $(cat "$work/err")"; return; }
  [ -e "$work/refused" ] && { bad "output written for: $*"; return; }
  ls -a "$work" | grep -q partial && { bad "staging left for: $*"; return; }
  ok
}
