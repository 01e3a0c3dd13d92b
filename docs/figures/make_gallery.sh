#!/usr/bin/env bash
# Regenerates the figures of the docs (all but docs/verification.sh's): the
# gallery of docs/figures.md (docs/figures/gallery-*.png, each command's
# main figures) and those README.md, docs/pile.md and docs/tutorial.md show,
# from the examples run into a temporary directory.
#   bash docs/figures/make_gallery.sh [BUILD_DIR]    (default build/release)
#   KEEP=DIR bash docs/figures/make_gallery.sh ...   (keeps every output in DIR)
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build/release}
bin="$build/barimpact"
[ -x "$bin" ] || { echo "make_gallery: no $bin (give the build directory)" >&2; exit 2; }
out=${KEEP:-$(mktemp -d)}
mkdir -p "$out"
[ -n "${KEEP:-}" ] || trap 'rm -rf "$out"' EXIT
ex=examples

quiet() { "$@" > "$out/last.log" 2>&1 || { cat "$out/last.log" >&2; exit 1; }; }

# Each command on one example, its figures drawn.
quiet "$bin" run "$ex/pile/steel-pipe-sand.toml" --out "$out/pile"
quiet "$bin" plot "$out/pile"
quiet "$bin" run "$ex/paper-example1.toml" --out "$out/example1"
quiet "$bin" plot "$out/example1"
quiet "$bin" exact "$ex/lines/drop-mass.toml" --out "$out/exact"
quiet "$bin" plot "$out/exact"
quiet "$bin" converge "$ex/paper-example1.toml" --schemes paper,newmark,central-difference --levels 3 \
  --set time.scheme=central-difference --set time.step=0.005 --out "$out/converge"
quiet "$bin" sweep "$ex/sweeps/penalty-to-rigid.toml" --out "$out/sweep" --jobs 2
quiet "$bin" plot "$out/sweep"
quiet "$bin" bearing "$ex/pile/steel-pipe-sand.toml" --out "$out/bearing" --capacity 0.5e6:3e6:8 --jobs 2
quiet "$bin" drive "$ex/pile/drive-pipe-drop.toml" --out "$out/drive" --jobs 2 --set "drive.depths=2:18:6"
quiet "$bin" run "$ex/hopkinson/shpb.toml" --out "$out/shpb"
sed "s|\.\./\.\./out/shpb|$out/shpb|" "$ex/hopkinson/analyse-run.toml" > "$out/analyse-run.toml"
quiet "$bin" hopkinson "$out/analyse-run.toml" --out "$out/hopkinson"
quiet "$bin" pda "$ex/pda/steel-pipe.toml" --out "$out/pda"
quiet "$bin" match "$ex/pda/steel-pipe.toml" --out "$out/match" --jobs 2

# The figures the README and the docs show.
quiet "$bin" run "$ex/paper-example2.toml" --out "$out/example2"
quiet "$bin" plot "$out/example2"
quiet "$bin" bearing "$ex/pile/steel-pipe-sand.toml" --out "$out/bearing-docs" --capacity 0.5e6:4e6:20 --jobs 2
quiet "$bin" run "$ex/pile/concrete-clay.toml" --out "$out/concrete"
quiet "$bin" plot "$out/concrete"
for lines in drop-mass hopkinson pile-hammer saint-venant; do
  quiet "$bin" run "$ex/lines/$lines.toml" --out "$out/lines-$lines"
  quiet "$bin" plot "$out/lines-$lines"
done
for plastic in taylor-bar paper-example1-yielding pipe-whip; do
  quiet "$bin" run "$ex/plastic/$plastic.toml" --out "$out/plastic-$plastic"
  quiet "$bin" plot "$out/plastic-$plastic"
done

# The chosen figures, PNG only.
pick() {  # source figure, gallery name
  cp "$out/$1" "docs/figures/gallery-$2.png"
}
pick pile/figures/blow_head.png pile-head
pick pile/figures/blow_toe.png pile-toe
pick pile/figures/stress_map.png pile-stress-map
pick pile/figures/joint_forces.png pile-joint-forces
pick example1/figures/displacement.png run-displacement
pick exact/figures/masses.png exact-masses
pick converge/convergence.png converge
pick sweep/figures/max_reaction.png sweep
pick bearing/bearing.png bearing
pick drive/drive.png drive
pick hopkinson/figures/stress_strain.png hopkinson-stress-strain
pick hopkinson/figures/waves.png hopkinson-waves
pick pda/force_velocity.png pda
pick match/force_match.png match
docs() {  # source figure, the docs' name
  cp "$out/$1" "docs/figures/$2.png"
}
docs example1/figures/displacement.png example1-displacement
docs example1/figures/energy.png example1-energy
docs example1/figures/snapshots.png example1-snapshots
docs example1/figures/stress_map.png example1-stress-map
docs example2/figures/impacts.png example2-impacts
docs pile/figures/blow_head.png pile-steel-pipe-head
docs pile/figures/blow_toe.png pile-steel-pipe-toe
docs pile/figures/blow_envelopes.png pile-steel-pipe-envelopes
docs bearing-docs/bearing.png pile-steel-pipe-bearing
docs concrete/figures/blow_head.png pile-concrete-head
docs concrete/figures/blow_envelopes.png pile-concrete-envelopes
docs lines-drop-mass/figures/joint_forces.png lines-drop-mass-joint-forces
docs lines-hopkinson/figures/gauges.png lines-hopkinson-gauges
docs lines-pile-hammer/figures/joint_forces.png lines-pile-hammer-joint-forces
docs lines-saint-venant/figures/stress_map.png lines-saint-venant-stress-map
docs plastic-taylor-bar/figures/plastic_map.png plastic-taylor-bar-plastic-map
docs plastic-paper-example1-yielding/figures/energy.png plastic-paper-example1-energy
docs plastic-paper-example1-yielding/figures/stress_map.png plastic-paper-example1-stress-map
docs plastic-pipe-whip/figures/plastic_map.png plastic-pipe-whip-plastic-map
ls -l docs/figures/gallery-*.png
