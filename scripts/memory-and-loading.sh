#!/usr/bin/env bash
# What loading, memory and start-up cost, for this checkout and (given
# commits) for each commit built beside it, one row each (docs/figures.md):
#
#   * peak memory (GNU time's maximum resident set, the median of three
#     runs), one frame of Tux and of a generated torus of 4M triangles
#     (`rastty render --cols 200 --rows 60 --color truecolor`), and per
#     triangle; in brackets beside Tux's, the process's floor: `rastty
#     --version`, which loads no model (the binary's and the C libraries'
#     pages it touches);
#   * normals at load: callgrind's inclusive count of
#     `Geometry::compute_normals` (normals, welding, closedness) on the
#     torus of 1M triangles, per triangle, and in brackets that of the
#     normals alone (`normals::smooth_normals`: face normals and angles,
#     sums, means and the crease test, without the connectivity);
#   * OBJ parsing: everything `obj::load` does but `Reader::finish` (which
#     computes the normals), inclusive counts on the same file, per byte;
#   * a steady Tux frame at 200×60 half blocks, render only
#     (examples/profile_scene, (40 frames − 10) / 30);
#   * whole-process instructions of `render cube` and of the teapot;
#   * the release binary's size, and stripped of symbols and line tables;
#   * under the table, for this checkout: what loading the same torus
#     costs where the file has normals (a `vn` for each position): the
#     inclusive count of `Geometry::analyze` a triangle, the welding,
#     corner lists and closedness that every mesh pays, with normals or
#     without; and how many of the functions the common commands run
#     cli/hot-functions.ld lays out first (scripts/hot-functions.sh --check).
#
#   scripts/memory-and-loading.sh [COMMIT...]     (needs valgrind, GNU time)
set -euo pipefail
cd "$(dirname "$0")/.."
tux=tests/models/linux-mascot-tux.obj
m1=target/load-cost/torus-1000000.obj
m4=target/load-cost/torus-4000000.obj
cargo build --release -q
cargo build --release -q --example torus_obj --example profile_scene
mkdir -p target/load-cost
for n in 1000000 4000000; do
  [ -s "target/load-cost/torus-$n.obj" ] || target/release/examples/torus_obj "$n" > "target/load-cost/torus-$n.obj"
done
# The binaries of a commit, built in a worktree with a target of its own.
build() {
  local rev=$1 dir=target/rev/$1
  git worktree prune
  [ -d "$dir" ] || git worktree add -q --detach "$dir" "$rev"
  # Not one target shared by the commits: cargo would find a commit built
  # before up to date and leave the binary of the last one built in place.
  CARGO_TARGET_DIR=$dir/target cargo build --release -q --locked --manifest-path "$dir/Cargo.toml" -p rastty-cli >&2
  CARGO_TARGET_DIR=$dir/target cargo build --release -q --locked --manifest-path "$dir/Cargo.toml" -p rastty --example profile_scene >&2
  echo "$dir/target/release"
}
count() { valgrind --tool=callgrind --callgrind-out-file=/dev/null "$@" 2>&1 >/dev/null | sed -n 's/.*Collected : //p'; }
# Peak memory, the median of three runs.
peak() {
  for _ in 1 2 3; do
    /usr/bin/time -o target/load-cost/time -f '%M' "$@" >/dev/null 2>&1
    cat target/load-cost/time
  done | sort -n | sed -n 2p
}
# Inclusive instructions of the function whose name ends in $1, in the
# callgrind run of `profile` (target/load-cost/cg.out). callgrind_annotate
# lists a function once for each source file its inlined code comes from
# (with or without the binary's name after it): the largest of these
# entries is the whole function with its callees; the others are parts of
# it.
profile() { valgrind --tool=callgrind --callgrind-out-file=target/load-cost/cg.out "$@" >/dev/null 2>&1; }
inclusive() {
  callgrind_annotate --inclusive=yes --threshold=100 target/load-cost/cg.out 2>/dev/null |
    grep -E "$1( \[[^]]*\])?\$" | grep -v '=>' | sed 's/ *(.*//; s/,//g' | sort -n | tail -1
}
row() { # label, directory of binaries
  local bin=$2/rastty frame tris1 bytes1 normals smooth load finish a b
  local args=(--cols 200 --rows 60 --color truecolor)
  tris1=1000000
  bytes1=$(stat -c %s "$m1")
  profile "$bin" render "$m1" "${args[@]}"
  normals=$(inclusive 'Geometry::compute_normals')
  # (Not in builds from before the function had its name.)
  smooth=$(inclusive 'normals::smooth_normals' || true)
  load=$(inclusive 'scene::obj::load')
  finish=$(inclusive 'obj::Reader::finish')
  a=$(count "$2/examples/profile_scene" ../shared/models/linux-mascot-tux.obj 10)
  b=$(count "$2/examples/profile_scene" ../shared/models/linux-mascot-tux.obj 40)
  frame=$(( (b - a) / 30 ))
  local tux_kb m4_kb ver_kb
  tux_kb=$(peak "$bin" render "$tux" "${args[@]}")
  ver_kb=$(peak "$bin" --version)
  m4_kb=$(peak "$bin" render "$m4" "${args[@]}")
  strip -o target/load-cost/stripped "$bin"
  printf '| %s | %.1f MiB (%.1f) | %.1f MiB (%d B) | %d (%s) | %.1f | %.2fM | %.2fM | %.2fM | %.1f MB / %.1f MB |\n' "$1" \
    "$(echo "$tux_kb / 1024" | bc -l)" "$(echo "$ver_kb / 1024" | bc -l)" "$(echo "$m4_kb / 1024" | bc -l)" $(( m4_kb * 1024 / 4000000 )) \
    $(( normals / tris1 )) "$([ -n "$smooth" ] && echo $(( smooth / tris1 )) || echo –)" "$(echo "($load - $finish) / $bytes1" | bc -l)" \
    "$(echo "$frame / 1000000" | bc -l)" \
    "$(echo "$(count "$bin" render cube) / 1000000" | bc -l)" \
    "$(echo "$(count "$bin" render tests/models/teapot.obj "${args[@]}") / 1000000" | bc -l)" \
    "$(echo "$(stat -c %s "$bin") / 1000000" | bc -l)" "$(echo "$(stat -c %s target/load-cost/stripped) / 1000000" | bc -l)"
}
printf '| build | peak memory, Tux (`rastty --version`) | peak memory, torus 4M (a triangle) | normals at load, a triangle (the normals alone) | OBJ parsing, a byte | steady Tux frame | `render cube` | teapot, one frame | binary / stripped |\n'
printf '|---|---:|---:|---:|---:|---:|---:|---:|---:|\n'
for rev in "$@"; do
  row "$rev" "$(build "$rev")"
done
row "$(git rev-parse --short HEAD)" target/release
# The torus with normals in the file: each `v` followed by a `vn`, each
# corner `v//v`.
mn=target/load-cost/torus-1000000-vn.obj
[ -s "$mn" ] || awk '/^v /{print; print "vn 0 0 1"; next}
  /^f /{printf "f"; for (i = 2; i <= NF; i++) printf " %s//%s", $i, $i; print ""; next}
  {print}' "$m1" > "$mn"
profile target/release/rastty render "$mn" --cols 200 --rows 60 --color truecolor
echo "with normals in the file, the torus's connectivity (\`Geometry::analyze\`): $(( $(inclusive 'Geometry::analyze') / 1000000 )) a triangle"
# How current cli/hot-functions.ld is (what its layout buys: cli/build.rs).
scripts/hot-functions.sh --check
