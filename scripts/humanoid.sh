#!/usr/bin/env bash
# A skinned human figure for docs/moving/ and scripts/pose-cost.sh, made by
# others: BCN_Epileptic.X from assimp's test models (Debian's package
# assimp-testmodels, BSD-3-clause as Debian's copyright file says; three
# meshes, one skin of 54 joints, one clip "Epileptisch" of 3.3 s in which the
# figure leaps about), written as glTF binary by assimp's own exporter
# (Debian's assimp-utils). Prints the path of the .glb; builds it once.
#
#   scripts/humanoid.sh            (needs apt-get download, or both packages)
set -euo pipefail
cd "$(dirname "$0")/.."
out=target/models/humanoid.glb
if [ ! -s "$out" ]; then
  mkdir -p target/models
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  src=/usr/share/assimp/models/X/BCN_Epileptic.X
  if [ ! -f "$src" ]; then
    (cd "$work" && apt-get download -q assimp-testmodels >/dev/null && dpkg -x assimp-testmodels_*.deb root)
    src=$work/root$src
  fi
  command -v assimp >/dev/null || { echo "needs assimp (apt-get install assimp-utils)" >&2; exit 1; }
  assimp export "$src" "$work/humanoid.glb" -fglb2 >/dev/null
  mv "$work/humanoid.glb" "$out"
fi
echo "$out"
