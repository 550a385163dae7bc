#!/usr/bin/env bash
# Instructions per frame, planned and full pipeline, for the planner's four
# benchmark scenes (docs/planner.md). Counted
# by callgrind, so the numbers repeat exactly on the same binary whatever
# else the machine is doing. Needs valgrind.
#
#   scripts/plan-cost.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --example profile_scene -q
bin=target/release/examples/profile_scene
count() { # scene frames flags...
  valgrind --tool=callgrind --callgrind-out-file=/dev/null "$bin" "$@" 2>&1 | sed -n 's/.*Collected : //p'
}
per_frame() { # scene flags...: (instructions of 40 frames − of 10) / 30, leaving out loading
  local scene=$1; shift
  local a b
  a=$(count "$scene" 10 "$@")
  b=$(count "$scene" 40 "$@")
  echo $(( (b - a) / 30 ))
}
echo "| scene | planned (instructions/frame) | full (instructions/frame) | full / planned |"
echo "|---|---:|---:|---:|"
while IFS='|' read -r name scene flags; do
  p=$(per_frame "$scene" $flags)
  f=$(per_frame "$scene" full $flags)
  printf '| %s | %s | %s | %s |\n' "$name" "$p" "$f" "$(awk "BEGIN { printf \"%.2f\", $f / $p }")"
done <<'SCENES'
2D flat tiles|examples/scenes/tiles.toml|
flat-shaded convex sphere|sphere|flat
smooth-lit bunny|tests/models/bunny.obj|
overlapping meshes|examples/scenes/overlap.toml|
SCENES
