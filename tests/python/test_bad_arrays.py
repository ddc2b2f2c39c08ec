# Bad arrays are refused before any work: TypeError for a wrong type or dtype, ValueError
# for a wrong shape or value, with a message that names the problem.
import numpy as np
import pytest

import meshsal

V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float64)
F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], dtype=np.int32)


def nan_at(i, k, value=np.nan):
    v = V.copy()
    v[i, k] = value
    return v


CASES = [
    # (vertices, faces, exception, words the message must hold)
    (V[:, :2], F, ValueError, "vertices must have shape (n, 3), got (4, 2)"),
    (V.ravel(), F, ValueError, "vertices must have shape (n, 3), got (12,)"),
    (V[None], F, ValueError, "vertices must have shape (n, 3), got (1, 4, 3)"),
    (V, F[:, :2], ValueError, "faces must have shape (n, 3), got (4, 2)"),
    (V, F.ravel(), ValueError, "faces must have shape (n, 3), got (12,)"),
    (V.astype(np.int64), F, TypeError, "vertices must be float32 or float64, got int64"),
    (V.astype(np.complex128), F, TypeError, "vertices must be float32 or float64, got complex128"),
    (V.astype(np.float16), F, TypeError, "vertices must be float32 or float64, got float16"),
    (V, F.astype(np.float64), TypeError, "faces must be an integer array (int32, int64, uint32, ...), got float64"),
    (V, F.astype(bool), TypeError, "faces must be an integer array"),
    (V, np.array([["a", "b", "c"]]), TypeError, "faces must be an integer array"),
    (None, F, TypeError, "vertices must be an array, got None"),
    (V, None, TypeError, "faces must be an array, got None"),
    (nan_at(2, 1), F, ValueError, "vertices: vertex 2 has a non-finite coordinate (nan)"),
    (nan_at(3, 0, np.inf), F, ValueError, "vertices: vertex 3 has a non-finite coordinate (inf)"),
    (nan_at(1, 2, -np.inf), F, ValueError, "vertices: vertex 1 has a non-finite coordinate (-inf)"),
    (nan_at(0, 0, 1e300), F, ValueError, "vertices: vertex 0 has a coordinate beyond float32's range"),
    (V, np.array([[0, 1, 4]]), ValueError, "faces: index 4 in face 0 is out of range for 4 vertices"),
    (V, np.array([[0, 1, 2], [0, -1, 2]]), ValueError, "faces: index -1 in face 1 is out of range for 4 vertices"),
    (V, np.array([[0, 1, 2**40]], dtype=np.int64), ValueError, "faces: index 1099511627776 in face 0 is out of range"),
    (V, np.array([[0, 1, 2**32]], dtype=np.uint64), ValueError, "faces: index 4294967296 in face 0 is out of range"),
]


@pytest.mark.parametrize("vertices, faces, exc, message", CASES)
@pytest.mark.parametrize("call", ["saliency", "simplify", "best_view", "render"])
def test_bad_array_refused(call, vertices, faces, exc, message):
    fn = getattr(meshsal, call)
    kwargs = {"ratio": 0.5} if call == "simplify" else {}
    with pytest.raises(exc) as e:
        fn(vertices, faces, backend="cpu", **kwargs)
    assert message in str(e.value)


def test_library_checks_become_meshsal_error():
    # Only zero-area triangles, no faces: the library's own validation, its message.
    flat = np.zeros((3, 3))
    with pytest.raises(meshsal.Error, match="zero"):
        meshsal.saliency(flat, np.array([[0, 1, 2]]), backend="cpu")
    with pytest.raises(meshsal.Error, match="empty|no triangles|no faces"):
        meshsal.saliency(V, np.zeros((0, 3), dtype=np.int32), backend="cpu")


@pytest.mark.parametrize("name, values, exc, message", [
    ("score", np.ones(3), ValueError, "score must have shape (4,), one value per vertex"),
    ("score", np.ones((4, 1)), ValueError, "score must have shape (4,)"),
    ("score", np.array([1, 1, np.nan, 1]), ValueError, "score: value 2 is not finite"),
    ("score", np.array(["a"] * 4), TypeError, "score must be a real array"),
])
def test_bad_score_refused(name, values, exc, message):
    with pytest.raises(exc) as e:
        meshsal.best_view(V, F, values, backend="cpu")
    assert message in str(e.value)


def test_bad_options_refused():
    with pytest.raises(ValueError, match="backend must be auto, cpu or gpu, got 'tpu'"):
        meshsal.saliency(V, F, backend="tpu")
    with pytest.raises(ValueError, match="method must be exact, fast or auto"):
        meshsal.saliency(V, F, method="slow")
    with pytest.raises(ValueError, match="precision must be"):
        meshsal.saliency(V, F, precision="half")
    with pytest.raises(meshsal.Error, match="eps"):
        meshsal.saliency(V, F, eps_frac=0.5, backend="cpu")
    with pytest.raises(meshsal.Error, match="scale"):
        meshsal.saliency(V, F, scales=[0, 2], backend="cpu")
    with pytest.raises(ValueError, match="give target_faces, ratio or target_error"):
        meshsal.simplify(V, F)
    with pytest.raises(ValueError, match="give only one of target_faces and ratio"):
        meshsal.simplify(V, F, 2, ratio=0.5)
    with pytest.raises(ValueError, match=r"ratio must be in \(0, 1\], got 1.5"):
        meshsal.simplify(V, F, ratio=1.5)
    with pytest.raises(ValueError, match=r"target_faces must be in \[1, 4000000000\], got 0"):
        meshsal.simplify(V, F, 0)
    with pytest.raises(TypeError, match="target_faces must be an integer, got float"):
        meshsal.simplify(V, F, 2.5)
    with pytest.raises(TypeError, match="ratio must be a number"):
        meshsal.simplify(V, F, ratio="half")
    assert meshsal.simplify(V, F, np.int64(2), weights="none").output_faces >= 2  # numpy ints
    with pytest.raises(ValueError, match="weights must be 'saliency', 'balanced', 'none' or an array"):
        meshsal.simplify(V, F, 2, weights="heavy")
    with pytest.raises(ValueError, match="up must be"):
        meshsal.render(V, F, up="w", backend="cpu")
    with pytest.raises(ValueError, match="phi must be in"):
        meshsal.render(V, F, phi=91, backend="cpu")
    with pytest.raises(meshsal.Error):
        meshsal.render(V, F, size=8, backend="cpu")
    with pytest.raises(meshsal.Error):
        meshsal.render(V, F, color_range="9,1", backend="cpu")
