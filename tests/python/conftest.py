# Shared fixtures of the Python module's tests (tests/python). ctest runs them with
# PYTHONPATH at the built module, MESHSAL_CLI at the built `meshsal` and MESHSAL_DATA_DIR
# at ../shared/data/meshes; tests that need a missing piece skip with the reason.
import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest


ROOT = Path(__file__).resolve().parents[2]


def _data_dir():
    return Path(os.environ.get("MESHSAL_DATA_DIR", ROOT.parent / "shared" / "data" / "meshes"))


def _data_required():
    """MESHSAL_REQUIRE_DATA=1 (set by .ci/run): a missing shared mesh fails instead of skipping."""
    return os.environ.get("MESHSAL_REQUIRE_DATA", "") not in ("", "0")


@pytest.fixture
def mesh_path():
    """mesh_path('bunny_3k.off') -> Path; skips when the scan is absent (fails under
    MESHSAL_REQUIRE_DATA=1)."""
    def find(name):
        p = _data_dir() / name
        if not p.exists():
            if _data_required():
                pytest.fail(f"missing shared data {p} (MESHSAL_REQUIRE_DATA=1 makes this a failure)")
            pytest.skip(f"missing shared data {p}")
        return p
    return find


@pytest.fixture
def cli():
    """cli(*args) -> CompletedProcess of the built `meshsal` (text), or skips without it."""
    exe = os.environ.get("MESHSAL_CLI", str(ROOT / "build" / "meshsal"))
    if not Path(exe).exists():
        pytest.skip(f"no meshsal executable at {exe}")

    def run(*args, check=True):
        r = subprocess.run([exe, *map(str, args)], capture_output=True, text=True)
        if check and r.returncode != 0:
            raise AssertionError(f"meshsal {' '.join(map(str, args))}: {r.returncode}: {r.stderr}")
        return r
    run.json = lambda *args: json.loads(run(*args).stdout)
    return run


def bumpy_sphere(rings=64, segments=128, bumps=7.0):
    """A closed UV sphere with a bumpy radius: (V float64 (n,3), F int64 (m,3))."""
    theta = np.linspace(0, np.pi, rings + 1)[1:-1]
    phi = np.linspace(0, 2 * np.pi, segments, endpoint=False)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    r = 1 + 0.05 * np.sin(bumps * t) * np.cos(bumps * p)
    ring = np.stack([r * np.sin(t) * np.cos(p), r * np.cos(t), r * np.sin(t) * np.sin(p)], -1).reshape(-1, 3)
    V = np.vstack([[0, 1, 0], ring, [0, -1, 0]])
    idx = lambda i, j: 1 + i * segments + (j % segments)  # noqa: E731
    F = []
    for j in range(segments):
        F.append([0, idx(0, j + 1), idx(0, j)])
        F.append([len(V) - 1, idx(rings - 2, j), idx(rings - 2, j + 1)])
    for i in range(rings - 2):
        for j in range(segments):
            a, b, c, d = idx(i, j), idx(i, j + 1), idx(i + 1, j), idx(i + 1, j + 1)
            F += [[a, b, c], [b, d, c]]
    return V.astype(np.float64), np.array(F, dtype=np.int64)


@pytest.fixture
def sphere():
    return bumpy_sphere(rings=24, segments=48)
