#!/usr/bin/env bash
# A PBR test model with a blended (alphaMode BLEND) coating, normal and
# metallic-roughness maps, made by others: ClearCoatTest.gltf (Khronos
# glTF-Sample-Models, © 2020 Analytical Graphics, Inc., CC-BY 4.0, by Ed
# Mackey), as Debian's package assimp-testmodels ships it. Renders
# docs/materials/clearcoat.png from it; the model is kept under
# target/models/ClearCoat-glTF/.
#
#   scripts/clearcoat.sh           (needs apt-get download, or the package)
set -euo pipefail
cd "$(dirname "$0")/.."
dir=target/models/ClearCoat-glTF
if [ ! -s "$dir/ClearCoatTest.gltf" ]; then
  mkdir -p target/models
  src=/usr/share/assimp/models/glTF2/ClearCoat-glTF
  if [ ! -d "$src" ]; then
    work=$(mktemp -d)
    trap 'rm -rf "$work"' EXIT
    (cd "$work" && apt-get download -q assimp-testmodels >/dev/null && dpkg -x assimp-testmodels_*.deb root)
    src=$work/root$src
  fi
  cp -r "$src" "$dir"
fi
cargo build --release -q
mkdir -p docs/materials
target/release/rastty render "$dir/ClearCoatTest.gltf" --cols 200 --rows 80 --glyphs octant \
  --output docs/materials/clearcoat.png
echo docs/materials/clearcoat.png
