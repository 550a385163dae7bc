#!/usr/bin/env bash
# docs/figures.md, regenerated: every performance figure the documentation
# quotes, from the repository's measuring scripts, run here and written
# verbatim with the commit they measured. Needs valgrind and GNU time; takes
# about half an hour (the 4M-triangle loads under callgrind, and building
# the commit the memory rows are compared with). With PEER set to a
# checkout of github.com/autopawn/3d-ascii-viewer (and gcc and ncurses'
# headers) it also measures rastty against it.
#
#   PEER=/tmp/3d-ascii-viewer scripts/figures.sh    # rewrites docs/figures.md
set -euo pipefail
cd "$(dirname "$0")/.."
out=docs/figures.md
commit=$(git rev-parse --short HEAD)
dirty=$(git status --porcelain --untracked-files=no | grep -q . && echo " (with uncommitted changes)" || true)
section() { # title, what it shows, script
  printf '\n## %s\n\n%s\n\n```\n$ %s\n' "$1" "$2" "$3"
  # shellcheck disable=SC2086 # a script and its arguments
  bash $3
  printf '```\n'
}
{
  cat <<HEAD
# Figures

Every performance figure of rastty in one place, written by
\`scripts/figures.sh\` (do not edit by hand: run it) on this repository at
commit $commit$dirty, on $(nproc) cores of $(sed -n 's/^model name\s*: //p' /proc/cpuinfo | head -1).
Instruction counts come from callgrind and repeat exactly on the same
binary; times wander by ±20 % on this machine and are given only where
the script says so. Module documentation keeps the reasons and the
invariants; the numbers live here. \`rastty bench\`'s accuracy and time
of every knob is [its own page](bench.md) (\`cargo run --release -- bench
--svg docs/bench.svg > docs/bench.md\`).
HEAD
  section "Frame cost" "Instructions a frame, (40 frames − 10) / 30: Tux at 200×60 cells in half blocks, render alone and through \`spin\` (render, blit, encode), and the torus at 1000×300 cells on one thread and in bands." scripts/frame-cost.sh
  section "Bands" "Milliseconds a frame (wall clock, noisy: ±20 %, and the ratio as much from run to run), render only, half blocks, truecolor, one band against two drawn in turn ten frames each (docs/planner.md)." scripts/bands.sh
  section "Posing" "Instructions a frame, (40 frames − 10) / 30, of a skinned tube of 12,800 vertices at 200×60 half blocks: without a rig, its clip held, its clip playing; the same for a skinned human figure of 54 joints through \`spin\` (scripts/humanoid.sh); and the posing's cost a vertex (docs/scenes.md)." scripts/pose-cost.sh
  section "What the planner saves" "Instructions a frame, planned and full pipeline, for the planner's four scenes (docs/planner.md)." scripts/plan-cost.sh
  section "Against euc" "Instructions a frame, rastty against the euc crate, the bunny at 200×120 samples (docs/accuracy.md)." scripts/vs-euc.sh
  section "Loading" "Whole process, one frame: instructions, peak memory and (noisy) wall time, Tux, the bunny and generated tori of 10k to 4M triangles (docs/scenes.md)." scripts/load-cost.sh
  section "Memory, loading and start-up" "Issue 37's rows, for the commit before it (3544dc4) and the one before the program's code was laid out (9d8112f), each built beside this one, and this one: peak memory of one frame of Tux (in brackets, of \`rastty --version\`, which loads no model: the process's floor) and of the 4M-triangle torus; instructions of normals at load (\`Geometry::compute_normals\`, with welding and closedness) a triangle (in brackets, the normals alone: \`normals::smooth_normals\`, without the connectivity) and of OBJ parsing a byte (all that \`obj::load\` does but the normals), on the 1M-triangle torus; a steady Tux frame (render only, 200×60 half blocks); whole-process \`render cube\` and teapot; the binary with line tables and stripped. Peak memory is the median of three runs. This commit's binary lays out the functions the common commands run side by side at the start of its code (\`cli/hot-functions.ld\`, why in \`cli/build.rs\`): the last line says how many of the functions those commands run it lays out there. The line above it is what loading the 1M torus costs where the file has normals (a \`vn\` for each position): \`Geometry::analyze\`, the welding, corner lists and closedness that every mesh pays, with normals or without, a triangle." "scripts/memory-and-loading.sh 3544dc4 9d8112f"
  if [ -n "${PEER:-}" ]; then
    section "Against 3d-ascii-viewer" "One run of both: one frame, whole process, 200×60 cells of ASCII without colour, instructions and peak memory; the peer built with -O2 (docs/scenes.md)." "scripts/vs-3d-ascii-viewer.sh $PEER"
  fi
} > "$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"
