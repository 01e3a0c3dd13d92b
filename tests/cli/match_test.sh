#!/usr/bin/env bash
# barimpact match: its files, columns and keys on the examples' generated
# records, and every refusal of bad [match] settings (exit 2, one line,
# nothing written).
# Usage: match_test.sh BARIMPACT EXAMPLES_DIR
set -u
. "$(dirname "${BASH_SOURCE[0]}")/preamble.sh"

# The steel pipe: the contract's files and columns, one match.csv row a
# sample of the window, soil.csv's segments and toe, the static test.
"$bin" match "$examples/pda/steel-pipe.toml" --out "$work/pipe" --no-plot > "$work/stdout" 2> "$work/stderr" && ok || bad "pipe exit: $(cat "$work/stderr")"
[ "$(head -1 "$work/pipe/match.csv")" = "t,force_measured,force_computed,velocity_z,wave_up_measured,wave_up_computed" ] && ok || bad "match.csv columns"
[ "$(head -1 "$work/pipe/soil.csv")" = "segment,top,bottom,resistance,quake,damping" ] && ok || bad "soil.csv columns"
[ "$(head -1 "$work/pipe/static.csv")" = "settlement,load" ] && ok || bad "static.csv columns"
[ "$(($(wc -l < "$work/pipe/soil.csv") - 1))" -eq 11 ] && ok || bad "10 segments and the toe"
tail -1 "$work/pipe/soil.csv" | grep -q '^toe,19.2,19.2,' && ok || bad "the toe's row: $(tail -1 "$work/pipe/soil.csv")"
sed -n 2p "$work/pipe/soil.csv" | grep -q '^1,1.2,' && ok || bad "segment 1 starts at 19.2 - 18 m: $(sed -n 2p "$work/pipe/soil.csv")"
samples=$(grep -o '"samples_matched": [0-9]*' "$work/pipe/summary.json" | grep -o '[0-9]*$')
[ "$(($(wc -l < "$work/pipe/match.csv") - 1))" -eq "$samples" ] && ok || bad "one match.csv row a matched sample ($samples)"
for key in capacity shaft toe match_quality evaluations iterations starts spread s_c; do
  grep -q "^  \"$key\": " "$work/pipe/summary.json" && ok || bad "summary.json has no $key"
done
# The capacity the record was made with: 600 kN on the shaft, 900 kN at the toe.
awk -F': ' '/^  "capacity"/ { c = $2 + 0; exit !(c > 1.47e6 && c < 1.53e6) }' "$work/pipe/summary.json" && ok || bad "capacity"
grep -q "capacity" "$work/stdout" && ok || bad "stdout: $(cat "$work/stdout")"
# A rerun replaces the directory barimpact wrote (with the figures, where the
# build has the Python package that draws them); someone else's needs --force.
if [ -f "$(dirname "$bin")/python/barimpact/__init__.py" ]; then
  "$bin" match "$examples/pda/steel-pipe.toml" --out "$work/pipe" > /dev/null 2>&1 && ok || bad "rerun with figures"
  for f in force_match.png resistance.png static_test.png; do [ -s "$work/pipe/$f" ] && ok || bad "no $f"; done
fi
"$bin" match "$examples/pda/steel-pipe.toml" --out "$work/pipe" --no-plot > /dev/null 2>&1 && ok || bad "rerun"
[ ! -e "$work/pipe/resistance.png" ] && ok || bad "--no-plot drew (or left the last run's figures)"
# --no-plot, then plot: the same figures, drawn into the directory.
if [ -f "$(dirname "$bin")/python/barimpact/__init__.py" ]; then
  "$bin" plot "$work/pipe" > /dev/null 2> "$work/stderr" && ok || bad "plot after --no-plot: $(cat "$work/stderr")"
  for f in force_match resistance static_test; do [ -s "$work/pipe/$f.png" ] && ok || bad "plot drew no $f.png"; done
  expect_refused "leave out --out" plot "$work/pipe" --out "$work/refused"
fi
mkdir "$work/theirs" && touch "$work/theirs/notes.txt"
"$bin" match "$examples/pda/steel-pipe.toml" --out "$work/theirs" --no-plot > /dev/null 2>&1 && bad "wrote beside someone's files" || ok
[ -e "$work/theirs/notes.txt" ] && ok || bad "their file deleted"

# Fewer unknowns: the toe and the shaft only, quakes and dampings as given.
sed 's/^\[match\].*$/[match]\nunknowns = ["shaft", "toe"]\nshaft_damping = 0.16\ntoe_damping = 0.15\nstarts = 1/' \
  "$examples/pda/concrete-pile.toml" > "$work/two.toml"
