#!/bin/bash
# Issue 42's targets on a machine with a Vulkan GPU, in one run (device time is short):
#   tools/bench_gpu_targets.sh [BUILD=build] [MESH_DIR=../shared/data/meshes] [repeats=3]
# MESH_DIR holds igea_loop2_2149k.ply.gz (MESH_NAME=... takes another, for a dry run on
# lavapipe with a small one). Prints, each with the device named:
#  1. bench_gpu_sweep on igea_loop2: the fp64 and layout probes, the exact sweep in both
#     layouts and precisions, each method's device curvature against its CPU twin (0 of N
#     vertices should differ: the device's double division and square root correctly
#     rounded), the fast method's stages, phases and host waits;
#  2. the exact method on igea_loop2: its stages (meshsal bench --backend gpu) and the whole
#     process (meshsal saliency --backend gpu --json; target: stages <= 0.5 s, process <= 2 s);
#  3. the fast method on igea_loop2 subdivided once (8.6M vertices, written once as binary
#     PLY): the whole process with --backend gpu and --backend cpu, taking turns, and the
#     ratio of the medians (target: gpu <= 0.5x cpu); a GPU run prints `ahead`, the seconds
#     it spent uploading while the PLY was read, beside its `device_warm_up` stage (what it
#     still waited for after the read);
#  4. views per second (bench_views --backend gpu).
# The build needs -DMESHSAL_BUILD_TOOLS=ON (bench_gpu_sweep, bench_views).
set -euo pipefail
BUILD=${1:-build}
MESHES=${2:-$(dirname "$0")/../../shared/data/meshes}
REPEATS=${3:-3}
MESH=$MESHES/${MESH_NAME:-igea_loop2_2149k.ply.gz}
[ -f "$MESH" ] || { echo "SKIPPED: missing $MESH"; exit 0; }
WORK=${TMPDIR:-/tmp}/meshsal_bench_gpu
mkdir -p "$WORK"
X4=$WORK/$(basename "$MESH" | cut -d. -f1)_x4.ply
[ -f "$X4" ] || "$BUILD/meshsal" bench "$MESH" --subdivide 1 --write-mesh "$X4"

echo "== 1. bench_gpu_sweep igea_loop2"
"$BUILD/bench_gpu_sweep" --repeat 2 "$MESH"

echo "== 2. exact igea_loop2: stages, then the whole process"
"$BUILD/meshsal" bench "$MESH" --backend gpu --repeat 3
process() {  # label, mesh, method, backend: one line with the wall seconds and the JSON's stages
  python3 - "$BUILD/meshsal" "$@" "$WORK/out.ply" <<'PY'
import json, subprocess, sys, time
binary, label, mesh, method, backend, out = sys.argv[1:7]
t = time.time()
r = subprocess.run([binary, "saliency", mesh, "-o", out, "--method", method, "--backend", backend, "--json"],
                   check=True, capture_output=True, text=True)
wall = time.time() - t
j = json.loads(r.stdout)
stages = " ".join(f"{name} {sec:.3f}" for name, sec in j.get("stages", {}).items())
print(f"{label:<10} {mesh.split('/')[-1]:<24} wall {wall:6.2f} s  read {j['read_seconds']:5.2f} s  "
      f"ahead {j.get('upload_while_reading_seconds', 0):5.3f} s  saliency {j['seconds']:6.2f} s  [{stages}]", flush=True)
print(f"WALL {label} {wall:.3f}", file=sys.stderr)
PY
}
process exact-gpu "$MESH" exact gpu 2>/dev/null  # the first pays the pipelines' compiles
process exact-gpu "$MESH" exact gpu 2>/dev/null

echo "== 3. fast, igea_loop2 x4, whole process, gpu and cpu taking turns"
: > "$WORK/walls"
for i in $(seq "$REPEATS"); do
  process fast-gpu "$X4" fast gpu 2>>"$WORK/walls"
  process fast-cpu "$X4" fast cpu 2>>"$WORK/walls"
done
python3 - "$WORK/walls" <<'PY'
import statistics, sys
w = {}
for line in open(sys.argv[1]):
    if line.startswith("WALL "):
        _, label, s = line.split()
        w.setdefault(label, []).append(float(s))
g, c = statistics.median(w["fast-gpu"]), statistics.median(w["fast-cpu"])
print(f"medians: gpu {g:.2f} s, cpu {c:.2f} s, gpu/cpu {g / c:.2f} (target <= 0.5)")
PY

echo "== 4. views per second"
"$BUILD/bench_views" --backend gpu
