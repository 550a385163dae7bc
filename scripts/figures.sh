#!/usr/bin/env bash
# docs/figures.md, regenerated: every performance figure the documentation
# quotes, measured here and written verbatim with the commit it measured.
# The one way rastty is measured: instructions by callgrind (they repeat
# exactly on the same binary, where this machine's clock wanders by
# ±20 %), peak memory by GNU time, and the clock only where it is the
# point (bands on several cores). The programs it runs that are not the
# `rastty` binary are the `rastty-measure` crate's (measure/).
#
#   scripts/figures.sh                               (needs valgrind, GNU time)
#   PEER=/tmp/3d-ascii-viewer scripts/figures.sh     (also against that peer)
#
# PEER names a checkout of github.com/autopawn/3d-ascii-viewer, built
# here with gcc -O2 (needs ncurses' headers). Takes about half an hour
# (the 4M-triangle loads under callgrind).
set -euo pipefail
cd "$(dirname "$0")/.."
out=docs/figures.md
work=target/figures
mkdir -p "$work"
cargo build --release -q --locked -p rastty-cli
cargo build --release -q --locked -p rastty-measure
bin=target/release
rastty=$bin/rastty
tux=tests/models/linux-mascot-tux.obj

# The one callgrind helper: instructions of a whole process.
count() { valgrind --tool=callgrind --callgrind-out-file=/dev/null "$@" 2>&1 >/dev/null | sed -n 's/.*Collected : //p'; }
# Instructions a frame: the command given a frame count last, (40 frames −
# 10) / 30, which leaves out loading and the first (full) frame.
per_frame() { local a b; a=$(count "$@" 10); b=$(count "$@" 40); echo $(( (b - a) / 30 )); }
# Peak memory in KiB, the median of three runs.
peak() {
  for _ in 1 2 3; do
    /usr/bin/time -o "$work/time" -f '%M' "$@" >/dev/null 2>&1
    cat "$work/time"
  done | sort -n | sed -n 2p
}
# Inclusive instructions of the function whose name ends in $1, in the
# callgrind run `profile` made: callgrind_annotate lists a function once
# for each source file its inlined code comes from; the largest is the
# whole function with its callees.
profile() { valgrind --tool=callgrind --callgrind-out-file="$work/cg.out" "$@" >/dev/null 2>&1; }
inclusive() {
  callgrind_annotate --inclusive=yes --threshold=100 "$work/cg.out" 2>/dev/null |
    grep -E "$1( \[[^]]*\])?\$" | grep -v '=>' | sed 's/ *(.*//; s/,//g' | sort -n | tail -1
}
mib() { echo "scale=1; $1 / 1024" | bc; }
millions() { echo "scale=2; $1 / 1000000" | bc; }
torus() { # the generated torus of $1 triangles
  local f=$work/torus-$1.obj
  [ -s "$f" ] || "$bin/torus_obj" "$1" >"$f"
  echo "$f"
}
triangles() { awk '/^f /{t += NF - 3} END {print t}' "$1"; }

frame_cost() {
  local big bands
  echo "Tux 200×60, render only: $(per_frame "$bin/profile_scene" "$tux") instructions a frame"
  echo "Tux 200×60, spin (render + blit + encode): $(per_frame "$rastty" spin "$tux" --cols 200 --rows 60 --glyphs half --color truecolor --frames) instructions a frame"
  big=$(per_frame "$rastty" spin --cols 1000 --rows 300 --glyphs half --color truecolor --threads 1 --frames)
  echo "torus 1000×300, spin (render + blit + encode), one thread: $big instructions a frame, $(( big / 300000 )) a cell"
  bands=$(per_frame "$rastty" spin --cols 1000 --rows 300 --glyphs half --color truecolor --threads auto --frames)
  echo "torus 1000×300, spin, in bands (every thread's instructions): $bands a frame, $(( bands / 300000 )) a cell"
}

