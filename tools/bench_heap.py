#!/usr/bin/env python3
"""What meshsal.keep_freed_memory() buys a Python program (issue 26).

    PYTHONPATH=build/python python3 tools/bench_heap.py [MESH] [--processes 4] [--calls 4]
                                                        [--method fast] [--threads 0]

Each measurement is a fresh interpreter (the heap policy is process-wide and cannot be
undone cleanly), alternating between the two settings so that the load of a shared machine
falls on both: `import meshsal`, load MESH, then --calls calls of
meshsal.saliency(V, F, method=METHOD, backend='cpu'), with or without
meshsal.keep_freed_memory() first. The first call of each process is dropped (it grows the
heap either way); for the others it records the wall time, the minor page faults and the
system CPU time of each call, and the process's peak resident memory. Prints one JSON object
with the medians over every kept call and the largest peak of each setting.
"""
import argparse
import json
import statistics
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

CHILD = r"""
import json, resource, sys, time
import meshsal
path, method, calls, threads, keep = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), sys.argv[5] == "1"
if keep:
    meshsal.keep_freed_memory()
V, F = meshsal.load(path)
rows = []
for i in range(calls):
    r0 = resource.getrusage(resource.RUSAGE_SELF)
    t0 = time.perf_counter()
    meshsal.saliency(V, F, method=method, backend="cpu", threads=threads)
    t = time.perf_counter() - t0
    r1 = resource.getrusage(resource.RUSAGE_SELF)
    rows.append({"seconds": t, "minor_faults": r1.ru_minflt - r0.ru_minflt, "system_s": r1.ru_stime - r0.ru_stime})
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
print(json.dumps({"calls": rows, "peak_rss_bytes": peak}))
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("mesh", nargs="?", default=str(ROOT.parent / "shared/data/meshes/igea_134k.ply.gz"))
    ap.add_argument("--processes", type=int, default=4, help="processes per setting")
    ap.add_argument("--calls", type=int, default=4, help="calls per process (the first is dropped)")
    ap.add_argument("--method", default="fast")
    ap.add_argument("--threads", type=int, default=0)
    a = ap.parse_args()
    if a.calls < 2:
        sys.exit("error: --calls must be at least 2 (the first call of each process is dropped)")
    kept = {"default": [], "keep_freed_memory": []}
    peaks = {"default": 0, "keep_freed_memory": 0}
    for _ in range(a.processes):
        for name, flag in (("default", "0"), ("keep_freed_memory", "1")):
            out = subprocess.run([sys.executable, "-c", CHILD, a.mesh, a.method, str(a.calls), str(a.threads), flag],
                                 capture_output=True, text=True)
            if out.returncode != 0:
                sys.exit(f"error: the {name} process failed: {out.stderr.strip()}")
            r = json.loads(out.stdout)
            kept[name] += r["calls"][1:]
            peaks[name] = max(peaks[name], r["peak_rss_bytes"])
    result = {"mesh": Path(a.mesh).name, "method": a.method, "threads": a.threads,
              "processes_per_setting": a.processes, "calls_kept_per_setting": len(kept["default"])}
    for name, rows in kept.items():
        result[name] = {
            "median_seconds": round(statistics.median(r["seconds"] for r in rows), 4),
            "best_seconds": round(min(r["seconds"] for r in rows), 4),
            "median_minor_faults": int(statistics.median(r["minor_faults"] for r in rows)),
            "median_system_s": round(statistics.median(r["system_s"] for r in rows), 3),
            "peak_rss_mib": round(peaks[name] / 2**20, 1),
        }
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
