#!/usr/bin/env bash
# docs/khronos.md: every glTF and GLB variant of the Khronos sample models
# drawn by `rastty render`, one frame of 80×24 cells, by two builds side by
# side: what each draws, what it does not draw (its notes), and what it
# refuses and why.
#
#   scripts/khronos.sh SAMPLES BEFORE AFTER > docs/khronos.md
#
# SAMPLES: a copy of glTF-Sample-Assets' Models folder's parent (this
# repository used a 2023 snapshot, DRx3D/glTF-Sample-Assets-OLD, its files
# written out of git); BEFORE and AFTER: two `rastty` binaries.
set -euo pipefail
cd "$(dirname "$0")/.."
samples=$1 before=$2 after=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# What one build says of one file: draws, draws with notes, or refused.
said() {
  local bin=$1 file=$2 out=$work/out rc=0
  timeout 120 "$bin" render "$file" --cols 80 --rows 24 --color none >/dev/null 2>"$out" || rc=$?
  if [ "$rc" -eq 0 ]; then
    local notes
    notes=$(sed -n 's/^note: [^:]*: not drawn: //p' "$out" | paste -sd';' - | sed 's/|/\\|/g')
    if [ -n "$notes" ]; then echo "draws; not drawn: $notes"; else echo "draws"; fi
  elif [ "$rc" -eq 124 ]; then
    echo "**timed out**"
  else
    # The error, less the file's path.
    local e
    e=$(sed -n 's/^error: //p' "$out" | head -1 | sed "s|$samples/||g; s|[^ ]*\.gl[tb][f]*: ||; s/|/\\\\|/g")
    echo "refused: ${e:-exit $rc}"
  fi
}
echo "# The Khronos glTF sample models"
echo
echo "Every glTF and GLB variant of the Khronos sample models (a 2023 snapshot of"
echo "glTF-Sample-Assets, the variants whose files were all there) drawn by"
echo "\`rastty render\`, one frame of 80×24 cells, by two builds: what each draws,"
echo "what it says it does not draw, and what it refuses and why. Written by"
echo "\`scripts/khronos.sh\` (do not edit by hand: run it)."
echo
echo "| model | variant | before | after |"
echo "|---|---|---|---|"
counts_b=(0 0 0) counts_a=(0 0 0) incomplete=0
while IFS= read -r file; do
  rel=${file#"$samples"/Models/}
  model=${rel%%/*}
  variant=$(basename "$(dirname "$rel")")
  b=$(said "$before" "$file")
  a=$(said "$after" "$file")
  # A variant the snapshot does not have whole is left out, counted.
  if [[ $b == *"No such file"* || $a == *"No such file"* ]]; then
    incomplete=$((incomplete + 1))
    continue
  fi
  for k in b a; do
    v=${!k}
    case $v in
      draws) i=0 ;;
      draws*) i=1 ;;
      *) i=2 ;;
    esac
    if [ $k = b ]; then counts_b[i]=$((counts_b[i] + 1)); else counts_a[i]=$((counts_a[i] + 1)); fi
  done
  echo "| $model | $variant | $b | $a |"
done < <(find "$samples/Models" \( -name '*.gltf' -o -name '*.glb' \) | sort)
echo
echo "| | before | after |"
echo "|---|---:|---:|"
echo "| draws everything it reads | ${counts_b[0]} | ${counts_a[0]} |"
echo "| draws, with a note of what it does not | ${counts_b[1]} | ${counts_a[1]} |"
echo "| refused | ${counts_b[2]} | ${counts_a[2]} |"
echo
echo "$incomplete variants are left out: the snapshot does not have all their files."

# The pictures scripts/khronos-pictures.sh made, where there are any.
if compgen -G "docs/khronos/*.png" >/dev/null; then
  echo
  echo "## Pictures"
  echo
  echo "Samples this work changed, at 100×32 cells: the build before, the build"
  echo "after, and the sample's own reference screenshot (\`scripts/khronos-pictures.sh\`)."
  for png in docs/khronos/*.png; do
    name=$(basename "$png" .png)
    echo
    echo "![$name: before, after, reference](khronos/$name.png)"
  done
fi

# Peak memory of the largest textured samples, one frame of 120×40 cells:
# each build as it stands, and the after build keeping textures whole.
echo
echo "## Memory"
echo
echo "Peak resident memory drawing one frame of 120×40 cells (\`/usr/bin/time -f %M\`)."
echo
echo "| model | before | after | after, \`--texture-size full\` |"
echo "|---|---:|---:|---:|"
peak() { /usr/bin/time -f %M "$@" >/dev/null 2>"$work/time" || true; echo "$(( $(tail -1 "$work/time") / 1024 )) MiB"; }
for m in StainedGlassLamp DamagedHelmet; do
  f=$samples/Models/$m/glTF/$m.gltf
  [ -f "$f" ] || continue
  echo "| $m | $(peak "$before" render "$f" --cols 120 --rows 40 --color none) | $(peak "$after" render "$f" --cols 120 --rows 40 --color none) | $(peak "$after" render "$f" --cols 120 --rows 40 --color none --texture-size full) |"
done
