# The module's results equal the CLI's on real scans: the same library calls, so the same
# numbers. The CLI writes saliency as float32 PLY properties and its JSON with 9
# significant digits: the module's doubles must give exactly those.
import numpy as np
import pytest

import meshsal


def stats(s):
    """The CLI's statistics of S (saliency_output.cpp: nearest rank percentiles)."""
    s = np.sort(s)
    rank = lambda p: s[min(len(s) - 1, max(int(np.ceil(p / 100.0 * len(s))) - 1, 0))]  # noqa: E731
    return {"min": s[0], "mean": np.sum(s) / len(s), "max": s[-1],
            "p10": rank(10), "p50": rank(50), "p90": rank(90), "p99": rank(99)}


def g9(x):
    return float("%.9g" % x)


@pytest.mark.parametrize("name", ["bunny_3k.off", "bunny_36k.obj"])
def test_saliency_equals_cli(name, mesh_path, cli, tmp_path):
    path = mesh_path(name)
    out = tmp_path / "sal.ply"
    j = cli.json("saliency", path, "-o", out, "--backend", "cpu", "--dump-scales", "--json")
    V, F = meshsal.load(str(path))
    r = meshsal.saliency(V, F, backend="cpu", raw_maps=True)
    _, _, props = meshsal.load(str(out), properties=True)
    assert r.backend == j["device"]
    assert g9(r.eps) == j["eps"]
    assert r.pairs == j["pairs"]
    assert int(r.is_point.sum()) == j["points"]
    # Every per-vertex value, as the CLI stores it (float32), bit for bit.
    np.testing.assert_array_equal(r.saliency.astype(np.float32), props["quality"])
    np.testing.assert_array_equal(r.curvature.astype(np.float32), props["curvature"])
    assert r.raw.shape == (5, len(V))
    for i in range(5):
        np.testing.assert_array_equal(r.raw[i].astype(np.float32), props[f"saliency_raw_{i}"])
    # Statistics of the doubles: the CLI's 9 digits exactly.
    for key, value in stats(r.saliency[r.is_point]).items():
        assert g9(value) == j["saliency"][key], key


def test_saliency_options_equal_cli(mesh_path, cli, tmp_path):
    path = mesh_path("bunny_3k.off")
    out = tmp_path / "sal.ply"
    cli("saliency", path, "-o", out, "--backend", "cpu", "--scales", "1.5,3", "--eps-frac", "0.004",
        "--method", "fast", "-q")
    V, F = meshsal.load(str(path))
    r = meshsal.saliency(V, F, backend="cpu", scales=[1.5, 3], eps_frac=0.004, method="fast")
    _, _, props = meshsal.load(str(out), properties=True)
    assert r.method == "fast"
    np.testing.assert_array_equal(r.saliency.astype(np.float32), props["quality"])
    # The string form of scales is the CLI's.
    r2 = meshsal.saliency(V, F, backend="cpu", scales="1.5,3", eps_frac=0.004, method="fast")
    np.testing.assert_array_equal(r.saliency, r2.saliency)


def test_fast_raw_maps_only_when_asked(mesh_path, cli, tmp_path):
    # The fast CPU path keeps no raw maps unless they are returned (--dump-scales,
    # raw_maps=True); S is the same either way, in the module and in the CLI's files.
    path = mesh_path("bunny_36k.obj")
    V, F = meshsal.load(str(path))
    lean = meshsal.saliency(V, F, backend="cpu", method="fast")
    full = meshsal.saliency(V, F, backend="cpu", method="fast", raw_maps=True)
    assert lean.raw is None
    assert full.raw.shape == (5, len(V))
    assert full.raw.max() > 0
    np.testing.assert_array_equal(lean.saliency, full.saliency)
    cli("saliency", path, "-o", tmp_path / "a.ply", "--backend", "cpu", "--method", "fast", "-q")
    cli("saliency", path, "-o", tmp_path / "b.ply", "--backend", "cpu", "--method", "fast", "--dump-scales", "-q")
    _, _, a = meshsal.load(str(tmp_path / "a.ply"), properties=True)
    _, _, b = meshsal.load(str(tmp_path / "b.ply"), properties=True)
    np.testing.assert_array_equal(a["quality"], b["quality"])
    np.testing.assert_array_equal(a["quality"], lean.saliency.astype(np.float32))
    np.testing.assert_array_equal(b["saliency_raw_2"], full.raw[2].astype(np.float32))


