# The module at parity with the CLI (issue 22): every option of `meshsal simplify` and
# `meshsal saliency`, save() writing the CLI's bytes, paths and their errors, short
# TypeErrors, a docstring line for every keyword.
import errno
import inspect
import os
from pathlib import Path

import numpy as np
import pytest

import meshsal


def same_bytes(a, b):
    assert Path(a).read_bytes() == Path(b).read_bytes()


# --- simplify --------------------------------------------------------------------------

@pytest.mark.parametrize("cli_args,kwargs", [
    (["--ratio", "0.2", "--weights", "balanced"], dict(ratio=0.2, weights="balanced")),
    (["--target-faces", "1500", "--weights", "balanced", "--lambda", "7", "--alpha-percentile", "40",
      "--weight-floor", "0.01"],
     dict(target_faces=1500, weights="balanced", lambda_=7, alpha_percentile=40, weight_floor=0.01)),
    (["--target-error", "0.5", "--weights", "none"], dict(target_error=0.5, weights="none")),
    (["--ratio", "0.3", "--target-error", "0.2", "--lock-border", "--method", "fast"],
     dict(ratio=0.3, target_error=0.2, lock_border=True, method="fast")),
])
def test_simplify_options_equal_cli(cli_args, kwargs, mesh_path, cli, tmp_path):
    path = mesh_path("bunny_3k.off")
    out, mine = tmp_path / "cli.ply", tmp_path / "py.ply"
    j = cli.json("simplify", path, "-o", out, "--backend", "cpu", "--json", *cli_args)
    V, F = meshsal.load(path)
    r = meshsal.simplify(V, F, backend="cpu", **kwargs)
    V2, F2 = meshsal.load(out)
    # float64 in (the OFF's decimals), float64 out; the CLI's PLY holds them in float32.
    assert r.vertices.dtype == np.float64 and V2.dtype == np.float32
    np.testing.assert_array_equal(r.vertices.astype(np.float32), V2)
    np.testing.assert_array_equal(r.faces, F2)
    assert (r.output_faces, r.target_faces, r.collapses, r.reached) == \
        (j["output_faces"], j["target_faces"], j["collapses"], j["reached"])
    assert r.weights == j["weights"]
    assert float("%.9g" % r.error_percent) == j["error_percent"]
    if r.weights != "none":
        assert (r.lambda_, r.alpha_percentile, r.weight_floor) == \
            (j["lambda"], j["alpha_percentile"], j["weight_floor"])
        assert "quality" in r.attributes  # S, as the CLI's PLY carries it
    # The whole file: save() with the result's attributes writes the CLI's bytes.
    meshsal.save(mine, r.vertices, r.faces, attributes=r.attributes, position_vertex=r.position_vertex)
    same_bytes(out, mine)


@pytest.mark.parametrize("ext", [".obj", ".ply"])
def test_simplify_attributes_equal_cli(ext, mesh_path, cli, tmp_path):
    # spot has texture coordinates and UV seams: the CLI carries them, and so does the module
    # with load(attributes=True).
    path = mesh_path("spot_3k.obj")
    out, mine = tmp_path / ("cli" + ext), tmp_path / ("py" + ext)
    cli("simplify", path, "-o", out, "--ratio", "0.25", "--backend", "cpu", "-q")
    V, F, A, pv = meshsal.load(path, attributes=True)
    assert set(A) == {"u", "v"} and pv is not None and len(pv) == len(V) > len(meshsal.load(path)[0])
    r = meshsal.simplify(V, F, ratio=0.25, backend="cpu", attributes=A, position_vertex=pv)
    assert set(r.attributes) == {"u", "v", "quality"}
    assert all(a.shape == (len(r.vertices),) and a.dtype == np.float32 for a in r.attributes.values())
    meshsal.save(mine, r.vertices, r.faces, attributes=r.attributes, position_vertex=r.position_vertex)
    same_bytes(out, mine)


