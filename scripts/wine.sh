#!/usr/bin/env bash
# The Windows program, built with mingw-w64 and run under wine: every frame
# it prints and every file it writes is the Linux build's, byte for byte.
#
#   scripts/wine.sh          (needs gcc-mingw-w64-x86-64 and wine64: .ci/run
#                             installs them; the rustup target is added here)
#
# wine 8 lacks bcryptprimitives.dll, which Rust's standard library asks for
# (ProcessPrng): scripts/wine/bcryptprimitives.c is a stand-in over
# RtlGenRandom, built beside the program. wine's console draws VT colour
# sequences garbled, so the interactive loop's picture is not compared here:
# what is run is what prints to a pipe or a file, and a refused device name.
set -euo pipefail
cd "$(dirname "$0")/.."
export CARGO_TERM_COLOR=never WINEDEBUG=-all
target=x86_64-pc-windows-gnu
rustup target add "$target" >/dev/null
export CARGO_TARGET_X86_64_PC_WINDOWS_GNU_LINKER=x86_64-w64-mingw32-gcc
cargo build -q --release --locked -p rastty-cli
cargo build -q --release --locked -p rastty-cli --target "$target"
dir=target/$target/release
x86_64-w64-mingw32-gcc -O2 -shared -o "$dir/bcryptprimitives.dll" scripts/wine/bcryptprimitives.c -ladvapi32
wine=$(command -v wine64 || echo /usr/lib/wine/wine64)
win() { "$wine" "$dir/rastty.exe" "$@"; }
lin() { target/release/rastty "$@"; }
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
win --version >/dev/null 2>&1 || true # wine makes its prefix on the first run

failed=0
same() { # same NAME: compares $scratch/win and $scratch/lin
    if cmp -s "$scratch/win" "$scratch/lin"; then
        echo "same: $1"
    else
        echo "DIFFERENT: $1" >&2
        failed=1
    fi
}

models=(torus cube sphere examples/models/crate.glb examples/models/arm.glb tests/models/bunny.obj tests/models/teapot.obj tests/models/fox.obj)
shared=../shared/models
for m in linux-mascot-tux.obj shiba-inu-binary.stl shiba-inu-ascii.stl animated/RiggedSimple.gltf; do
    [ -f "$shared/$m" ] && models+=("$shared/$m")
done
for m in "${models[@]}"; do
    for look in "--glyphs half --color truecolor" "--glyphs octant --color 256 --shading flat" "--glyphs braille --color 16 --aa 4x"; do
        # shellcheck disable=SC2086
        win render "$m" --cols 96 --rows 30 $look >"$scratch/win"
        # shellcheck disable=SC2086
        lin render "$m" --cols 96 --rows 30 $look >"$scratch/lin"
        same "render $m $look"
    done
done
win spin torus --frames 12 --cols 60 --rows 20 --color 256 >"$scratch/win"
lin spin torus --frames 12 --cols 60 --rows 20 --color 256 >"$scratch/lin"
same "spin torus --frames 12 to a pipe"
for out in fox.png fox.svg; do
    win render tests/models/fox.obj --output "$scratch/w-$out" --cols 40 --rows 12
    lin render tests/models/fox.obj --output "$scratch/l-$out" --cols 40 --rows 12
    cp "$scratch/w-$out" "$scratch/win"
    cp "$scratch/l-$out" "$scratch/lin"
    same "render --output $out"
done
SOURCE_DATE_EPOCH=1700000000 win spin torus --frames 3 --cols 30 --rows 8 --record "$scratch/win" >/dev/null
SOURCE_DATE_EPOCH=1700000000 lin spin torus --frames 3 --cols 30 --rows 8 --record "$scratch/lin" >/dev/null
# The header names the shell and TERM, which differ: the frames must not.
tail -n +2 "$scratch/win" >"$scratch/w" && mv "$scratch/w" "$scratch/win"
tail -n +2 "$scratch/lin" >"$scratch/l" && mv "$scratch/l" "$scratch/lin"
same "spin --record (the events)"
# A Windows device name is not a file.
if err=$(win render nul.obj 2>&1); then
    echo "nul.obj was read" >&2
    failed=1
elif [ "$err" != "error: nul.obj: is NUL, a device name on Windows, not a file" ]; then
    echo "nul.obj: $err" >&2
    failed=1
else
    echo "refused: nul.obj"
fi
win render torus --cols 10 --rows 3 --record NUL >/dev/null && echo "written through: --record NUL"
exit $failed