def test_tiled_saliency_equals_cli_and_untiled(mesh_path, cli, tmp_path):
    # tiles=N is `--tiles N`, and (exact method) the untiled map bit for bit; the CLI's
    # out-of-core run writes the same values.
    path = mesh_path("bunny_36k.obj")
    out, ooc = tmp_path / "tiled.ply", tmp_path / "ooc.ply"
    j = cli.json("saliency", path, "-o", out, "--backend", "cpu", "--tiles", "4", "--json")
    cli("saliency", path, "-o", ooc, "--backend", "cpu", "--memory-limit", "200M", "-q")
    V, F = meshsal.load(str(path))
    r = meshsal.saliency(V, F, backend="cpu", tiles=4)
    whole = meshsal.saliency(V, F, backend="cpu")
    assert r.tiles == j["tiles"] and r.tiles > 1 and whole.tiles == 0
    np.testing.assert_array_equal(r.saliency, whole.saliency)
    np.testing.assert_array_equal(r.curvature, whole.curvature)
    for p in (out, ooc):
        _, _, props = meshsal.load(str(p), properties=True)
        np.testing.assert_array_equal(r.saliency.astype(np.float32), props["quality"])


def test_out_of_core_files_equal_cli(mesh_path, cli, tmp_path):
    # saliency_file and simplify_file are `--memory-limit` runs: the CLI's bytes.
    src = mesh_path("bunny_3k.off")
    V, F = meshsal.load(str(src))
    path = tmp_path / "in.ply"
    meshsal.save(str(path), V, F)
    a, b = tmp_path / "a.ply", tmp_path / "b.ply"
    cli("saliency", path, "-o", a, "--memory-limit", "100M", "--method", "exact", "-q")
    r = meshsal.saliency_file(path, b, memory_limit="100M", method="exact")
    assert a.read_bytes() == b.read_bytes()
    assert r["vertices"] == len(V) and r["faces"] == len(F) and r["tiles"] >= 1
    c, d = tmp_path / "c.ply", tmp_path / "d.ply"
    j = cli.json("simplify", path, "-o", c, "--ratio", "0.2", "--memory-limit", "100M", "--tiles", "2", "--json")
    s = meshsal.simplify_file(path, d, ratio=0.2, memory_limit=100 << 20, tiles=2)
    assert c.read_bytes() == d.read_bytes()
    assert s["output_faces"] == j["output_faces"] and s["tiles"] == j["tiles"] == 2
    assert s["groups_at_once"] == j["groups_at_once"] >= 1
    # In memory, tiled: the weights from S in the same tiles, as the CLI's (the fast method's
    # tiled S differs from the whole one's in the last bits).
    e, f = tmp_path / "e.ply", tmp_path / "f.ply"
    cli("simplify", path, "-o", e, "--ratio", "0.2", "--tiles", "3", "--method", "fast", "--backend", "cpu", "-q")
    meshsal.simplify_file(path, f, ratio=0.2, tiles=3, method="fast", backend="cpu")
    assert e.read_bytes() == f.read_bytes()
    with pytest.raises(ValueError):
        meshsal.simplify_file(path, d, ratio=0.2, target_faces=10)
    with pytest.raises(meshsal.Error, match="smallest workable limit"):
        meshsal.simplify_file(path, d, ratio=0.2, memory_limit="1M")


