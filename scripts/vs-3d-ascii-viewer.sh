#!/usr/bin/env bash
# rastty against 3d-ascii-viewer (github.com/autopawn/3d-ascii-viewer, a C
# terminal mesh viewer), from one run of both: one frame of a model, whole
# process (start, load, draw, print), 200×60 cells of ASCII without colour
# (`rastty render --glyphs ascii --color none`, `3d-ascii-viewer --snap 0 0`):
# instructions (callgrind) and peak memory (GNU time). The peer is built
# with -O2 (its Makefile passes no -O). Models: Tux, the teapot, the bunny
# and generated tori of 1M and 4M triangles (examples/torus_obj, as
# scripts/load-cost.sh makes them). The 4M rows take some minutes under
# callgrind. Needs valgrind, GNU time, gcc and ncurses' headers.
#
#   git clone https://github.com/autopawn/3d-ascii-viewer /tmp/peer
#   scripts/vs-3d-ascii-viewer.sh /tmp/peer
set -euo pipefail
peer_src=$(realpath "$1")
cd "$(dirname "$0")/.."
# RASTTY=path measures another build of rastty (an older commit's).
bin=${RASTTY:-target/release/rastty}
[ -n "${RASTTY:-}" ] || cargo build --release -q
cargo build --release -q --example torus_obj
peer=target/vs-peer/3d-ascii-viewer-O2
mkdir -p target/vs-peer target/load-cost
gcc -O2 -o "$peer" "$peer_src"/src/*.c -lm -lncurses
for n in 1000000 4000000; do
  [ -s "target/load-cost/torus-$n.obj" ] || target/release/examples/torus_obj "$n" > "target/load-cost/torus-$n.obj"
done
# The peer starts curses even for one snap: it needs a terminal type.
export TERM=xterm
count() { valgrind --tool=callgrind --callgrind-out-file=/dev/null "$@" 2>&1 >/dev/null | sed -n 's/.*Collected : //p'; }
peak() { /usr/bin/time -o target/vs-peer/time -f '%M' "$@" >/dev/null 2>&1; cat target/vs-peer/time; }
mib() { echo "scale=1; $1 / 1024" | bc; }
printf '| model | triangles | rastty instructions | peer instructions | ratio | rastty peak memory | peer peak memory |\n'
printf '|---|---:|---:|---:|---:|---:|---:|\n'
for model in tests/models/linux-mascot-tux.obj tests/models/teapot.obj tests/models/bunny.obj \
    target/load-cost/torus-1000000.obj target/load-cost/torus-4000000.obj; do
  tris=$(awk '/^f /{t += NF - 3} END {print t}' "$model")
  ours=("$bin" render "$model" --cols 200 --rows 60 --glyphs ascii --color none)
  theirs=("$peer" --snap 0 0 -w 200 -h 60 "$model")
  a=$(count "${ours[@]}")
  b=$(count "${theirs[@]}")
  printf '| %s | %d | %.1fM | %.1fM | %.2f× | %s MiB | %s MiB |\n' "$(basename "$model")" "$tris" \
    "$(echo "$a / 1000000" | bc -l)" "$(echo "$b / 1000000" | bc -l)" "$(echo "$a / $b" | bc -l)" \
    "$(mib "$(peak "${ours[@]}")")" "$(mib "$(peak "${theirs[@]}")")"
done
