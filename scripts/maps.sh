#!/usr/bin/env bash
# PBR models with normal, metallic-roughness, occlusion and emissive maps
# (and no tangents: MikkTSpace's are made), made by others: two controllers
# of the WebXR input profiles (npm package @webxr-input-profiles/assets
# 1.0.20, MIT licence, © 2019 Amazon; the models' trademarks are their
# makers'). Renders docs/materials/<model>.png of each; the
# package is kept under target/models/webxr-assets/.
#
#   scripts/maps.sh                (needs npm, or the package unpacked there)
set -euo pipefail
cd "$(dirname "$0")/.."
dir=target/models/webxr-assets
if [ ! -d "$dir/package/dist/profiles" ]; then
  mkdir -p "$dir"
  (cd "$dir" && npm pack -q @webxr-input-profiles/assets@1.0.20 >/dev/null && tar xzf webxr-input-profiles-assets-1.0.20.tgz)
fi
cargo build --release -q
mkdir -p docs/materials
p=$dir/package/dist/profiles
for m in generic-trigger-squeeze-thumbstick microsoft-mixed-reality; do
  target/release/rastty render "$p/$m/left.glb" --cols 100 --rows 40 \
    --glyphs octant --background '#8a8f99' --output "docs/materials/$m.png"
  echo "docs/materials/$m.png"
done
