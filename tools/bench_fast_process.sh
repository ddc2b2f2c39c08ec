#!/bin/bash
# The fast method's whole-process benchmark (issue 25, docs/benchmarks.md "The fast method
# at the limit"): `meshsal saliency IN -o OUT --method fast --backend cpu` on igea_loop2
# (2.1M vertices, the shipped .ply.gz) and on igea_loop2 midpoint-subdivided once (8.6M
# vertices, a temporary binary PLY), timed as a whole (reading and writing included) with
# its peak resident memory, for one or two builds taking turns, so that both meet the same
# load on a shared machine.
# Usage: tools/bench_fast_process.sh [NEW=build/meshsal] [OLD] [repeats, default 3]
set -euo pipefail
NEW=${1:-build/meshsal}
OLD=${2:-}
REPEATS=${3:-3}
WORK=${TMPDIR:-/tmp}/meshsal_bench_fast
MESH=$(dirname "$0")/../../shared/data/meshes/igea_loop2_2149k.ply.gz
[ -f "$MESH" ] || { echo "SKIPPED: missing shared data $MESH"; exit 0; }
mkdir -p "$WORK"
PLY=$WORK/igea_loop2_x4.ply
[ -f "$PLY" ] || "$NEW" bench "$MESH" --subdivide 1 --write-mesh "$PLY"

run() {  # label, binary, input: one line with wall seconds and peak memory
  python3 - "$@" "$WORK/out.ply" <<'PY'
import json, subprocess, sys, time
label, binary, mesh, out = sys.argv[1:5]
t = time.time()
r = subprocess.run([binary, "saliency", mesh, "-o", out, "--method", "fast", "--backend", "cpu", "--json"],
                   check=True, capture_output=True, text=True)
wall = time.time() - t
j = json.loads(r.stdout)
# Builds older than the peak's report (4c9c1b2, issue 41's yardstick) print none.
peak = (f"peak {j['peak_rss'] / 2**20:6.0f} MiB = {j['peak_rss'] / j['vertices']:4.0f} B/vertex"
        if 'peak_rss' in j else "peak not reported")
print(f"{label:<4} {mesh.split('/')[-1]:<24} {j['vertices']:>9} vertices  wall {wall:6.2f} s  "
      f"read {j['read_seconds']:5.2f} s  saliency {j['seconds']:6.2f} s  {peak}", flush=True)
PY
}

for mesh in "$MESH" "$PLY"; do
  for i in $(seq "$REPEATS"); do
    [ -n "$OLD" ] && run old "$OLD" "$mesh"
    run new "$NEW" "$mesh"
  done
done
