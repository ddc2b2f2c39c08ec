# The one view pipeline: Python's best_view gives the view that `meshsal viewpoint`,
# `render --best` and `batch --view` print (one library call, best_viewpoint, with the same
# defaults), to the last printed digit; elevation and up go through it the same way.
import json

import numpy as np
import pytest

import meshsal
from conftest import bumpy_sphere


def g9(x):
    """A number as the CLI's JSON prints it (%.9g), read back."""
    return float("%.9g" % x)


OTHER = {"restarts": 3, "seed": 5, "resolution": 256, "depth_tol": 1.5}


@pytest.mark.parametrize("elevation,other", [(None, False), ((0.0, 40.0), False), (None, True)])
def test_one_view_in_every_front_end(elevation, other, mesh_path, cli, tmp_path):
    path = mesh_path("bunny_3k.off")
    el = [] if elevation is None else ["--elevation", "%g,%g" % elevation]
    kw = OTHER if other else {}
    for k, v in kw.items():
        el += ["--" + k.replace("_", "-"), str(v)]
    vp = cli.json("viewpoint", path, "--backend", "cpu", *el)
    rb = cli.json("render", path, "--best", "--backend", "cpu", "--size", "64", "-o", tmp_path / "r.png", "--json", *el)
    cli("batch", path, "-o", tmp_path / "b", "--view", "--backend", "cpu", "--size", "64", "-q", *el)
    lines = [json.loads(x) for x in (tmp_path / "b" / "batch.jsonl").read_text().splitlines() if x.strip()]
    bv = [x["view"] for x in lines if isinstance(x.get("view"), dict)][0]
    V, F = meshsal.load(str(path))
    b = meshsal.best_view(V, F, backend="cpu", elevation=elevation, **kw)
    for key in ["theta_deg", "phi_deg"]:
        assert g9(b[key]) == vp[key] == rb[key] == bv[key], key
    for key in ["theta", "phi"]:
        assert g9(b[key]) == vp[key] == rb[key], key
    assert [g9(x) for x in b["direction"]] == vp["direction"] == rb["direction"]
    assert g9(b["visible_score"]) == vp["visible_score"] == bv["visible_score"]
    assert g9(b["visible_fraction"]) == vp["visible_fraction"] == bv["visible_fraction"]
    assert b["resolution"] == vp["resolution"] == (256 if other else 512)
    # The band searched, said by both (the default one when none is given).
    assert list(b["elevation"]) == vp["elevation"]
    assert vp["elevation"][0] <= b["phi_deg"] <= vp["elevation"][1]
    if elevation is not None:
        assert b["elevation"] == elevation and vp["elevation"] == list(elevation)
        assert 0 <= b["phi_deg"] <= 40


def test_up_axis_is_a_frame():
    # A mesh turned so that z is up, searched with up='z', gives the y-up mesh's angles.
    V, F = bumpy_sphere(rings=24, segments=48)
    score = np.maximum(0, V[:, 1] + 0.3 * V[:, 0])
    Vz = np.stack([V[:, 0], -V[:, 2], V[:, 1]], axis=1)
    a = meshsal.best_view(V, F, score, backend="cpu", resolution=96, restarts=3, up="y")
    b = meshsal.best_view(Vz, F, score, backend="cpu", resolution=96, restarts=3, up="z")
    for key in ["theta", "phi", "visible_score"]:
        assert a[key] == b[key], key
    c = meshsal.best_view(Vz, F, score, backend="cpu", resolution=96, restarts=3, up="z", elevation=(-20, 20))
    assert -20 <= c["phi_deg"] <= 20 + 1e-9 and c["phi_deg"] != b["phi_deg"]


def test_elevation_checked():
    V, F = bumpy_sphere(rings=12, segments=24)
    score = np.maximum(0, V[:, 1])
    for bad in [(30, 10), (-91, 0), (0, 95)]:
        with pytest.raises(meshsal.Error, match="elevation range"):
            meshsal.best_view(V, F, score, backend="cpu", resolution=32, restarts=1, elevation=bad)
    with pytest.raises(ValueError, match="elevation must be"):
        meshsal.best_view(V, F, score, backend="cpu", elevation=(1, 2, 3))
    with pytest.raises(ValueError, match="elevation needs best=True"):
        meshsal.render(V, F, score, elevation=(0, 10))
    img = meshsal.render(V, F, score, best=True, elevation=(0, 10), size=32, backend="cpu")
    assert img.shape == (32, 32, 3)
