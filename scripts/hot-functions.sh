#!/usr/bin/env bash
# Writes cli/hot-functions.txt: the functions of the release binary that
# the common commands run, in the order they are first needed, command by
# command (start-up, a small model, Tux, spin, then pictures, colours and
# the other loaders), which cli/build.rs gives the linker to lay out side
# by side (why: its doc). Symbols are the binary's own mangled names: they
# change with the compiler, the dependencies and the feature set, and new
# functions are not in the file until it is written again; those whose
# names depend on where the repository is are left out (see below). With --check,
# writes nothing and says how many of the functions run are in the file.
#
#   scripts/hot-functions.sh [--check]        (needs valgrind)
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q -p rastty-cli
bin=$PWD/target/release/rastty
out=target/hot-functions
mkdir -p "$out"
m=../shared/models
tux=tests/models/linux-mascot-tux.obj
runs=(
  "--version"
  "render cube"
  "render $tux --cols 200 --rows 60 --color truecolor"
  "spin $tux --frames 8 --cols 120 --rows 40 --color 256"
  "render tests/models/teapot.obj --color 16 --glyphs braille"
  "render tests/models/bunny.obj --output $out/bunny.png"
  "render tests/models/fox.obj --color truecolor"
  "render tests/models/shiba-inu-binary.stl"
)
[ -d "$m/animated" ] && runs+=("spin $m/animated/BoxAnimated.gltf --frames 4 --cols 80 --rows 30")
: > "$out/all.txt"
k=0
for r in "${runs[@]}"; do
  k=$((k + 1))
  # shellcheck disable=SC2086
  valgrind --tool=callgrind --demangle=no --compress-strings=no \
    --callgrind-out-file="$out/cg.$k" "$bin" $r > /dev/null 2>&1
  # The functions of the binary itself (not of the C libraries, nor
  # callgrind's names for code without a symbol); those no command before
  # ran appended, by name. Not the names LLVM ends with `.llvm.` and a
  # hash of the code unit, which changes with the folder the repository
  # is in: a clone elsewhere would not find them.
  awk -v bin="$bin" '
    /^ob=/ { ob = substr($0, 4) }
    /^fn=/ { if (ob == bin) print substr($0, 4) }
  ' "$out/cg.$k" | grep -E '^[A-Za-z_]' | sort -u > "$out/run.$k"
  grep -vF '.llvm.' "$out/run.$k" | grep -vxF -f "$out/all.txt" >> "$out/all.txt" || true
done
if [ "${1:-}" = --check ]; then
  run=$(sort -u "$out"/run.* | wc -l)
  listed=$(sort -u "$out"/run.* | grep -cxF -f <(grep -v '^#' cli/hot-functions.txt) || true)
  folder=$(sort -u "$out"/run.* | grep -cF '.llvm.' || true)
  echo "cli/hot-functions.txt lists $listed of the $run functions the commands run ($folder have names that depend on the folder)"
  exit 0
fi
{
  echo "# Written by scripts/hot-functions.sh: the functions the common commands run,"
  echo "# which the linker lays out side by side (cli/build.rs)."
  cat "$out/all.txt"
} > cli/hot-functions.txt
echo "$(wc -l < "$out/all.txt") functions in cli/hot-functions.txt"
