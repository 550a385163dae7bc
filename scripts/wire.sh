#!/usr/bin/env bash
# The three `--wire` modes (`w` in spin) on the fox (CC-BY 4.0, see
# ../shared/models/README.md) whole, and on Tux (CC0) drawn 2.2 times
# larger around its head: docs/wire/<model>-<mode>.png, 200×64 cells of
# octants (400×256 samples), each cell 4×8 pixels.
#
#   scripts/wire.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q
mkdir -p docs/wire
models=../shared/models
for mode in solid lines edges; do
  view=(--cols 200 --rows 64 --glyphs octant --cell-px 4x8 --wire "$mode")
  target/release/rastty render "$models/fox.obj" "${view[@]}" --output "docs/wire/fox-$mode.png"
  target/release/rastty render "$models/linux-mascot-tux.obj" "${view[@]}" \
    --zoom 2.2 --pan 0.05,-0.55 --output "docs/wire/tux-$mode.png"
  echo "docs/wire/fox-$mode.png docs/wire/tux-$mode.png"
done