@pytest.mark.parametrize("weights", ["saliency", "none"])
def test_simplify_equals_cli(weights, mesh_path, cli, tmp_path):
    # A mesh without texture coordinates: the CLI carries OBJ attributes (and splits vertices
    # at UV seams), the module's load() and simplify() take positions only.
    path = mesh_path("max_planck_5k.obj")
    out = tmp_path / "simp.ply"
    j = cli.json("simplify", path, "-o", out, "--ratio", "0.1", "--weights", weights, "--backend", "cpu", "--json")
    V, F = meshsal.load(str(path))
    r = meshsal.simplify(V, F, ratio=0.1, weights=weights, backend="cpu")
    V2, F2 = meshsal.load(str(out))
    # float64 in, float64 out; the CLI's PLY holds float32 (enough, 1e-7 of the diagonal).
    assert r.vertices.dtype == np.float64 and V2.dtype == np.float32
    np.testing.assert_array_equal(r.vertices.astype(np.float32), V2)
    np.testing.assert_array_equal(r.faces, F2)
    assert (r.output_faces, r.target_faces, r.collapses, r.reached) == \
        (j["output_faces"], j["target_faces"], j["collapses"], j["reached"])
    if weights == "saliency":
        assert g9(r.alpha) == j["alpha"]


def test_simplify_saliency_from_equals_cli(mesh_path, cli, tmp_path):
    path = mesh_path("bunny_3k.off")
    sal, out = tmp_path / "sal.ply", tmp_path / "simp.ply"
    cli("saliency", path, "-o", sal, "--backend", "cpu", "-q")
    cli("simplify", path, "-o", out, "--target-faces", "1000", "--saliency-from", sal, "--lambda", "50", "-q")
    V, F = meshsal.load(str(path))
    S = meshsal.load(str(sal), properties=True)[2]["quality"]
    r = meshsal.simplify(V, F, 1000, saliency=S, lambda_=50)
    V2, F2 = meshsal.load(str(out))
    # float64 in, float64 out; the CLI's PLY holds float32 (enough, 1e-7 of the diagonal).
    assert r.vertices.dtype == np.float64 and V2.dtype == np.float32
    np.testing.assert_array_equal(r.vertices.astype(np.float32), V2)
    np.testing.assert_array_equal(r.faces, F2)


@pytest.mark.parametrize("up", ["y", "z"])
def test_best_view_equals_cli(up, mesh_path, cli):
    path = mesh_path("max_planck_5k.obj")
    j = cli.json("viewpoint", path, "--views", "200", "--backend", "cpu", "--up", up, "--resolution", "256")
    V, F = meshsal.load(str(path))
    b = meshsal.best_view(V, F, views=200, backend="cpu", up=up, resolution=256)
    assert b["device"] == j["device"]
    assert b["views_evaluated"] == j["views_evaluated"]
    assert float("%.9g" % b["visible_score"]) == j["visible_score"]
    assert g9(b["visible_fraction"]) == j["visible_fraction"]
    for key in ["theta", "phi", "theta_deg", "phi_deg"]:
        assert g9(b[key]) == j[key], key
        assert g9(b["exhaustive"][key]) == j["exhaustive"][key], key
    assert [g9(x) for x in b["direction"]] == j["direction"]


def test_error_message_equals_cli(cli, tmp_path):
    bad = tmp_path / "bad.off"
    bad.write_text("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n")
    r = cli("saliency", bad, "-o", tmp_path / "out.ply", check=False)
    assert r.returncode == 1
    with pytest.raises(meshsal.Error) as e:
        meshsal.load(str(bad))
    assert "error: " + str(e.value) == r.stderr.strip()
    assert isinstance(e.value, ValueError) and isinstance(e.value, RuntimeError)


def test_gpu_saliency_equals_cli(mesh_path, cli, tmp_path):
    # The Vulkan backend from inside the module (lavapipe here): the CLI's --backend gpu result.
    if not meshsal.built_with_vulkan():
        pytest.skip("built without Vulkan")
    try:
        meshsal.devices()
    except meshsal.Error as e:
        pytest.skip(str(e))
    path = mesh_path("bunny_3k.off")
    out = tmp_path / "sal.ply"
    j = cli.json("saliency", path, "-o", out, "--backend", "gpu", "--json")
    V, F = meshsal.load(str(path))
    r = meshsal.saliency(V, F, backend="gpu")
    _, _, props = meshsal.load(str(out), properties=True)
    assert r.backend == j["device"] and r.precision == j["precision"]
    np.testing.assert_array_equal(r.saliency.astype(np.float32), props["quality"])