planner() {
  echo "| scene | planned (instructions/frame) | full (instructions/frame) | full / planned |"
  echo "|---|---:|---:|---:|"
  while IFS='|' read -r name scene flags; do
    local p f
    # shellcheck disable=SC2086 # flags are words
    p=$(per_frame_scene "$scene" "" $flags)
    # shellcheck disable=SC2086
    f=$(per_frame_scene "$scene" full $flags)
    printf '| %s | %s | %s | %s |\n' "$name" "$p" "$f" "$(awk "BEGIN { printf \"%.2f\", $f / $p }")"
  done <<'SCENES'
2D flat tiles|examples/scenes/tiles.toml|
flat-shaded convex sphere|sphere|flat
smooth-lit bunny|tests/models/bunny.obj|
overlapping meshes|examples/scenes/overlap.toml|
SCENES
}
# profile_scene SCENE FRAMES [full] [flat], per frame.
per_frame_scene() {
  local scene=$1 full=$2 a b
  shift 2
  # shellcheck disable=SC2086 # an empty $full is no word
  a=$(count "$bin/profile_scene" "$scene" 10 $full "$@")
  # shellcheck disable=SC2086
  b=$(count "$bin/profile_scene" "$scene" 40 $full "$@")
  echo $(( (b - a) / 30 ))
}

posing() {
  local s h p humanoid v
  s=$(per_frame "$bin/pose_cost" static); h=$(per_frame "$bin/pose_cost" held); p=$(per_frame "$bin/pose_cost" playing)
  echo "| tube, 12,800 vertices | instructions a frame |"
  echo "|---|---:|"
  echo "| no rig | $s |"
  echo "| skinned, clip held (posed once) | $h |"
  echo "| skinned, clip playing (posed every frame) | $p |"
  echo "| posing, a vertex: (playing − held) / 12,800 | $(( (p - h) / 12800 )) |"
  if humanoid=$(scripts/humanoid.sh 2>/dev/null); then
    v=$("$rastty" render "$humanoid" --cols 200 --rows 60 --time 1 --explain 2>&1 | sed -n 's/^ *\([0-9]*\) vertices posed$/\1/p')
    h=$(per_frame "$rastty" spin "$humanoid" --cols 200 --rows 60 --glyphs half --color truecolor --speed 0 --frames)
    p=$(per_frame "$rastty" spin "$humanoid" --cols 200 --rows 60 --glyphs half --color truecolor --speed 1 --frames)
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
}

against_euc() {
  for who in rastty euc; do
    echo "$who: $(per_frame "$bin/vs_euc" "$who") instructions a frame"
  done
}

loading() {
  local args=(--cols 200 --rows 60 --color truecolor) model tris size instr kb secs
  printf '| model | triangles | file | instructions | per triangle | peak memory | per triangle | time |\n'
  printf '|---|---:|---:|---:|---:|---:|---:|---:|\n'
  for model in "$tux" tests/models/bunny.obj "$(torus 10000)" "$(torus 100000)" "$(torus 1000000)" "$(torus 4000000)"; do
    tris=$(triangles "$model")
    size=$(stat -c %s "$model")
    instr=$(count "$rastty" render "$model" "${args[@]}")
    read -r kb secs < <( { /usr/bin/time -f '%M %e' "$rastty" render "$model" "${args[@]}" >/dev/null; } 2>&1 | tail -1)
    printf '| %s | %d | %.1f MiB | %.1fM | %d | %.1f MiB | %d B | %s s |\n' \
      "$(basename "$model")" "$tris" "$(echo "$size / 1048576" | bc -l)" \
      "$(echo "$instr / 1000000" | bc -l)" $(( instr / tris )) \
      "$(echo "$kb / 1024" | bc -l)" $(( kb * 1024 / tris )) "$secs"
  done
}

