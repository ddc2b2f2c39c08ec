#!/bin/bash
# Tiled simplification's quality (README, simplify --tiles; issue 41): for igea_134k and
# bunny_36k at 10% and 1%, the untiled run and 2, 4, 8 tiles: the RMS error of `compare`
# over the untiled result's at the same target, the faces written, and the seconds of the
# whole command tiled / untiled. WEIGHTS=none (the default: plain quadrics) or balanced.
# Usage: tools/bench_tiled_quality.sh [build/meshsal]
set -euo pipefail
MESHSAL=${1:-build/meshsal}
DATA=$(dirname "$0")/../../shared/data/meshes
WEIGHTS=${WEIGHTS:-none}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

# simplify IN OUT ARGS...: seconds of the whole command
simplify() {
  local in=$1 out=$2; shift 2
  local start=$(date +%s.%N)
  "$MESHSAL" simplify "$in" -o "$out" --weights "$WEIGHTS" --backend cpu -q "$@" 2> /dev/null
  python3 -c "import sys; print(f'{float(sys.argv[2]) - float(sys.argv[1]):.2f}')" "$start" "$(date +%s.%N)"
}
rms() { "$MESHSAL" compare "$1" "$2" --json | python3 -c 'import json, sys; print(json.load(sys.stdin)["rms"])'; }
faces() { "$MESHSAL" compare "$1" "$2" --json | python3 -c 'import json, sys; print(json.load(sys.stdin)["simplified_faces"])'; }

echo "weights $WEIGHTS: RMS over untiled, faces, seconds tiled/untiled"
echo "| mesh, target | 2 tiles | 4 tiles | 8 tiles |"
echo "|---|---|---|---|"
for name in igea_134k.ply.gz bunny_36k.obj; do
  mesh=$DATA/$name
  [ -f "$mesh" ] || { echo "SKIPPED: missing shared data $mesh"; continue; }
  for ratio in 0.1 0.01; do
    t0=$(simplify "$mesh" "$WORK/u.ply" --ratio $ratio)
    r0=$(rms "$mesh" "$WORK/u.ply")
    row="| ${name%%.*} ${ratio} ($(faces "$mesh" "$WORK/u.ply"))"
    for tiles in 2 4 8; do
      t=$(simplify "$mesh" "$WORK/t.ply" --ratio $ratio --tiles $tiles)
      r=$(rms "$mesh" "$WORK/t.ply")
      row="$row | $(python3 -c "print(f'{$r / $r0:.2f}x')"), $(faces "$mesh" "$WORK/t.ply"), $t/$t0 s"
    done
    echo "$row |"
  done
done
