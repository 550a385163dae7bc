#!/usr/bin/env bash
# Writes cli/hot-functions.ld: a linker script that lays out first in
# .text, side by side, the functions of the release binary that the common
# commands run, in the order they are first needed, command by command
# (start-up, a small model, Tux, spin, then pictures, colours and the other
# loaders), then the rest of the code as the linker would. cli/build.rs
# gives it to the linker (why: its doc). The code stays in the one section
# named .text, where valgrind finds its symbols (in a section of another
# name, callgrind names none of its functions).
#
# A function is named by its section, `.text.` and its symbol (or
# `.text.unlikely.` and its symbol, where the compiler found it cold: a
# mangled name is matched after any prefix, a plain C name exactly): the
# program's own mangled names, which change with the compiler, the
# dependencies and the feature set (a function new since the script was
# last written is not in it). Where LLVM ends a name with `.llvm.` and a
# hash of its code unit (which changes with the folder the repository is
# in), the section is matched whatever the hash. Functions with the same
# code share one body under several names: each name at a body's address
# is listed, as callgrind reports one of them.
#
# Two builds of the program are looked at, as their symbols differ: the
# workspace's (`cargo build --release`, `cargo run --release`, which the
# README and the figures use) and the program's alone (`cargo build
# --release -p rastty-cli`, `cargo install --path cli`), whose
# dependencies are built with fewer features.
#
# With --check, writes nothing and says how many of the functions the
# commands run the workspace's binary has before the script's end mark.
#
#   scripts/hot-functions.sh [--check]        (needs valgrind)
set -euo pipefail
cd "$(dirname "$0")/.."
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

# The functions binary $1 runs (of its own: not of the C libraries, nor
# callgrind's names for code without a symbol), appended to $2 command
# by command, those no command before ran by name; its symbols by address
# (in decimal) in $2.symbols.
collect() {
  local bin=$1 list=$2 k=0
  : > "$list"
  for r in "${runs[@]}"; do
    k=$((k + 1))
    # shellcheck disable=SC2086
    valgrind --tool=callgrind --demangle=no --compress-strings=no \
      --callgrind-out-file="$out/cg" "$bin" $r > /dev/null 2>&1
    awk -v bin="$bin" '
      /^ob=/ { ob = substr($0, 4) }
      /^fn=/ { if (ob == bin) print substr($0, 4) }
    ' "$out/cg" | grep -E '^[A-Za-z_]' | sort -u > "$out/run"
    grep -vxF -f "$list" "$out/run" >> "$list" || true
  done
  nm -t d --defined-only "$bin" | awk '$2 ~ /^[tTwW]$/ { print $1, $3 }' > "$list.symbols"
}

cargo build --release -q
collect "$PWD/target/release/rastty" "$out/workspace"
if [ "${1:-}" = --check ]; then
  end=$(awk '$3 == "__rastty_hot_end" { print $1 + 0 }' <(nm -t d target/release/rastty))
  awk -v end="${end:-0}" '
    NR == FNR { want[$0] = 1; next }
    ($2 in want) { hot[$2] = hot[$2] || $1 + 0 < end }
    END { n = 0; h = 0; for (s in want) { n++; if (hot[s]) h++ }
          printf "%d of the %d functions the commands run are laid out first\n", h, n }
  ' "$out/workspace" "$out/workspace.symbols"
  exit 0
fi
CARGO_TARGET_DIR=$out/target cargo build --release -q -p rastty-cli
collect "$PWD/$out/target/release/rastty" "$out/program"

# Each name run, then the other names at its address; a name's section
# pattern, with any hash after `.llvm.` matched by `*`: the workspace's,
# then the program's.
for b in workspace program; do
  awk '
    NR == FNR { names[$1] = names[$1] " " $2; at[$2] = $1; next }
    { print $0; n = split(names[at[$0]], same, " "); for (i = 1; i <= n; i++) if (same[i] != $0) print same[i] }
  ' "$out/$b.symbols" "$out/$b"
done | sed 's/\.llvm\.[0-9]*$/.llvm.*/' | awk '!seen[$0]++' > "$out/patterns"
{
  echo "/* Written by scripts/hot-functions.sh: the functions the common commands run,"
  echo "   side by side at the start of .text (cli/build.rs). */"
  echo "SECTIONS"
  echo "{"
  echo "  .text : {"
  sed -E 's/^(_ZN|_R).*/    *(.text.*\0)/; s/^[^ ].*/    *(.text.\0)/' "$out/patterns"
  echo "    __rastty_hot_end = .;"
  echo "    *(.text .text.*)"
  echo "  }"
  echo "}"
  echo "INSERT BEFORE .init;"
} > cli/hot-functions.ld
echo "$(wc -l < "$out/patterns") section patterns in cli/hot-functions.ld"
