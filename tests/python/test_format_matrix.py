# The round-trip matrix's Python column (issue 37): saliency_file and simplify_file run the
# library's one pipeline, so for every reader format x writer format they write the bytes
# `meshsal saliency` and `meshsal simplify` (with --lod too) write; load(attributes=True)
# reads S back from the formats that keep its value.
import numpy as np
import pytest

import meshsal

FORMATS = ["ply", "gltf", "glb", "obj", "off", "stl"]


@pytest.fixture
def inputs(tmp_path, sphere):
    """The sphere with normals, texture coordinates, colours and a scalar, in every format."""
    V, F = sphere
    n = len(V)
    N = V / np.linalg.norm(V, axis=1, keepdims=True)
    attrs = {"nx": N[:, 0], "ny": N[:, 1], "nz": N[:, 2], "u": (V[:, 0] + 1) / 2, "v": (V[:, 1] + 1) / 2,
             "red": np.round(120 + 100 * V[:, 0]), "green": np.full(n, 200.0), "blue": np.round(120 + 100 * V[:, 2]),
             "confidence": np.arange(n) % 7.0}
    attrs = {k: np.asarray(a, dtype=np.float32) for k, a in attrs.items()}
    paths = {}
    for f in FORMATS:
        paths[f] = tmp_path / ("in." + f)
        meshsal.save(paths[f], V, F, attributes=attrs)
    return paths


def same_file(a, b):
    """Byte equality, an OBJ's mtllib line (it names the .mtl after its own file) aside."""
    da, db = a.read_bytes(), b.read_bytes()
    if a.suffix == ".obj":
        da = da.replace(b"mtllib " + a.with_suffix(".mtl").name.encode(), b"mtllib X")
        db = db.replace(b"mtllib " + b.with_suffix(".mtl").name.encode(), b"mtllib X")
    return da == db


@pytest.mark.parametrize("reader", FORMATS)
def test_python_writes_the_commands_bytes(reader, inputs, cli, tmp_path):
    src = inputs[reader]
    for writer in FORMATS:
        cli_out, py_out = tmp_path / f"cli_s_{reader}.{writer}", tmp_path / f"py_s_{reader}.{writer}"
        if writer == "stl":
            with pytest.raises(meshsal.Error, match="STL has no place for saliency"):
                meshsal.saliency_file(src, py_out, backend="cpu")
        else:
            cli("saliency", src, "-o", cli_out, "--backend", "cpu", "-q")
            meshsal.saliency_file(src, py_out, backend="cpu")
            assert same_file(cli_out, py_out), (reader, writer, "saliency")
        cli_out, py_out = tmp_path / f"cli_r_{reader}.{writer}", tmp_path / f"py_r_{reader}.{writer}"
        cli("simplify", src, "-o", cli_out, "--ratio", "0.5", "--backend", "cpu", "-q")
        r = meshsal.simplify_file(src, py_out, ratio=0.5, backend="cpu")
        assert same_file(cli_out, py_out), (reader, writer, "simplify")
        assert r["outputs"][0] == str(py_out)
        cli_out, py_out = tmp_path / f"cli_l_{reader}.{writer}", tmp_path / f"py_l_{reader}.{writer}"
        cli("simplify", src, "-o", cli_out, "--lod", "0.5", "--backend", "cpu", "-q")
        r = meshsal.simplify_file(src, py_out, lod=[0.5], backend="cpu")
        files = r["outputs"]
        assert len(r["levels"]) == 1
        if writer in ("glb", "gltf"):
            assert same_file(cli_out, py_out), (reader, writer, "lod")
        else:
            level = py_out.with_name(py_out.stem + "_lod1." + writer)
            assert files[0] == str(level)
            assert same_file(cli_out.with_name(cli_out.stem + "_lod1." + writer), level), (reader, writer, "lod")


def test_load_reads_saliency_back_from_ply_and_gltf(inputs, tmp_path):
    src = inputs["ply"]
    S = {}
    for f in ("ply", "glb", "gltf"):
        out = tmp_path / ("s." + f)
        meshsal.saliency_file(src, out, backend="cpu")
        S[f] = meshsal.load(out, attributes=True)[2]["quality"]
    np.testing.assert_array_equal(S["ply"], S["glb"])
    np.testing.assert_array_equal(S["ply"], S["gltf"])
    assert S["ply"].max() > 0
