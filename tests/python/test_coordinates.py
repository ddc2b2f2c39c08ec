# Issue 22 (1): coordinates far from the origin (a scan at survey coordinates) give the results
# of the same scan at the origin, and float64 vertices come back as float64.
import numpy as np

import meshsal

SHIFT = np.array([5e5, 4e6, 100.0])


def test_survey_coordinates_give_the_origin_results(sphere):
    V, F = sphere
    V = V * 12.5                                   # a 25 m scan
    far = V + SHIFT
    s0 = meshsal.saliency(V, F, backend="cpu").saliency
    s1 = meshsal.saliency(far, F, backend="cpu").saliency
    assert np.abs(s1 - s0).max() <= 1e-5 * s0.max()
    # What the old float32 path gave: the coordinates rounded where they lie.
    naive = meshsal.saliency(far.astype(np.float32), F, backend="cpu").saliency
    assert np.abs(naive - s0).max() > 1e-2 * s0.max()

    r0 = meshsal.simplify(V, F, ratio=0.2, backend="cpu")
    r1 = meshsal.simplify(far, F, ratio=0.2, backend="cpu")
    assert r1.vertices.dtype == np.float64
    np.testing.assert_array_equal(r1.faces, r0.faces)
    diag = np.linalg.norm(V.max(0) - V.min(0))
    assert np.abs(r1.vertices - SHIFT - r0.vertices).max() <= 1e-7 * diag
    # Survivors no collapse moved come back exactly as given.
    r2 = meshsal.simplify(far, F, ratio=0.9, backend="cpu")
    same = (r2.vertices == far[r2.vertex_origin]).all(axis=1)
    assert same.sum() > len(same) // 2


def test_precision_follows_the_input(sphere, tmp_path):
    V, F = sphere
    assert meshsal.simplify(V, F, ratio=0.5).vertices.dtype == np.float64
    assert meshsal.simplify(V.astype(np.float32), F, ratio=0.5).vertices.dtype == np.float32
    # A text file's decimals come back as float64, exactly as written.
    p = tmp_path / "far.obj"
    p.write_text("v 500000.125 4000000.3 100.01\nv 500001 4000000.3 100\nv 500000 4000001.7 100.5\nf 1 2 3\n")
    V2, F2 = meshsal.load(p)
    assert V2.dtype == np.float64
    assert V2.tolist() == [[500000.125, 4000000.3, 100.01], [500001, 4000000.3, 100], [500000, 4000001.7, 100.5]]
