#!/usr/bin/env python3
"""What the Python call adds to the library's time (issue 15: at most 5% on bunny_36k).

    PYTHONPATH=build/python python3 tools/bench_python.py [MESH] [--rounds 5] [--build build]

Rounds alternate between the two, so that the load of a shared machine falls on both:
  C++:    build/bench_saliency_call MESH 3 (compute_saliency's wall time, CPU path, default
          options; the first, cold call of each process is dropped),
  Python: meshsal.saliency(V, F, backend='cpu') twice, with V, F as meshsal.load gives them
          (float32, uint32) and as trimesh holds them (float64, int64): the arrays checked
          and read in, the GIL released, the results wrapped as numpy arrays.
Also the module's own cost alone: simplify() with a target above the face count does only
the arrays in, the mesh validation and the arrays out. Prints one JSON object.
"""
import argparse
import json
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

import meshsal

ROOT = Path(__file__).resolve().parents[1]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("mesh", nargs="?", default=str(ROOT.parent / "shared/data/meshes/bunny_36k.obj"))
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--build", default=str(ROOT / "build"))
    a = ap.parse_args()
    harness = Path(a.build) / "bench_saliency_call"
    if not harness.exists():
        sys.exit(f"error: {harness} not found (cmake --build build --target bench_saliency_call)")

    V, F = meshsal.load(a.mesh)
    layouts = {"float32_uint32": (V, F), "float64_int64": (V.astype(np.float64), F.astype(np.int64))}
    meshsal.saliency(V, F, backend="cpu")  # warm: thread pool, page faults
    cpp, py = [], {k: [] for k in layouts}
    for _ in range(a.rounds):
        out = subprocess.run([str(harness), a.mesh, "3"], capture_output=True, text=True, check=True).stdout
        cpp += json.loads(out)["wall_s"][1:]
        for name, (v, f) in layouts.items():
            t = time.perf_counter()
            meshsal.saliency(v, f, backend="cpu")
            py[name].append(time.perf_counter() - t)

    own = {}
    for name, (v, f) in layouts.items():
        ts = []
        for _ in range(20):
            t = time.perf_counter()
            meshsal.simplify(v, f, len(f) + 1)
            ts.append(time.perf_counter() - t)
        own[name] = statistics.median(ts)

    res = {"mesh": a.mesh, "vertices": int(len(V)), "rounds": a.rounds,
           "cpp_call_s": {"best": min(cpp), "median": statistics.median(cpp)}}
    for name, ts in py.items():
        res[name] = {"python_call_s": {"best": min(ts), "median": statistics.median(ts)},
                     "added_best": min(ts) / min(cpp) - 1,
                     "added_median": statistics.median(ts) / statistics.median(cpp) - 1,
                     "module_own_s": own[name],
                     "module_own_fraction": own[name] / min(cpp)}
    print(json.dumps(res, indent=1))


if __name__ == "__main__":
    sys.exit(main())
