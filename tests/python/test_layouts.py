# Arrays as trimesh and Open3D hold them (float64 vertices, int64 faces), float32/uint32, and
# non-contiguous views all give the same results (per precision of the coordinates).
import threading
import time

import numpy as np

import meshsal
from conftest import bumpy_sphere


def read_only(a):
    a = a.copy()
    a.flags.writeable = False
    return a


def test_layouts_give_identical_results(sphere):
    V64, F64 = sphere
    # float64 coordinates are localized in double (meshsal.h, Mesh::origin), float32 ones
    # from their float values: one reference for each.
    ref32 = meshsal.saliency(V64.astype(np.float32), F64.astype(np.uint32), backend="cpu")
    ref64 = meshsal.saliency(V64, F64.astype(np.uint32), backend="cpu")
    wide = np.zeros((len(V64), 7))
    wide[:, 1:7:2] = V64                     # a strided column view, as from a structured array
    layouts = [
        (V64, F64),                                        # trimesh: float64, int64
        (V64.astype(np.float32), F64.astype(np.int32)),    # Open3D-like float32, int32
        (np.asfortranarray(V64), np.asfortranarray(F64)),  # column-major
        (wide[:, 1:7:2], F64[:, :]),                       # non-contiguous view
        (V64[::-1][::-1], F64.astype(np.uint64)),          # negative strides twice
        (V64.tolist(), F64.tolist()),                      # plain lists
        (V64.astype(">f8"), F64.astype(">i4")),            # big-endian, as read from a file
        (read_only(V64), read_only(F64)),                  # read-only buffers
    ]
    assert not layouts[3][0].flags.c_contiguous
    for i, (V, F) in enumerate(layouts):
        r = meshsal.saliency(V, F, backend="cpu")
        ref = ref32 if i == 1 else ref64
        np.testing.assert_array_equal(r.saliency, ref.saliency)
        np.testing.assert_array_equal(r.curvature, ref.curvature)


def test_results_are_owned_arrays(sphere):
    V, F = sphere
    r = meshsal.saliency(V, F, backend="cpu", smoothed=True, raw_maps=True)
    n = len(V)
    assert r.saliency.dtype == np.float64 and r.saliency.shape == (n,)
    assert r.curvature.shape == (n,) and r.smoothed.shape == (n,)
    assert r.raw.shape == (5, n) and r.is_point.dtype == bool and r.is_point.all()
    # The arrays wrap the library's vectors (no copy): numpy does not own the data buffer,
    # a capsule does; they stay valid after the result object is gone.
    s = r.saliency
    assert not s.flags.owndata and s.base is not None
    del r
    assert np.isfinite(s).all() and s.max() > 0
    assert meshsal.saliency(V, F, backend="cpu").raw is None


def test_load_returns_library_arrays(tmp_path):
    p = tmp_path / "quad.obj"
    p.write_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n")
    V, F = meshsal.load(str(p))
    assert V.dtype == np.float32 and V.shape == (4, 3)
    assert F.dtype == np.uint32 and F.tolist() == [[0, 1, 2], [0, 2, 3]]  # fan-triangulated
    assert not V.flags.owndata


def test_gil_released_during_saliency():
    V, F = bumpy_sphere(rings=160, segments=320)  # ~51k vertices: a call of a second or so
    ticks = []
    stop = threading.Event()

    def counter():
        while not stop.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    t = threading.Thread(target=counter)
    t.start()
    try:
        time.sleep(0.05)
        start = time.perf_counter()
        meshsal.saliency(V, F, backend="cpu", threads=1)
        end = time.perf_counter()
    finally:
        stop.set()
        t.join()
    inside = [x for x in ticks if start < x < end]
    # Without the release the counter could not run at all during the call (it holds the
    # GIL throughout); with it, it ticks about every millisecond.
    assert end - start > 0.2, "the call was too short to tell"
    assert len(inside) >= 50, f"{len(inside)} ticks in {end - start:.3f} s"
