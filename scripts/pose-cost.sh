#!/usr/bin/env bash
# What posing a moving model costs, in instructions a frame (callgrind,
# (40 frames − 10) / 30): a skinned tube of 12,800 vertices (four joints,
# two a vertex) at 200×60 half blocks, drawn without a rig, with its clip
# held (posed once), and playing (posed every frame); and the posing's
# cost a vertex, (playing − held) / vertices. examples/pose_cost.rs.
#
#   scripts/pose-cost.sh          (needs valgrind)
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q --example pose_cost
count() { valgrind --tool=callgrind --callgrind-out-file=/dev/null target/release/examples/pose_cost "$@" 2>&1 | sed -n 's/.*Collected : //p'; }
per_frame() { local a b; a=$(count "$1" 10); b=$(count "$1" 40); echo $(( (b - a) / 30 )); }
s=$(per_frame static); h=$(per_frame held); p=$(per_frame playing)
echo "| tube, 12,800 vertices | instructions a frame |"
echo "|---|---:|"
echo "| no rig | $s |"
echo "| skinned, clip held (posed once) | $h |"
echo "| skinned, clip playing (posed every frame) | $p |"
echo "| posing, a vertex: (playing − held) / 12,800 | $(( (p - h) / 12800 )) |"
