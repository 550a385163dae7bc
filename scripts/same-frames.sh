#!/usr/bin/env bash
# Frames of every shared model, glyph mode and colour depth (and a few
# frames of `spin`, and the moving models at three times) from one `rastty`
# binary, written to a directory, so
# that two binaries' frames can be compared byte for byte:
#
#   scripts/same-frames.sh OLD-BINARY /tmp/before
#   scripts/same-frames.sh target/release/rastty /tmp/after
#   diff -r /tmp/before /tmp/after && echo identical
set -euo pipefail
bin=$(realpath "$1"); out=$2
cd "$(dirname "$0")/.."
mkdir -p "$out"
models=(examples/models/crate.glb tests/models/bunny.obj tests/models/fox.obj)
for m in ../shared/models/*.obj ../shared/models/*.stl; do [ -f "$m" ] && models+=("$m"); done
for m in "${models[@]}"; do
  name=$(basename "$m")
  for g in ascii block half quadrant sextant octant braille; do
    for c in truecolor 256 16; do
      "$bin" render "$m" --cols 100 --rows 30 --glyphs "$g" --color "$c" > "$out/$name.$g.$c" 2>&1 || true
    done
  done
  "$bin" spin "$m" --cols 80 --rows 24 --frames 5 --color 256 > "$out/$name.spin" 2>&1 || true
done
"$bin" spin --cols 120 --rows 40 --frames 5 --threads 2 > "$out/default.spin" 2>&1 || true
for m in examples/models/arm.glb ../shared/models/animated/*.gltf; do
  [ -f "$m" ] || continue
  name=$(basename "$m")
  for t in 0 0.7 1.9; do
    "$bin" render "$m" --cols 100 --rows 30 --glyphs sextant --time "$t" > "$out/$name.$t" 2>&1 || true
  done
  "$bin" spin "$m" --cols 80 --rows 24 --frames 20 --color 256 > "$out/$name.spin" 2>&1 || true
done
