#!/usr/bin/env bash
# docs/khronos/*.png: Khronos sample models this repository's glTF work
# changed, each drawn by two builds at 100×32 cells (truecolor half
# blocks) beside the sample's own reference screenshot.
#
#   scripts/khronos-pictures.sh SAMPLES BEFORE AFTER
#
# SAMPLES, BEFORE and AFTER as for scripts/khronos.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
samples=$1 before=$2 after=$3
out=docs/khronos
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# MODEL, or MODEL/VARIANT for another variant than glTF (its picture named
# MODEL-VARIANT).
for entry in DamagedHelmet MetalRoughSpheresNoTextures EnvironmentTest NegativeScaleTest TextureSettingsTest SimpleInstancing MeshPrimitiveModes SimpleSparseAccessor GlassVaseFlowers \
  ClearCoatCarPaint SheenChair GlamVelvetSofa SpecGlossVsMetalRough MultiUVTest SpecularTest BrainStem/glTF-Draco; do
  model=${entry%%/*} variant=glTF name=$entry
  if [[ $entry == */* ]]; then variant=${entry#*/} name=$model-$variant; fi
  dir=$samples/Models/$model
  file=$(find "$dir/$variant" -maxdepth 1 \( -name '*.gltf' -o -name '*.glb' \) | head -1)
  [ -n "$file" ] || continue
  for build in before after; do
    bin=${!build}
    # A build that refuses the model draws nothing: a blank frame.
    if ! "$bin" render "$file" --cols 100 --rows 32 --color truecolor --output "$work/$build.png" 2>/dev/null; then
      convert -size 800x512 xc:black "$work/$build.png"
    fi
  done
  ref=$(find "$dir/screenshot" -maxdepth 1 -name 'screenshot.*' | head -1)
  convert "$ref" -resize x512 "$work/reference.png"
  convert "$work/before.png" "$work/after.png" "$work/reference.png" -background '#202020' -splice 8x0 +append -strip "$out/$name.png"
done
echo "wrote $out"
