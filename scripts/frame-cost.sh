#!/usr/bin/env bash
# Instructions a frame, counted by callgrind as (instructions of 40 frames −
# of 10) / 30, which leaves out loading and the first (full) frame:
#
#   1. Tux at 200×60 cells, half blocks, truecolor, render only
#      (examples/profile_scene, turning 3° a frame);
#   2. the same through `rastty spin` (render, blit and encode; not a tty);
#   3. the built-in torus spinning at 1000×300 cells, half blocks, truecolor,
#      through `rastty spin`: render, blit and encode, also per cell; on one
#      thread, and in bands on every core (`--threads auto`), where the
#      count is every thread's instructions together.
#
#   scripts/frame-cost.sh          (needs valgrind)
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --example profile_scene -q
cargo build --release -q
tux=../shared/models/linux-mascot-tux.obj
[ -f "$tux" ] || { echo "needs $tux" >&2; exit 1; }
count() { valgrind --tool=callgrind --callgrind-out-file=/dev/null "$@" 2>&1 | sed -n 's/.*Collected : //p'; }
per_frame() {
  local a b
  a=$("$@" 10)
  b=$("$@" 40)
  echo $(( (b - a) / 30 ))
}
profile() { count target/release/examples/profile_scene "$tux" "$1"; }
spin_tux() { count target/release/rastty spin "$tux" --cols 200 --rows 60 --glyphs half --color truecolor --frames "$1"; }
spin_big() { count target/release/rastty spin --cols 1000 --rows 300 --glyphs half --color truecolor --threads 1 --frames "$1"; }
spin_bands() { count target/release/rastty spin --cols 1000 --rows 300 --glyphs half --color truecolor --threads auto --frames "$1"; }
echo "Tux 200×60, render only: $(per_frame profile) instructions a frame"
echo "Tux 200×60, spin (render + blit + encode): $(per_frame spin_tux) instructions a frame"
big=$(per_frame spin_big)
echo "torus 1000×300, spin (render + blit + encode), one thread: $big instructions a frame, $(( big / 300000 )) a cell"
bands=$(per_frame spin_bands)
echo "torus 1000×300, spin, in bands (every thread's instructions): $bands a frame, $(( bands / 300000 )) a cell"
