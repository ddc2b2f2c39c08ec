# The module's other entry points: simplify's targets and weights, render's pictures,
# best_view with a given score, devices, docstrings.
import numpy as np
import pytest

import meshsal


def test_simplify_targets_and_weights(sphere):
    V, F = sphere
    r = meshsal.simplify(V, F, 500, weights="none")
    assert (r.output_faces, r.target_faces, r.reached, r.unchanged) == (500, 500, True, False)
    V2, F2 = r                                   # unpacks as (vertices, faces)
    assert V2.dtype == np.float64 and F2.dtype == np.uint32 and F2.shape == (500, 3)  # as V
    assert int(F2.max()) < len(V2) == len(r.vertex_origin)
    assert (np.diff(r.vertex_origin.astype(np.int64)) > 0).all()  # survivors in input order


def test_simplify_weights_change_the_result(sphere):
    V, F = sphere
    plain = meshsal.simplify(V, F, ratio=0.2, weights="none", backend="cpu")
    salient = meshsal.simplify(V, F, ratio=0.2, backend="cpu")
    assert salient.weights == "balanced" and salient.alpha > 0  # the default
    assert salient.device.startswith("cpu (") and plain.device == "cpu"
    assert plain.output_faces == salient.output_faces == round(0.2 * len(F))
    assert not np.array_equal(plain.vertex_origin, salient.vertex_origin)
    # Weights given as an array: all ones is the plain quadric error.
    ones = meshsal.simplify(V, F, ratio=0.2, weights=np.ones(len(V)))
    np.testing.assert_array_equal(ones.vertices, plain.vertices)
    np.testing.assert_array_equal(ones.faces, plain.faces)


def test_simplify_target_above_faces_returns_mesh_unchanged(sphere):
    V, F = sphere
    r = meshsal.simplify(V, F, len(F) + 10)
    assert r.unchanged and r.output_faces == len(F) and "unchanged" in r.note
    np.testing.assert_array_equal(r.faces, F)


def test_render_picture(sphere):
    V, F = sphere
    img = meshsal.render(V, F, size=64, backend="cpu")
    assert img.shape == (64, 64, 3) and img.dtype == np.uint8
    assert (img[0, 0] == 255).all()                  # white background in the corner
    centre = img[24:40, 24:40].reshape(-1, 3).astype(int)
    assert (np.ptp(centre, axis=1) > 30).any()       # saliency colours, not grey
    grey = meshsal.render(V, F, size=64, grey=True)
    g = grey[24:40, 24:40].reshape(-1, 3).astype(int)
    assert (np.ptp(g, axis=1) == 0).all() and (g < 255).any()  # shaded grey surface
    # Given values: a constant colours the surface evenly; another view, another picture.
    side = meshsal.render(V, F, np.arange(len(V), dtype=float), theta=90, size=64, backend="cpu")
    front = meshsal.render(V, F, np.arange(len(V), dtype=float), size=64, backend="cpu")
    assert not np.array_equal(side, front)
    ranged = meshsal.render(V, F, np.arange(len(V), dtype=float), size=64, color_range=("10%", "90%"))
    assert not np.array_equal(ranged, front)
    assert np.array_equal(ranged, meshsal.render(V, F, np.arange(len(V), dtype=float), size=64,
                                                 color_range="10%,90%"))


def test_best_view_with_given_score(sphere):
    V, F = sphere
    # All the score on the +x side: the best view looks from +x (theta 90 degrees).
    score = np.where(V[:, 0] > 0.5, 1.0, 0.0)
    b = meshsal.best_view(V, F, score, restarts=4, resolution=128, backend="cpu")
    assert b["score_source"] == "given"
    assert b["direction"][0] > 0.9 and abs(b["theta_deg"] - 90) < 15
    assert 0.5 < b["visible_fraction"] <= 1 and b["exhaustive"] is None
    # up='z' searches in the z-up frame (its random starts are other directions), so it may
    # end elsewhere on the flat top of U; it still looks from +x, theta 90 in that frame too.
    up_z = meshsal.best_view(V, F, score, restarts=4, resolution=128, backend="cpu", up="z")
    assert up_z["direction"][0] > 0.9 and abs(up_z["theta_deg"] - 90) < 15
    assert up_z["visible_score"] == pytest.approx(b["visible_score"], rel=0.05)


def test_docstrings_and_devices():
    for name in ["load", "saliency", "simplify", "best_view", "render", "devices", "built_with_vulkan"]:
        doc = getattr(meshsal, name).__doc__
        assert doc.startswith(name + "("), name
    assert "backend" in meshsal.saliency.__doc__ and "GIL" in meshsal.saliency.__doc__
    if meshsal.built_with_vulkan():
        try:
            devs = meshsal.devices()
        except meshsal.Error:
            pytest.skip("no Vulkan driver")
        assert all({"index", "name", "type"} <= set(d) for d in devs)
