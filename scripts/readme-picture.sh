#!/usr/bin/env bash
# The README's picture: one frame of a shared model (Tux, CC0; see
# ../shared/models/README.md), painted by rastty's own `render --output`.
# Regenerate it after a change to what frames look like:
#
#   scripts/readme-picture.sh [MODELS_DIR]     # default ../shared/models
set -euo pipefail
cd "$(dirname "$0")/.."
models=${1:-../shared/models}
cargo build --release --quiet
./target/release/rastty render "$models/linux-mascot-tux.obj" \
    --cols 96 --rows 30 --glyphs octant --color truecolor \
    --output docs/tux.png
echo "wrote docs/tux.png ($(wc -c <docs/tux.png) bytes)"
