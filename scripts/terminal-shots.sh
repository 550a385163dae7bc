#!/usr/bin/env bash
# docs/pixels/*.png: rastty in real terminals, headless. kitty 0.26 draws
# the kitty graphics protocol (with Mesa's software OpenGL) and xterm as a
# VT340 draws sixel, each under Xvfb; ImageMagick's `import` takes the
# window. The same models in character cells beside them.
#
#   scripts/terminal-shots.sh    (needs xvfb, kitty, xterm, imagemagick,
#                                 libgl1-mesa-dri; Debian's packages)
#
# Under Xvfb kitty 0.26 does not repaint what changes beside a picture
# while one is shown (a script that only prints text next to a still
# image shows the same), so the spinning shots give the scene a
# background of its own, and no status line.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q --locked -p rastty-cli
rastty=$PWD/target/release/rastty
out=docs/pixels
mkdir -p "$out"
display=:97
Xvfb "$display" -screen 0 1000x640x24 >/dev/null 2>&1 &
xvfb=$!
trap 'kill $xvfb 2>/dev/null' EXIT
sleep 1
export DISPLAY=$display
# shot NAME SECONDS TERMINAL… -- COMMAND: runs COMMAND in the terminal and
# takes the screen SECONDS later.
shot() {
  local name=$1 after=$2; shift 2
  "$@" >/dev/null 2>&1 &
  local pid=$!
  sleep "$after"
  import -window root "$out/$name.png"
  kill "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
}
kitty=(kitty --config NONE -o font_size=11 -o remember_window_size=no -o initial_window_width=1000 -o initial_window_height=640)
xterm=(xterm -ti vt340 -geometry 110x34 -fa Monospace -fs 10)
fox=../shared/models/fox.obj
tux=tests/models/linux-mascot-tux.obj
crate=examples/models/crate.glb
shot kitty-render 4 "${kitty[@]}" sh -c "$rastty render $fox --cols 50 --rows 14 --yaw 30; $rastty render $crate --cols 50 --rows 14 --yaw 30; sleep 9"
shot kitty-render-cells 4 "${kitty[@]}" sh -c "$rastty render $fox --cols 50 --rows 14 --yaw 30 --graphics cells --color truecolor; $rastty render $crate --cols 50 --rows 14 --yaw 30 --graphics cells --color truecolor; sleep 9"
shot kitty-spin 4 "${kitty[@]}" sh -c "$rastty spin $tux --background '#1e2a38' --frames 200"
shot kitty-spin-cells 4 "${kitty[@]}" sh -c "$rastty spin $tux --background '#1e2a38' --graphics cells --frames 200"
shot xterm-sixel-spin 4 "${xterm[@]}" -e sh -c "$rastty spin $fox --hud --frames 200"
shot xterm-sixel-render 4 "${xterm[@]}" -e sh -c "$rastty render $crate --cols 60 --rows 18 --graphics sixel --yaw 30; sleep 9"
shot xterm-cells-spin 4 "${xterm[@]}" -e sh -c "$rastty spin $fox --hud --graphics cells --frames 200"
echo "wrote $out"