def test_simplify_target_rules_and_default_weighting(sphere):
    V, F = sphere
    with pytest.raises(ValueError, match="give target_faces, ratio or target_error"):
        meshsal.simplify(V, F)
    with pytest.raises(ValueError, match="only one of target_faces and ratio"):
        meshsal.simplify(V, F, 100, ratio=0.5)
    with pytest.raises(ValueError, match="weights must be 'saliency', 'balanced', 'none'"):
        meshsal.simplify(V, F, ratio=0.5, weights="paper")
    with pytest.raises(ValueError, match="target_error must be in"):
        meshsal.simplify(V, F, target_error=101)
    r = meshsal.simplify(V, F, target_error=0.5, weights="none", backend="cpu")
    assert r.error_percent <= 0.5 and r.output_faces < len(F)
    # The default weighting is the library's (kDefaultWeighting), shown in the signature.
    r = meshsal.simplify(V, F, ratio=0.5, backend="cpu")
    assert r.weights == inspect.signature(meshsal.simplify).parameters["weights"].default == "balanced"
    assert r.lambda_ == 3 and r.alpha_percentile == 50
    p = meshsal.simplify(V, F, ratio=0.5, backend="cpu", weights="saliency")  # the paper's recipe
    assert (p.lambda_, p.alpha_percentile) == (100, 30)


def test_simplify_attributes_checked(sphere):
    V, F = sphere
    n = len(V)
    with pytest.raises(TypeError, match="attributes must be a dict"):
        meshsal.simplify(V, F, ratio=0.5, weights="none", attributes=[1, 2])
    with pytest.raises(ValueError, match=r"attributes\['u'\] must have shape"):
        meshsal.simplify(V, F, ratio=0.5, weights="none", attributes={"u": np.zeros(n + 1)})
    with pytest.raises(ValueError, match="bad name"):
        meshsal.simplify(V, F, ratio=0.5, weights="none", attributes={"a b": np.zeros(n)})
    with pytest.raises(ValueError, match=r"position_vertex: entry 0 must be a whole number in \[0, 0\], got 2$"):
        meshsal.simplify(V, F, ratio=0.5, weights="none", position_vertex=np.full(n, 2))
    # Normals are carried and renormalised; a plain channel is interpolated.
    nrm = V / np.linalg.norm(V, axis=1)[:, None]
    r = meshsal.simplify(V, F, ratio=0.3, weights="none",
                         attributes={"nx": nrm[:, 0], "ny": nrm[:, 1], "nz": nrm[:, 2], "h": V[:, 1]})
    assert set(r.attributes) == {"nx", "ny", "nz", "h"}
    length = np.sqrt(r.attributes["nx"] ** 2 + r.attributes["ny"] ** 2 + r.attributes["nz"] ** 2)
    np.testing.assert_allclose(length, 1, atol=1e-5)
    assert r.position_vertex is None


# --- saliency ----------------------------------------------------------------------------

def test_saliency_has_every_cli_option():
    # `meshsal saliency` options: --backend --precision --method --device --scales --eps-frac
    # --dump-scales (raw_maps) --threads; and Sm (smoothed), which simplification uses.
    params = inspect.signature(meshsal.saliency).parameters
    for name in ["backend", "precision", "method", "device", "scales", "eps_frac", "raw_maps", "threads",
                 "smoothed"]:
        assert name in params, name


# --- save / load -------------------------------------------------------------------------

@pytest.mark.parametrize("name", ["bunny_3k.off", "spot_3k.obj"])
def test_save_saliency_equals_cli(name, mesh_path, cli, tmp_path):
    path = mesh_path(name)
    out, mine = tmp_path / "cli.ply", tmp_path / "py.ply"
    cli("saliency", path, "-o", out, "--backend", "cpu", "-q")
    V, F = meshsal.load(path)
    r = meshsal.saliency(V, F, backend="cpu")
    meshsal.save(mine, V, F, r.saliency)
    same_bytes(out, mine)
    # And back: the saliency PLY loads with its quality.
    V2, F2, props = meshsal.load(mine, properties=True)
    np.testing.assert_array_equal(V2, V.astype(np.float32))  # the text's decimals, in a float PLY
    np.testing.assert_array_equal(props["quality"], r.saliency.astype(np.float32))


def test_save_plain_mesh_equals_cli_simplify_unchanged(mesh_path, cli, tmp_path):
    # A target above the face count: the CLI writes the mesh as loaded (with its attributes).
    path = mesh_path("spot_3k.obj")
    for ext in [".obj", ".ply"]:
        out, mine = tmp_path / ("cli" + ext), tmp_path / ("py" + ext)
        cli("simplify", path, "-o", out, "--target-faces", "100000", "-q")
        V, F, A, pv = meshsal.load(path, attributes=True)
        meshsal.save(mine, V, F, attributes=A, position_vertex=pv)
        same_bytes(out, mine)


