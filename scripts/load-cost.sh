#!/usr/bin/env bash
# What loading costs, whole process: `rastty render MODEL --cols 200
# --rows 60 --color truecolor` (load, one frame, print) on Tux, the bunny
# and generated tori of 10k to 4M triangles: instructions (callgrind),
# peak memory (GNU time) and wall time (GNU time; noisy). docs/scenes.md, "Loading models".
# Needs valgrind and /usr/bin/time; the 4M torus takes a few minutes under
# callgrind.
#
#   scripts/load-cost.sh
set -euo pipefail
cd "$(dirname "$0")/.."
# RASTTY=path measures another build of rastty (an older commit's).
bin=${RASTTY:-target/release/rastty}
[ -n "${RASTTY:-}" ] || cargo build --release -q
cargo build --release -q --example torus_obj
dir=target/load-cost
mkdir -p "$dir"
for n in 10000 100000 1000000 4000000; do
  [ -s "$dir/torus-$n.obj" ] || target/release/examples/torus_obj "$n" > "$dir/torus-$n.obj"
done
args=(--cols 200 --rows 60 --color truecolor)
printf '| model | triangles | file | instructions | per triangle | peak memory | per triangle | time |\n'
printf '|---|---:|---:|---:|---:|---:|---:|---:|\n'
for model in tests/models/linux-mascot-tux.obj tests/models/bunny.obj \
    "$dir"/torus-10000.obj "$dir"/torus-100000.obj "$dir"/torus-1000000.obj "$dir"/torus-4000000.obj; do
  tris=$(awk '/^f /{t += NF - 3} END {print t}' "$model")
  size=$(stat -c %s "$model")
  instr=$(valgrind --tool=callgrind --callgrind-out-file=/dev/null "$bin" render "$model" "${args[@]}" 2>&1 >/dev/null | sed -n 's/.*Collected : //p')
  read -r kb secs < <( { /usr/bin/time -f '%M %e' "$bin" render "$model" "${args[@]}" >/dev/null; } 2>&1 | tail -1)
  printf '| %s | %d | %.1f MiB | %.1fM | %d | %.1f MiB | %d B | %s s |\n' \
    "$(basename "$model")" "$tris" "$(echo "$size / 1048576" | bc -l)" \
    "$(echo "$instr / 1000000" | bc -l)" $(( instr / tris )) \
    "$(echo "$kb / 1024" | bc -l)" $(( kb * 1024 / tris )) "$secs"
done
