#!/usr/bin/env bash
# barimpact pda: its files and columns on the examples' generated records, and
# every refusal of a bad record (exit 2, one line, nothing written).
# Usage: pda_test.sh BARIMPACT EXAMPLES_DIR
set -u
. "$(dirname "${BASH_SOURCE[0]}")/preamble.sh"

# The steel pipe's record: pda.csv with the contract's columns, one row a
# sample; summary.json with the contract's keys; the figures.
"$bin" pda "$examples/pda/steel-pipe.toml" --out "$work/pipe" > "$work/stdout" 2> "$work/stderr" && ok || bad "pipe exit: $(cat "$work/stderr")"
[ "$(head -1 "$work/pipe/pda.csv" | cut -d, -f1-6)" = "t,force,velocity_z,wave_down,wave_up,displacement" ] && ok || bad "pda.csv columns"
samples=$(($(wc -l < "$examples/pda/steel-pipe.csv") - 2))
[ "$(($(wc -l < "$work/pipe/pda.csv") - 1))" -eq "$samples" ] && ok || bad "one row a sample ($samples)"
for key in t1 t2 fmx vmx emx dmx csx tsx rmx rmx_time rsp bta bta_depth; do
  grep -q "^  \"$key\": " "$work/pipe/summary.json" && ok || bad "summary.json has no $key"
done
if [ -f "$(dirname "$bin")/python/barimpact/__init__.py" ]; then  # a build with the Python package (figures)
  for f in force_velocity.png waves.png; do [ -s "$work/pipe/$f" ] && ok || bad "no $f"; done
fi
grep -q "RMX" "$work/stdout" && ok || bad "stdout: $(cat "$work/stdout")"
"$bin" pda "$examples/pda/concrete-pile.toml" --out "$work/concrete" --no-plot > /dev/null 2>&1 && ok || bad "concrete exit"
[ ! -e "$work/concrete/waves.png" ] && ok || bad "--no-plot drew"
# --no-plot, then plot: the figures drawn into the directory.
if [ -f "$(dirname "$bin")/python/barimpact/__init__.py" ]; then
  "$bin" plot "$work/concrete" > /dev/null 2>&1 && [ -s "$work/concrete/waves.png" ] && ok || bad "plot after --no-plot"
fi
# A rerun replaces the directory barimpact wrote; someone else's needs --force.
"$bin" pda "$examples/pda/concrete-pile.toml" --out "$work/concrete" --no-plot > /dev/null 2>&1 && ok || bad "rerun"
mkdir "$work/theirs" && touch "$work/theirs/notes.txt"
"$bin" pda "$examples/pda/concrete-pile.toml" --out "$work/theirs" --no-plot > /dev/null 2>&1 && bad "wrote beside someone's files" || ok
"$bin" pda "$examples/pda/concrete-pile.toml" --out "$work/theirs" --no-plot --force > /dev/null 2>&1 && [ -s "$work/theirs/pda.csv" ] && ok || bad "--force"

