#!/usr/bin/env bash
# One band against one a core, render only, wall clock (examples/bands.rs):
#
#   scripts/bands.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cargo run --release -q --example bands