def test_best_view_curvature_score_equals_cli(mesh_path, cli):
    # The paper's baseline, --score curvature, is abs(curvature) of the saliency result.
    path = mesh_path("max_planck_5k.obj")
    j = cli.json("viewpoint", path, "--score", "curvature", "--backend", "cpu", "--resolution", "256")
    V, F = meshsal.load(str(path))
    H = meshsal.saliency(V, F, backend="cpu").curvature
    b = meshsal.best_view(V, F, np.abs(H), backend="cpu", resolution=256)
    assert float("%.9g" % b["visible_score"]) == j["visible_score"]
    assert g9(b["visible_fraction"]) == j["visible_fraction"]
    assert (g9(b["theta"]), g9(b["phi"])) == (j["theta"], j["phi"])


def test_gltf_save_equals_cli(mesh_path, cli, tmp_path):
    # `meshsal saliency -o x.glb` and meshsal.save(x.glb, V, F, S): the same bytes; the GLB
    # holds the model's coordinates as floats (no added node transform), as a float PLY does:
    # it reads back as the PLY does, with the same saliency.
    path = mesh_path("bunny_3k.off")
    cli.json("saliency", path, "-o", tmp_path / "cli.glb", "--backend", "cpu", "--json")
    V, F = meshsal.load(str(path))
    r = meshsal.saliency(V, F, backend="cpu")
    meshsal.save(str(tmp_path / "py.glb"), V, F, r.saliency)
    assert (tmp_path / "py.glb").read_bytes() == (tmp_path / "cli.glb").read_bytes()
    V2, F2 = meshsal.load(str(tmp_path / "py.glb"))
    np.testing.assert_array_equal(F2, F)
    np.testing.assert_allclose(V2, V, rtol=0, atol=1e-6)
    meshsal.save(str(tmp_path / "py.ply"), V, F)
    V3, F3 = meshsal.load(str(tmp_path / "py.ply"))
    np.testing.assert_array_equal(V2, V3)
    np.testing.assert_array_equal(meshsal.saliency(V2, F2, backend="cpu").saliency,
                                  meshsal.saliency(V3, F3, backend="cpu").saliency)
    np.testing.assert_allclose(meshsal.saliency(V2, F2, backend="cpu").saliency, r.saliency, rtol=0,
                               atol=1e-4 * r.saliency.max())


def test_lod_equals_cli(mesh_path, cli, tmp_path):
    # simplify(lod=...) and `meshsal simplify --lod`: the same chain, level by level.
    path = mesh_path("bunny_3k.off")
    cli("simplify", path, "-o", tmp_path / "cli.obj", "--lod", "0.5,0.1", "--backend", "cpu", "-q")
    V, F = meshsal.load(str(path))
    levels = meshsal.simplify(V, F, lod=[0.5, 0.1], backend="cpu")
    assert len(levels) == 2
    assert levels[0].target_faces in (len(F) // 2, (len(F) + 1) // 2)  # a closed mesh may end one face above
    assert levels[1].target_faces == int(0.1 * len(F) + 0.5)  # a ratio of the input's faces
    for i, r in enumerate(levels, start=1):
        V2, F2 = meshsal.load(str(tmp_path / f"cli_lod{i}.obj"))
        np.testing.assert_array_equal(F2, r.faces)
        np.testing.assert_allclose(V2, r.vertices, rtol=0, atol=1e-6)
        assert "quality" in r.attributes
    # The string form, and what lod does not go with.
    assert [r.output_faces for r in meshsal.simplify(V, F, lod="0.5,0.1", backend="cpu")] == [r.output_faces for r in levels]
    with pytest.raises(ValueError, match="lod names every level"):
        meshsal.simplify(V, F, ratio=0.5, lod=[0.2])
    with pytest.raises(ValueError, match=r"level 2 \(0.5\) is not below level 1 \(0.2\)"):
        meshsal.simplify(V, F, lod=[0.2, 0.5], backend="cpu")
    with pytest.raises(ValueError, match="not both"):  # which has fewer faces depends on the mesh
        meshsal.simplify(V, F, lod=[0.5, 300], backend="cpu")
    with pytest.raises(ValueError, match="lod ratios must be in"):
        meshsal.simplify(V, F, lod=[1.5])