def test_save_and_load_round_trip(sphere, tmp_path):
    V, F = sphere
    for ext in [".obj", ".ply", ".PLY", ".off"]:
        p = tmp_path / ("ball" + ext)
        meshsal.save(p, V, F)
        V2, F2 = meshsal.load(p)  # an OBJ's decimals come back float64: the same floats
        np.testing.assert_array_equal(V2.astype(np.float32), V.astype(np.float32))
        np.testing.assert_array_equal(F2, F)
    with pytest.raises(meshsal.Error, match=r"ball.xyz: path must be a \.ply, \.gltf, \.glb, \.obj, \.off or \.stl file"):
        meshsal.save(tmp_path / "ball.xyz", V, F)  # the library's check (a ValueError)
    meshsal.save(tmp_path / "ball.stl", V, F)  # STL: corners by value, welded again in order of first use
    assert meshsal.load(tmp_path / "ball.stl")[1].shape == F.shape
    # S where the format keeps it: its colours in an OBJ, nothing in an STL (refused).
    meshsal.save(tmp_path / "ball_s.obj", V, F, np.arange(len(V), dtype=float))
    assert "red" in meshsal.load(tmp_path / "ball_s.obj", attributes=True)[2]
    with pytest.raises(ValueError, match="STL has no place for saliency"):
        meshsal.save(tmp_path / "ball_s.stl", V, F, np.zeros(len(V)))
    with pytest.raises(ValueError, match=r"saliency must have shape"):
        meshsal.save(tmp_path / "ball.ply", V, F, np.zeros(3))
    with pytest.raises(ValueError, match="give properties=True or attributes=True"):
        meshsal.load(tmp_path / "ball.ply", properties=True, attributes=True)


# --- paths and their errors --------------------------------------------------------------

def test_missing_file_raises_file_not_found(tmp_path, sphere):
    missing = tmp_path / "nope.obj"
    for p in [missing, str(missing)]:
        with pytest.raises(FileNotFoundError) as e:
            meshsal.load(p)
        assert isinstance(e.value, meshsal.Error) and isinstance(e.value, meshsal.FileNotFoundError)
        assert e.value.errno == errno.ENOENT and e.value.filename == p
        assert str(e.value).startswith(str(missing) + ": ") and "\n" not in str(e.value)
    V, F = sphere
    with pytest.raises(FileNotFoundError) as e:
        meshsal.save(tmp_path / "no" / "such" / "folder.ply", V, F)
    assert isinstance(e.value, meshsal.Error) and e.value.errno == errno.ENOENT
    # Other bad input stays meshsal.Error (a ValueError), not an OSError.
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nf 1 2 3\n")
    with pytest.raises(meshsal.Error) as e:
        meshsal.load(bad)
    assert not isinstance(e.value, OSError)


@pytest.mark.skipif(not hasattr(os, "geteuid") or os.geteuid() == 0, reason="root reads and writes any file")
def test_unreadable_file_raises_permission_error(tmp_path, sphere):
    p = tmp_path / "locked.obj"
    p.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    p.chmod(0)
    with pytest.raises(PermissionError) as e:
        meshsal.load(p)
    assert isinstance(e.value, meshsal.Error) and e.value.errno == errno.EACCES
    folder = tmp_path / "ro"
    folder.mkdir()
    folder.chmod(0o555)
    V, F = sphere
    with pytest.raises(PermissionError):
        meshsal.save(folder / "out.ply", V, F)


_AS_NOBODY = r"""
import errno, sys
import numpy as np
import meshsal
folder = sys.argv[1]
try:
    meshsal.load(folder + "/locked.obj")
    print("no error")
except PermissionError as e:
    assert isinstance(e, meshsal.Error) and isinstance(e, meshsal.PermissionError)
    assert e.errno == errno.EACCES and e.filename == folder + "/locked.obj"
    print("load:", e)
try:
    meshsal.save(folder + "/out.ply", np.eye(3), np.array([[0, 1, 2]]))
    print("no error")
except PermissionError as e:
    assert isinstance(e, meshsal.Error) and e.errno == errno.EACCES
    print("save:", e)
"""


