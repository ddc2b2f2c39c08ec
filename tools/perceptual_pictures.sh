#!/usr/bin/env bash
# The README's picture of both models: each shared scan from its best view in the default
# band (the angles of README's "Viewpoints: the default band" table), coloured by the paper's
# saliency (left: --model lee2005) and by the perceptual model (right: --model perceptual).
#   tools/perceptual_pictures.sh [OUT.png]      (default docs/models_side_by_side.png)
# MESHSAL (default build/meshsal) and DATA (default ../shared/data/meshes) may be set.
# Needs numpy for tools/side_by_side.py (Debian: python3-numpy).
set -euo pipefail
meshsal=${MESHSAL:-build/meshsal}
data=${DATA:-../shared/data/meshes}
out=${1:-docs/models_side_by_side.png}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/lee2005" "$tmp/perceptual"
names=()
while read -r mesh theta phi; do
  [ -f "$data/$mesh" ] || { echo "skipping $mesh: not in $data" >&2; continue; }
  name=${mesh%%.*}
  for model in lee2005 perceptual; do
    "$meshsal" render "$data/$mesh" --model "$model" --method auto --theta "$theta" --phi "$phi" --size 256 -q \
      -o "$tmp/$model/${name}_view.png"
  done
  names+=("$name")
done <<'LIST'
bunny_36k.obj -25.3 10.0
armadillo_43k.obj 2.5 10.0
igea_134k.ply.gz 17.2 12.8
max_planck_5k.obj -179.2 10.0
dragon_50k.ply 151.9 20.5
lucy_50k.ply 178.4 10.0
LIST
[ ${#names[@]} -gt 0 ] || { echo "no scans found in $data" >&2; exit 1; }
/usr/bin/python3 "$(dirname "$0")/side_by_side.py" "$out" "$tmp/lee2005" "$tmp/perceptual" "${names[@]}"
echo "wrote $out"