# Bad records. A small record: P = 2 MN half-sine over 2 ms from t = 2 ms, a
# uniform pile with 2L/c = 8 ms, Z = 4e5 N s/m, samples every 0.1 ms to 40 ms.
record() {  # name, then the scales of F1 F2 (of f) and V1 V2 (of v); writes $work/NAME.csv
  awk -v a1="$2" -v a2="$3" -v b1="$4" -v b2="$5" 'BEGIN {
    print "t,F1,F2,V1,V2"
    for (k = 0; k < 400; k++) {
      t = k * 1e-4; s = (t - 0.002) / 0.002
      f = (s > 0 && s < 1) ? 2e6 * sin(3.141592653589793 * s) : 0; v = f / 4e5
      printf "%.6g,%.8g,%.8g,%.8g,%.8g\n", t, a1 * f, a2 * f, b1 * v, b2 * v
    }
  }' > "$work/$1.csv"
}
toml() {  # name, csv name, extra [pile] lines, [record] channel lines, other sections
  printf '[pile]\nlength = 20.0\narea = 0.01\nmodulus = 200e9\ndensity = 8000.0\n%b\n[record]\nfile = "%s.csv"\n%b\n%b\n' \
    "$3" "$2" "$4" "$5" > "$work/$1.toml"
}
two='force = ["F1", "F2"]\nvelocity = ["V1", "V2"]'
record good 1 1 1 1
toml good good "" "$two" ""
"$bin" pda "$work/good.toml" --out "$work/good" --no-plot > /dev/null 2>&1 && ok || bad "the small record is analysed"
grep -q '"bta": 1.0' "$work/good/summary.json" && ok || bad "the small record's beta"
toml nofile missing "" "$two" ""
expect_refused "missing.csv cannot be read" pda "$work/nofile.toml" --out "$work/refused"
toml nocol good "" 'force = ["F1", "F3"]\nvelocity = "V1"' ""
expect_refused 'force: no column "F3"' pda "$work/nocol.toml" --out "$work/refused"
cp "$work/good.csv" "$work/cell.csv" && echo "0.05,1,x,0,0" >> "$work/cell.csv"
toml cell cell "" "$two" ""
expect_refused 'cell.csv:402: record: column "F2" holds "x"' pda "$work/cell.toml" --out "$work/refused"
cp "$work/good.csv" "$work/time.csv" && echo "0.01,0,0,0,0" >> "$work/time.csv"
toml time time "" "$two" ""
expect_refused 'time column "t" is not increasing' pda "$work/time.toml" --out "$work/refused"
record tension -1 0 0 0
toml tension tension "" 'force = "F1"\nvelocity = "V1"' ""
expect_refused "record: no impact" pda "$work/tension.toml" --out "$work/refused"
head -100 "$work/good.csv" > "$work/short.csv"
toml short short "" "$two" ""
expect_refused "before t2 = t1 + 2L/c" pda "$work/short.toml" --out "$work/refused"
(head -1 "$work/good.csv"; sed -n '15,$p' "$work/good.csv") > "$work/late.csv"
toml late late "" "$two" ""
expect_refused "starts too late for the offsets" pda "$work/late.toml" --out "$work/refused"
record bending 0.25 1 1 1
toml bending bending "" "$two" ""
expect_refused 'force channels "F1" and "F2" differ at t1' pda "$work/bending.toml" --out "$work/refused"
record slow 1 1 1 0.5
toml slow slow "" 'force = "F1"\nvelocity = "V2"' ""
expect_refused "F / (Z v) = 2 at t1" pda "$work/slow.toml" --out "$work/refused"
toml unknown good "colour = 1" "$two" ""
expect_refused "unknown key pile.colour" pda "$work/unknown.toml" --out "$work/refused"
printf '[pile]\nlength = 20.0\narea = 0.01\nmodulus = 200e9\n[record]\nfile = "good.csv"\nforce = "F1"\nvelocity = "V1"\n' > "$work/nodensity.toml"
expect_refused "pile.density is missing" pda "$work/nodensity.toml" --out "$work/refused"
toml negative good "wave_speed = -1" "$two" ""
expect_refused "pile.wave_speed must be > 0" pda "$work/negative.toml" --out "$work/refused"
toml both good "" 'force = "F1"\nstrain = "F2"\nvelocity = "V1"' ""
expect_refused "record.strain and force both given" pda "$work/both.toml" --out "$work/refused"
toml neither good "" 'force = "F1"' ""
expect_refused "record.velocity is missing" pda "$work/neither.toml" --out "$work/refused"
toml damping good "" "$two" '[case_method]\ndamping = -0.1'
expect_refused "case_method.damping must be in [0, 1]" pda "$work/damping.toml" --out "$work/refused"
expect_refused "cannot read the record file" pda "$work/none.toml" --out "$work/refused"

echo "$passed passed, $failed failed"
[ $failed -eq 0 ]