@pytest.mark.skipif(not hasattr(os, "geteuid") or os.geteuid() != 0, reason="needs root to run a check as nobody")
def test_unreadable_file_raises_permission_error_as_nobody():
    # Root reads and writes any file: the check runs in a child process as nobody, on a
    # file it may not read in a folder it may not write.
    import shutil
    import subprocess
    import sys
    import tempfile
    folder = tempfile.mkdtemp(prefix="meshsal_perm_")
    try:
        os.chmod(folder, 0o755)
        locked = Path(folder) / "locked.obj"
        locked.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
        locked.chmod(0)

        def as_nobody():
            os.setgid(65534)
            os.setgroups([])
            os.setuid(65534)

        # (LD_PRELOAD and the sanitizers' options: tools/sanitize.sh preloads their runtimes.)
        env = {k: v for k, v in os.environ.items()
               if k in ("PYTHONPATH", "PATH", "LD_PRELOAD", "ASAN_OPTIONS", "UBSAN_OPTIONS", "LSAN_OPTIONS")}
        env["PYTHONDONTWRITEBYTECODE"] = "1"
        r = subprocess.run([sys.executable, "-c", _AS_NOBODY, folder], env=env, preexec_fn=as_nobody,
                           capture_output=True, text=True, timeout=120)
        if "No module named" in r.stderr or "Permission denied: '" in r.stderr:
            pytest.skip("nobody cannot import this build of meshsal: " + r.stderr.strip().splitlines()[-1])
        assert r.returncode == 0, r.stderr
        assert r.stdout.splitlines() == [
            f"load: {locked}: cannot open: Permission denied",
            f"save: {folder}/out.ply: cannot write: folder '{folder}' is not writable (Permission denied)"]
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def test_permission_error_class():
    # The class that an unreadable file raises (root, as the tests run, reads any file).
    assert issubclass(meshsal.PermissionError, PermissionError)
    assert issubclass(meshsal.PermissionError, meshsal.Error)
    assert issubclass(meshsal.FileNotFoundError, FileNotFoundError)
    assert str(meshsal.PermissionError("x.obj: cannot open: Permission denied")) == \
        "x.obj: cannot open: Permission denied"


# --- short errors --------------------------------------------------------------------------

@pytest.mark.parametrize("call,names", [
    (lambda V, F: meshsal.simplify(V, F, ratio=0.5, no_such_option=1), ["no_such_option"]),
    (lambda V, F: meshsal.saliency(V, F, eps=0.01), ["eps"]),
    (lambda V, F: meshsal.saliency(V, F, smoothed="yes"), ["smoothed"]),
    (lambda V, F: meshsal.saliency(V, F, eps_frac="big"), ["eps_frac", "number"]),
    (lambda V, F: meshsal.saliency(V, F, eps_frac=V), ["eps_frac", "ndarray"]),
    (lambda V, F: meshsal.saliency(V, F, threads=1.5), ["threads", "integer"]),  # -1: a ValueError
    (lambda V, F: meshsal.saliency(V, F, method=3), ["method", "str"]),
    (lambda V, F: meshsal.simplify(V, F, ratio=0.5, lock_border=V), ["lock_border"]),
    (lambda V, F: meshsal.simplify(V, F, ratio=0.5, lambda_="x"), ["lambda_", "number"]),
    (lambda V, F: meshsal.simplify(V, F, ratio=V), ["ratio", "single number"]),
    (lambda V, F: meshsal.simplify(V, F, target_error=V), ["target_error"]),
    (lambda V, F: meshsal.saliency(V), ["faces"]),
    (lambda V, F: meshsal.saliency(V, F, V), ["positional"]),
    (lambda V, F: meshsal.render(V, F, sizee=64), ["sizee"]),
    (lambda V, F: meshsal.best_view(V, F, views="many"), ["views"]),
    (lambda V, F: meshsal.save("x.ply", V, F, colour=V), ["colour"]),
    (lambda V, F: meshsal.load(V), ["path"]),
])
def test_argument_errors_are_short(call, names, sphere):
    V, F = sphere
    with pytest.raises(TypeError) as e:
        call(V, F)
    message = str(e.value)
    assert "\n" not in message and len(message) < 200, message
    assert "array(" not in message and "Invoked with" not in message, message
    for name in names:
        assert name in message, message


def test_signatures_and_docstrings_name_every_keyword():
    for f in [meshsal.load, meshsal.save, meshsal.saliency, meshsal.simplify]:
        params = inspect.signature(f).parameters
        doc = f.__doc__
        body = doc.split("\n\n", 1)[1]  # after the signature
        for name in params:
            assert name in body, (f.__name__, name)
