#!/usr/bin/env bash
# What posing a moving model costs, in instructions a frame (callgrind,
# (40 frames − 10) / 30): a skinned tube of 12,800 vertices (four joints,
# two a vertex) at 200×60 half blocks, drawn without a rig, with its clip
# held (posed once), and playing (posed every frame); and the posing's
# cost a vertex, (playing − held) / vertices. examples/pose_cost.rs.
# Then a real skinned figure (scripts/humanoid.sh: 54 joints, 5,126
# triangles) through `rastty spin` at 200×60 half blocks, its clip held
# (`--speed 0`) and playing, where scripts/humanoid.sh can make it.
#
#   scripts/pose-cost.sh          (needs valgrind)
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q --example pose_cost
measure() { valgrind --tool=callgrind --callgrind-out-file=/dev/null "$@" 2>&1 >/dev/null | sed -n 's/.*Collected : //p'; }
count() { measure target/release/examples/pose_cost "$@"; }
per_frame() { local a b; a=$(count "$1" 10); b=$(count "$1" 40); echo $(( (b - a) / 30 )); }
s=$(per_frame static); h=$(per_frame held); p=$(per_frame playing)
echo "| tube, 12,800 vertices | instructions a frame |"
echo "|---|---:|"
echo "| no rig | $s |"
echo "| skinned, clip held (posed once) | $h |"
echo "| skinned, clip playing (posed every frame) | $p |"
echo "| posing, a vertex: (playing − held) / 12,800 | $(( (p - h) / 12800 )) |"

if humanoid=$(scripts/humanoid.sh 2>/dev/null); then
  cargo build --release -q
  spin() { measure target/release/rastty spin "$humanoid" --cols 200 --rows 60 --glyphs half --color truecolor --speed "$1" --frames "$2"; }
  held() { spin 0 "$1"; }
  playing() { spin 1 "$1"; }
  per() { local a b; a=$("$1" 10); b=$("$1" 40); echo $(( (b - a) / 30 )); }
  v=$(target/release/rastty render "$humanoid" --cols 200 --rows 60 --time 1 --explain 2>&1 | sed -n 's/^ *\([0-9]*\) vertices posed$/\1/p')
  h=$(per held); p=$(per playing)
  echo
  echo "| skinned figure ($v vertices, 54 joints), spin | instructions a frame |"
  echo "|---|---:|"
  echo "| clip held (\`--speed 0\`: posed once) | $h |"
  echo "| clip playing (posed every frame) | $p |"
  echo "| posing, a vertex: (playing − held) / $v | $(( (p - h) / v )) |"
else
  echo
  echo "(the skinned figure is left out: scripts/humanoid.sh could not make it)"
fi
