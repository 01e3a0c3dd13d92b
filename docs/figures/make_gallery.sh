#!/usr/bin/env bash
# Regenerates the gallery of docs/figures.md: runs each command on an
# example into a temporary directory and copies its main figures to
# docs/figures/gallery-*.png.
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
ls -l docs/figures/gallery-*.png