sed -i "s|file = \"concrete-pile.csv\"|file = \"$examples/pda/concrete-pile.csv\"|" "$work/two.toml"
"$bin" match "$work/two.toml" --out "$work/two" --no-plot > /dev/null 2> "$work/stderr" && ok || bad "two unknowns: $(cat "$work/stderr")"
grep -q '"shaft_damping": 0.16,' "$work/two/summary.json" && ok || bad "a damping not fitted keeps its value"
grep -q '"starts": 1,' "$work/two/summary.json" && ok || bad "one start"

# An unevenly sampled record is matched unfiltered, with a warning in
# summary.json and on stderr; --strict then exits 4, its results written.
awk -F, 'NR == 300 { $1 = $1 + 5e-6 } { print }' OFS=, "$examples/pda/steel-pipe.csv" > "$work/uneven.csv"
sed "s|file = \"steel-pipe.csv\"|file = \"$work/uneven.csv\"|" "$examples/pda/steel-pipe.toml" > "$work/uneven.toml"
"$bin" match "$work/uneven.toml" --out "$work/uneven" --no-plot --strict > /dev/null 2> "$work/stderr"
[ $? -eq 4 ] && grep -q "match-unfiltered" "$work/stderr" && ok || bad "an uneven record's warning and --strict: $(cat "$work/stderr")"
grep -q '"match-unfiltered: the samples are not evenly spaced' "$work/uneven/summary.json" && grep -q '"low_pass": null' "$work/uneven/summary.json" && ok || bad "summary.json's warning"

# Bad settings: the key and its rule, nothing written.
bad_match() {  # name, [match] lines, expected message
  sed "s|file = \"steel-pipe.csv\"|file = \"$examples/pda/steel-pipe.csv\"|; /^\[match\]/,\$d" "$examples/pda/steel-pipe.toml" > "$work/$1.toml"
  printf '\n[match]\n%b\n' "$2" >> "$work/$1.toml"
  expect_refused "$3" match "$work/$1.toml" --out "$work/refused"
}
bad_match zero 'segments = 0' "match.segments must be a whole number in [1, 50]"
bad_match deep 'embedded = 30.0' "match.embedded must be in (0, 19.2] m"
bad_match law 'damping_law = "coulomb"' 'match.damping_law must be "smith" or "viscous"'
bad_match unknown 'unknowns = ["shaft", "skin"]' 'match.unknowns names "skin"'
bad_match quake 'toe_quake = 0.03' "match.toe_quake must be in [0.0005, 0.015]"
bad_match key 'segmnets = 4' "match.segmnets"
expect_refused "--jobs" match "$examples/pda/steel-pipe.toml" --out "$work/refused" --jobs -1
# The record's own refusals are pda's.
printf '[pile]\nlength = 20.0\narea = 0.01\nmodulus = 200e9\ndensity = 8000.0\n[record]\nfile = "none.csv"\nforce = "F"\nvelocity = "V"\n' > "$work/nofile.toml"
expect_refused "none.csv cannot be read" match "$work/nofile.toml" --out "$work/refused"

# A signal ends the fit: exit 130, nothing written, no staging left.
"$bin" match "$examples/pda/steel-pipe.toml" --out "$work/signalled" --no-plot > /dev/null 2>&1 &
pid=$!
sleep 0.3
kill -INT "$pid"
wait "$pid"
[ $? -eq 130 ] && ok || bad "SIGINT's exit"
[ ! -e "$work/signalled" ] && ! ls -a "$work" | grep -q partial && ok || bad "a signalled match left files"

# Ceres Solver is the fitting module's, loaded when a match fits: the
# command's start-up loads neither it nor the libraries it links.
needed=$(readelf -d "$bin" | grep NEEDED)
echo "$needed" | grep -qiE "ceres|glog|gflags|cholmod|gfortran|lapack|hdf5" && bad "the command needs: $needed" || ok
# Without its module (a command copied alone), a match ends on one line naming it; nothing written.
# (BARIMPACT_MODULE_DIR names an empty directory, the first place looked: an
# install of this version elsewhere on the machine would be found later.)
mkdir "$work/alone" "$work/empty" && cp "$bin" "$work/alone/barimpact"
BARIMPACT_MODULE_DIR="$work/empty" "$work/alone/barimpact" match "$examples/pda/steel-pipe.toml" --out "$work/alone/out" --no-plot > /dev/null 2> "$work/err"
code=$?
[ $code -eq 2 ] && [ "$(wc -l < "$work/err")" -eq 1 ] && grep -q "^barimpact: error: signal matching needs the fitting module libbarimpact_fit.so" "$work/err" &&
  [ ! -e "$work/alone/out" ] && ! ls -a "$work/alone" | grep -q partial && ok ||
  bad "a match without its module: exit $code: $(cat "$work/err")"

echo "match: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