memory() {
  local args=(--cols 200 --rows 60 --color truecolor) m1 m4 mn normals smooth load finish
  m1=$(torus 1000000); m4=$(torus 4000000)
  echo "| what | figure |"
  echo "|---|---:|"
  echo "| peak memory, one frame of Tux | $(mib "$(peak "$rastty" render "$tux" "${args[@]}")") MiB |"
  echo "| peak memory, \`rastty --version\` (the process's floor) | $(mib "$(peak "$rastty" --version)") MiB |"
  local kb4; kb4=$(peak "$rastty" render "$m4" "${args[@]}")
  echo "| peak memory, one frame of the 4M-triangle torus | $(mib "$kb4") MiB ($(( kb4 * 1024 / 4000000 )) B a triangle) |"
  profile "$rastty" render "$m1" "${args[@]}"
  normals=$(inclusive 'Geometry::compute_normals')
  smooth=$(inclusive 'normals::smooth_normals')
  load=$(inclusive 'scene::obj::load_in')
  finish=$(inclusive 'obj::Reader::finish')
  echo "| normals at load, 1M-triangle torus: welding, closedness and normals, a triangle | $(( normals / 1000000 )) instructions |"
  echo "| the normals alone (\`normals::smooth_normals\`), a triangle | $(( smooth / 1000000 )) instructions |"
  echo "| OBJ parsing (\`obj::load_in\` less its normals), a byte | $(echo "scale=1; ($load - $finish) / $(stat -c %s "$m1")" | bc) instructions |"
  # The torus with normals in the file: each `v` followed by a `vn`.
  mn=$work/torus-1000000-vn.obj
  [ -s "$mn" ] || awk '/^v /{print; print "vn 0 0 1"; next}
    /^f /{printf "f"; for (i = 2; i <= NF; i++) printf " %s//%s", $i, $i; print ""; next}
    {print}' "$m1" >"$mn"
  profile "$rastty" render "$mn" "${args[@]}"
  echo "| with normals in the file, the connectivity alone (\`Geometry::analyze\`), a triangle | $(( $(inclusive 'Geometry::analyze') / 1000000 )) instructions |"
  echo "| whole process, \`rastty render cube\` | $(millions "$(count "$rastty" render cube)")M instructions |"
  echo "| whole process, teapot, one frame | $(millions "$(count "$rastty" render tests/models/teapot.obj "${args[@]}")")M instructions |"
  strip -o "$work/stripped" "$rastty"
  echo "| the binary, with line tables / stripped | $(millions "$(stat -c %s "$rastty")") MB / $(millions "$(stat -c %s "$work/stripped")") MB |"
}

against_peer() {
  local peer=$work/3d-ascii-viewer-O2 model tris a b ours theirs
  gcc -O2 -o "$peer" "$PEER"/src/*.c -lm -lncurses
  export TERM=xterm
  printf '| model | triangles | rastty instructions | peer instructions | ratio | rastty peak memory | peer peak memory |\n'
  printf '|---|---:|---:|---:|---:|---:|---:|\n'
  for model in "$tux" tests/models/teapot.obj tests/models/bunny.obj "$(torus 1000000)" "$(torus 4000000)"; do
    tris=$(triangles "$model")
    ours=("$rastty" render "$model" --cols 200 --rows 60 --glyphs ascii --color none)
    theirs=("$peer" --snap 0 0 -w 200 -h 60 "$model")
    a=$(count "${ours[@]}")
    b=$(count "${theirs[@]}")
    printf '| %s | %d | %.1fM | %.1fM | %.2f× | %s MiB | %s MiB |\n' "$(basename "$model")" "$tris" \
      "$(echo "$a / 1000000" | bc -l)" "$(echo "$b / 1000000" | bc -l)" "$(echo "$a / $b" | bc -l)" \
      "$(mib "$(peak "${ours[@]}")")" "$(mib "$(peak "${theirs[@]}")")"
  done
}

# The same code with every `#[inline(always)]` made a plain `#[inline]`,
# built beside this one: what forcing the inlining buys, where it stands.
inlining() {
  local copy=$work/inline-copy plain sites
  rm -rf "$copy"; mkdir -p "$copy"
  git ls-files -z | xargs -0 cp --parents -t "$copy"
  sites=$(grep -rc '#\[inline(always)\]' src | awk -F: '{n += $2} END {print n}')
  grep -rl '#\[inline(always)\]' "$copy/src" | xargs sed -i 's/#\[inline(always)\]/#[inline]/'
  CARGO_TARGET_DIR=$work/inline-target cargo build --release -q --locked \
    --manifest-path "$copy/Cargo.toml" -p rastty-cli -p rastty-measure
  plain=$work/inline-target/release
  local m1; m1=$(torus 1000000)
  echo "| instructions | \`#[inline(always)]\` as it stands ($sites sites) | \`#[inline]\` throughout |"
  echo "|---|---:|---:|"
  echo "| Tux 200×60, render only, a frame | $(per_frame "$bin/profile_scene" "$tux") | $(per_frame "$plain/profile_scene" "$tux") |"
  echo "| Tux, one frame, whole process (loading) | $(millions "$(count "$rastty" render "$tux" --cols 200 --rows 60)")M | $(millions "$(count "$plain/rastty" render "$tux" --cols 200 --rows 60)")M |"
  echo "| 1M-triangle torus, one frame, whole process (loading) | $(millions "$(count "$rastty" render "$m1" --cols 200 --rows 60)")M | $(millions "$(count "$plain/rastty" render "$m1" --cols 200 --rows 60)")M |"
}

# Bytes a frame: the command given a frame count last, (40 frames − 10) / 30.
bytes_a_frame() { local a b; a=$("$@" 10 | wc -c); b=$("$@" 40 | wc -c); echo $(( (b - a) / 30 )); }

# Pixels: the same scenes at 960×540 pixels in each protocol (120×31 cells
# of 8×18 pixels, the last row the status line's), against cells at 200×60;
# then sixel from one PNG, rastty's encoder against chafa's.
pixels() {
  local px=(--cols 120 --rows 31 --cell-size 8x18) cells=(--cols 200 --rows 60 --glyphs half --color truecolor)
  local scene p png=$work/tux-960x540.png
  echo "| scene | output | instructions a frame | bytes a frame | bytes a second at 30 fps |"
  echo "|---|---|---:|---:|---:|"
  local b
  for scene in tux torus; do
    # The torus is the built-in scene: no model named.
    local spin=("$rastty" spin)
    [ "$scene" = tux ] && spin+=("$tux")
    b=$(bytes_a_frame "${spin[@]}" "${cells[@]}" --frames)
    echo "| $scene | cells, 200×60 half blocks | $(per_frame "${spin[@]}" "${cells[@]}" --frames) | $b | $((b * 30)) |"
    for p in kitty sixel iterm; do
      b=$(bytes_a_frame "${spin[@]}" "${px[@]}" --graphics "$p" --frames)
      echo "| $scene | $p, 960×540 pixels | $(per_frame "${spin[@]}" "${px[@]}" --graphics "$p" --frames) | $b | $((b * 30)) |"
    done
  done
  "$rastty" render "$tux" --cols 120 --rows 30 --cell-size 8x18 --graphics sixel --output "$png"
  echo
  echo "| sixel of one 960×540 PNG of Tux, whole process | instructions | bytes |"
  echo "|---|---:|---:|"
  echo "| rastty (\`sixel_png\`, 256 registers) | $(millions "$(count "$bin/sixel_png" "$png")")M | $("$bin/sixel_png" "$png" | wc -c) |"
  if command -v chafa >/dev/null; then
    # chafa sized to the same 960×540 pixels (its cells are 8×8 here).
    local chafa=(chafa -f sixels --animate off --polite on --size 120x68 --stretch "$png")
    echo "| chafa $(chafa --version | sed -n 's/^Chafa version //p;q') (\`${chafa[*]}\`) | $(millions "$(count "${chafa[@]}")")M | $("${chafa[@]}" | wc -c) |"
  fi
  if command -v kitty >/dev/null && command -v Xvfb >/dev/null; then
    echo
    echo "| Tux, 300 frames at 30 fps in kitty $(kitty --version | cut -d' ' -f2) under Xvfb (1000×640) | CPU of rastty (user + system over the run) | what spin said |"
    echo "|---|---:|---|"
    Xvfb :96 -screen 0 1000x640x24 >/dev/null 2>&1 &
    local xvfb=$! g
    sleep 1
    for g in cells kitty; do
      DISPLAY=:96 timeout 60 kitty --config NONE -o font_size=11 -o remember_window_size=no \
        -o initial_window_width=1000 -o initial_window_height=640 \
        sh -c "/usr/bin/time -o $work/cpu-$g -f '%U %S %e' $rastty spin $tux --fps 30 --frames 300 --graphics $g 2>$work/said-$g" >/dev/null 2>&1 || true
      echo "| --graphics $g | $(awk '{printf "%.0f %%", 100 * ($1 + $2) / $3}' "$work/cpu-$g") | $(sed -n 's/^note: //p' "$work/said-$g" | paste -sd';' -) |"
    done
    kill $xvfb
  fi
}

section() { # title, what it shows, function
  printf '\n## %s\n\n%s\n\n```\n' "$1" "$2"
  "$3"
  printf '```\n'
}
commit=$(git rev-parse --short HEAD)
dirty=$(git status --porcelain --untracked-files=no | grep -q . && echo " (with uncommitted changes)" || true)
{
  cat <<HEAD
# Figures

Every performance figure of rastty in one place, written by
\`scripts/figures.sh\` (do not edit by hand: run it) on this repository at
commit $commit$dirty, on $(nproc) cores of $(sed -n 's/^model name\s*: //p' /proc/cpuinfo | head -1).
Instruction counts come from callgrind and repeat exactly on the same
binary; times wander by ±20 % on this machine and are given only where
the clock is the point. The documentation keeps the reasons and the
invariants; the numbers live here. \`rastty bench\`'s accuracy and time
of every knob is [its own page](bench.md) (\`cargo run --release -- bench
--svg docs/bench.svg > docs/bench.md\`).
HEAD
  section "Frame cost" "Instructions a frame, (40 frames − 10) / 30: Tux at 200×60 cells in half blocks, render alone (\`measure/src/bin/profile_scene.rs\`) and through \`spin\` (render, blit, encode), and the torus at 1000×300 cells on one thread and in bands." frame_cost
  section "Bands" "Milliseconds a frame by the clock (noisy: ±20 %, and the ratio as much from run to run), render only, half blocks, truecolor, one band against two drawn in turn ten frames each (docs/planner.md; \`measure/src/bin/bands.rs\`)." "$bin/bands"
  section "Posing" "Instructions a frame of a skinned tube of 12,800 vertices at 200×60 half blocks: without a rig, its clip held, its clip playing (\`measure/src/bin/pose_cost.rs\`); the same for a skinned human figure of 54 joints through \`spin\` (\`scripts/humanoid.sh\` makes it); and the posing's cost a vertex (docs/scenes.md)." posing
  section "What the planner saves" "Instructions a frame, planned and full pipeline, for the planner's four scenes (docs/planner.md)." planner
  section "Against euc" "Instructions a frame, rastty against the euc crate drawing the bunny at 200×120 samples (docs/accuracy.md; \`measure/src/bin/vs_euc.rs\`)." against_euc
  section "Bytes a frame" "The diffing encoder's bytes a frame, a square turning a full circle in 60 frames at 80×24 cells in every glyph mode, truecolor, against ratatui's \`Canvas\` (docs/usage.md; \`measure/src/bin/bytes_per_frame.rs\`)." "$bin/bytes_per_frame"
  section "Loading" "Whole process, one frame: instructions, peak memory and (noisy) wall time, Tux, the bunny and generated tori of 10k to 4M triangles (docs/scenes.md)." loading
  section "Memory and start-up" "Peak memory (the median of three runs), what loading costs a triangle and a byte (callgrind's inclusive counts, on the 1M-triangle torus), whole-process counts of two small commands, and the binary's size." memory
  section "Pixels" "Instructions and bytes a frame, (40 frames − 10) / 30, of Tux and the torus through \`spin\` at 960×540 pixels in each protocol (\`--graphics\`), against character cells at 200×60; sixel from one PNG, rastty's encoder against chafa's, whole process (docs/usage.md's Pixels); and the CPU \`spin\` takes at 30 frames a second in a real kitty, headless (where kitty's software OpenGL drains less than the frames need, \`spin\` steps down, and the last column says so)." pixels
  section "Inlining" "What \`#[inline(always)]\` buys where it stands (the rasterizer, fill, vertex, shading and encoding stages and the OBJ reader and its normals): the same code built with a plain \`#[inline]\` in its place, instructions through the same commands. Where forcing did not pay (the camera, the mesh's accessors, clipping's setup, statistics, palettes, the line encoder) it is a plain \`#[inline]\`." inlining
  if [ -n "${PEER:-}" ]; then
    section "Against 3d-ascii-viewer" "One run of both: one frame, whole process, 200×60 cells of ASCII without colour, instructions and peak memory; the peer built with -O2 (docs/scenes.md)." against_peer
  fi
} >"$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"
