# Issue 36 (4, 5): Python writes as the CLI does (the library's output check: never the
# input, through a link either, the format from the suffix or refused), and takes its
# arguments as Python does: sequences held as owned references (lists, tuples, numpy arrays,
# ranges and generators), bytes and 0-d arrays refused as sequences, integers out of range
# a ValueError naming the value, bools no numbers, a device index that does not exist a
# ValueError.
import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

import meshsal


@pytest.fixture
def read_only_input(tmp_path, sphere):
    """A small mesh as a binary PLY, read-only: (path, its bytes)."""
    V, F = sphere
    p = tmp_path / "in.ply"
    meshsal.save(p, V, F)
    p.chmod(0o444)
    return p, p.read_bytes()


def out_of_core_calls():
    return [
        ("saliency_file", lambda i, o, **k: meshsal.saliency_file(i, o, method="fast", threads=1, **k)),
        ("simplify_file", lambda i, o, **k: meshsal.simplify_file(i, o, ratio=0.5, weights="none", threads=1, **k)),
    ]


# --- 4. writes -------------------------------------------------------------------------

@pytest.mark.parametrize("name,call", out_of_core_calls())
def test_file_calls_never_write_over_their_input_through_a_link(tmp_path, read_only_input, name, call):
    src, before = read_only_input
    link, hard = tmp_path / "link.ply", tmp_path / "hard.ply"
    link.symlink_to(src)
    os.link(src, hard)
    for out in (src, link, hard):
        with pytest.raises(meshsal.Error, match=rf"^{out}: the output is the input file '{src}' \(an output never "
                                                r"replaces an input\)$"):
            call(src, out)
    assert src.read_bytes() == before
    assert link.is_symlink()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["hard.ply", "in.ply", "link.ply"]


@pytest.mark.parametrize("name,call", out_of_core_calls())
def test_file_calls_refuse_a_name_that_is_not_a_ply(tmp_path, read_only_input, name, call):
    # Under a memory limit the file written is a binary PLY; in memory every mesh format
    # is written, as the CLI writes it; a name of no format is refused either way.
    src, before = read_only_input
    for ext in (".obj", ".glb", ".gltf", ".ply.gz"):
        out = tmp_path / ("out" + ext)
        with pytest.raises(ValueError, match=r"^memory_limit writes a binary PLY: give an output name ending in \.ply$"):
            call(src, out, memory_limit="100M")
        assert not out.exists()
    for ext in (".obj", ".glb", ".off"):
        call(src, tmp_path / ("in_memory" + ext))
        assert (tmp_path / ("in_memory" + ext)).exists()
    with pytest.raises(meshsal.Error, match=r"the output must be a \.ply, \.gltf, \.glb, \.obj, \.off or \.stl file$"):
        call(src, tmp_path / "out.ply.gz")
    assert src.read_bytes() == before
    call(src, tmp_path / "out.PLY")  # the suffix's case does not matter
    assert (tmp_path / "out.PLY").read_bytes().startswith(b"ply\nformat binary_little_endian")


def test_file_calls_raise_file_errors_for_the_output_folder(tmp_path, read_only_input):
    src, _ = read_only_input
    out = tmp_path / "missing" / "out.ply"
    with pytest.raises(meshsal.FileNotFoundError) as e:
        meshsal.saliency_file(src, out)
    assert e.value.filename == out


def test_save_goes_through_the_library_check(tmp_path, sphere):
    V, F = sphere
    for name in ("out.ply.gz", "out", "out.txt"):
        p = tmp_path / name
        with pytest.raises(meshsal.Error,
                           match=rf"^{p}: path must be a \.ply, \.gltf, \.glb, \.obj, \.off or \.stl file$"):
            meshsal.save(p, V, F)
        assert not p.exists()
    # The check's housekeeping: a temporary a killed writer left beside the output goes.
    stale = tmp_path / "out.ply.tmp.AbC123"
    stale.write_bytes(b"half a file")
    meshsal.save(tmp_path / "out.ply", V, F)
    assert not stale.exists()
    assert meshsal.load(tmp_path / "out.ply")[1].shape == F.shape


# --- 5. arguments ----------------------------------------------------------------------

def test_lod_takes_any_sequence_of_levels_held_as_owned_references(sphere):
    # A child interpreter: a level read through a borrowed handle crashed it (numpy's items
    # and range's are fresh objects, freed before they were read).
    child = textwrap.dedent("""
        import json, sys
        sys.path.insert(0, sys.argv[1])
        import numpy as np
        from conftest import bumpy_sphere
        import meshsal
        V, F = bumpy_sphere(rings=24, segments=48)
        out = {}
        for name, lod in [("list", [0.5, 0.2]), ("tuple", (0.5, 0.2)), ("array", np.array([0.5, 0.2])),
                          ("float32", np.array([0.5, 0.2], dtype=np.float32)), ("counts", np.array([1500, 500])),
                          ("range", range(1500, 400, -500)), ("generator", (x for x in [0.5, 0.2]))]:
            out[name] = [r.output_faces for r in meshsal.simplify(V, F, lod=lod, weights="none")]
        print(json.dumps(out))
    """)
    r = subprocess.run([sys.executable, "-c", child, str(Path(__file__).parent)], capture_output=True, text=True,
                       env=os.environ, timeout=300)
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    n = len(sphere[1])
    assert out["list"] == [n // 2, round(0.2 * n)]
    for name in ("tuple", "array", "float32", "generator"):
        assert out[name] == out["list"], name
    assert out["counts"] == [1500, 500]
    assert out["range"] == [1500, 1000, 500]


def test_lod_refuses_bytes_zero_d_arrays_and_counts_beyond_any_integer(sphere):
    V, F = sphere
    for bad in (b"0.5", bytearray(b"0.5"), np.array(0.5), 5, {0.5: 1}):
        with pytest.raises(TypeError, match="lod must be a list of ratios"):
            meshsal.simplify(V, F, lod=bad)
    for bad in ([True], ["0.5"], [0.5, None]):
        with pytest.raises(TypeError, match="lod items must be a number"):
            meshsal.simplify(V, F, lod=bad)
    with pytest.raises(ValueError, match=r"lod face counts must be in \[1, 4000000000\], got 1180591620717411303424"):
        meshsal.simplify(V, F, lod=[2 ** 70])
    with pytest.raises(ValueError, match="1 to 16 levels"):
        meshsal.simplify(V, F, lod=(0.5 for _ in iter(int, 1)))  # endless: read no further than 17


def test_out_of_core_integers_beyond_any_integer_are_value_errors(tmp_path, read_only_input):
    src, _ = read_only_input
    out = tmp_path / "out.ply"
    with pytest.raises(ValueError, match=r"memory_limit must be in \[1, 18446744073709551615\], got 1180591620717411303424"):
        meshsal.saliency_file(src, out, memory_limit=2 ** 70)
    with pytest.raises(ValueError, match=r"memory_limit must be in \[1, .*\], got 0"):
        meshsal.simplify_file(src, out, ratio=0.5, memory_limit=0)
    with pytest.raises(ValueError, match=r"target_faces must be in \[1, 4000000000\], got 1180591620717411303424"):
        meshsal.simplify_file(src, out, target_faces=2 ** 70)
    with pytest.raises(ValueError, match=r"tiles must be in \[0, 4294967295\], got -1"):
        meshsal.saliency_file(src, out, tiles=-1)
    for bad in (True, 1.5, "100"):
        with pytest.raises(TypeError, match="target_faces must be an integer"):
            meshsal.simplify_file(src, out, target_faces=bad)
    with pytest.raises(TypeError, match="memory_limit must be a size"):
        meshsal.saliency_file(src, out, memory_limit=True)
    with pytest.raises(TypeError, match="ratio must be a number"):
        meshsal.simplify_file(src, out, ratio="0.5")
    assert not out.exists()
    # numpy's integers are integers.
    meshsal.simplify_file(src, out, target_faces=np.int64(1000), memory_limit=np.uint64(2 ** 30), weights="none")
    assert out.exists()


def test_integers_out_of_range_are_value_errors_naming_the_value(sphere):
    V, F = sphere
    cases = [
        (meshsal.saliency, dict(threads=-1), r"threads must be in \[0, 4294967295\], got -1"),
        (meshsal.saliency, dict(threads=2 ** 70), r"got 1180591620717411303424"),
        (meshsal.saliency, dict(tiles=2 ** 40), r"tiles must be in \[0, 4294967295\], got 1099511627776"),
        (meshsal.simplify, dict(ratio=0.5, threads=-2), r"threads must be in \[0, 4294967295\], got -2"),
        (meshsal.best_view, dict(seed=-1), r"seed must be in \[0, 18446744073709551615\], got -1"),
        (meshsal.best_view, dict(seed=2 ** 64), r"got 18446744073709551616"),
        (meshsal.best_view, dict(restarts=2 ** 70), r"restarts must be in \[1, 1000\], got 1180591620717411303424"),
        (meshsal.best_view, dict(views=-5), r"views must be in \[0, 1000000\], got -5"),
        (meshsal.best_view, dict(resolution=2 ** 33), r"resolution must be in \[16, 8192\], got 8589934592"),
        (meshsal.render, dict(size=2 ** 40), r"size must be in \[-2147483648, 2147483647\], got 1099511627776"),
        (meshsal.render, dict(supersample=-2 ** 40), r"got -1099511627776"),
        (meshsal.render, dict(theta=10 ** 400), r"theta is out of range, got 1000"),
    ]
    for f, kwargs, message in cases:
        with pytest.raises(ValueError, match=message):
            f(V, F, backend="cpu", **kwargs)
    with pytest.raises(ValueError, match=r"max_input_bytes must be in \[0, 18446744073709551615\], got -1"):
        meshsal.load("any.ply", max_input_bytes=-1)


def test_bools_are_not_numbers_and_numbers_not_bools(sphere):
    V, F = sphere
    cases = [
        (meshsal.saliency, dict(threads=True), "threads must be an integer, got bool"),
        (meshsal.saliency, dict(tiles=np.True_), "tiles must be an integer, got bool"),
        (meshsal.saliency, dict(eps_frac=True), "eps_frac must be a number, got bool"),
        (meshsal.saliency, dict(eps_frac=np.array([0.003])), "eps_frac must be a single number, got ndarray"),
        (meshsal.saliency, dict(scales=[True, 3]), "scales must be a number, got bool"),
        (meshsal.best_view, dict(views=True), "views must be an integer, got bool"),
        (meshsal.best_view, dict(depth_tol=False), "depth_tol must be a number, got bool"),
        (meshsal.render, dict(theta=True), "theta must be a number, got bool"),
        (meshsal.render, dict(supersample=2.0), "supersample must be an integer, got float"),
        (meshsal.saliency, dict(raw_maps=1), "raw_maps must be True or False, got int"),
        (meshsal.saliency, dict(smoothed=None), "smoothed must be True or False, got NoneType"),
        (meshsal.simplify, dict(ratio=0.5, lock_border=1), "lock_border must be True or False, got int"),
        (meshsal.render, dict(grey="yes"), "grey must be True or False, got str"),
    ]
    for f, kwargs, message in cases:
        with pytest.raises(TypeError, match=message):
            f(V, F, backend="cpu", **kwargs)
    with pytest.raises(TypeError, match="on must be True or False, got int"):
        meshsal.keep_freed_memory(1)


def test_sequence_arguments_take_any_iterable_but_bytes_and_zero_d_arrays(sphere):
    V, F = sphere
    s = meshsal.saliency(V, F, backend="cpu", scales=[2, 3, 4]).saliency
    for scales in ((2, 3, 4), np.array([2.0, 3.0, 4.0]), range(2, 5), (x for x in [2, 3, 4])):
        np.testing.assert_array_equal(meshsal.saliency(V, F, backend="cpu", scales=scales).saliency, s)
    for bad in (b"\x02\x03\x04", np.array(2.0), 2):
        with pytest.raises(TypeError, match="scales must be a sequence of numbers"):
            meshsal.saliency(V, F, backend="cpu", scales=bad)
    view = meshsal.best_view(V, F, s, restarts=1, resolution=64, elevation=(0, 60))
    for elevation in ([0, 60], np.array([0, 60]), (x for x in (0, 60)), "0,60"):
        assert meshsal.best_view(V, F, s, restarts=1, resolution=64, elevation=elevation) == view
    for bad in (b"\x00\x3c", np.array(30.0)):
        with pytest.raises(TypeError, match="elevation must be"):
            meshsal.best_view(V, F, s, elevation=bad)
    with pytest.raises(TypeError, match="elevation must be a number, got str"):
        meshsal.best_view(V, F, s, elevation=("a", "b"))
    with pytest.raises(ValueError, match="elevation must be .* got more than 2 values"):
        meshsal.best_view(V, F, s, elevation=range(10))
    image = meshsal.render(V, F, s, size=32, color_range=(0, 1))
    np.testing.assert_array_equal(meshsal.render(V, F, s, size=32, color_range=np.array([0, 1])), image)
    with pytest.raises(TypeError, match="color_range must be 'LO,HI' or a pair"):
        meshsal.render(V, F, s, size=32, color_range=b"0,1")
    with pytest.raises(TypeError, match="color_range must be a number, got bytes"):
        meshsal.render(V, F, s, size=32, color_range=(b"0", 1))


def test_a_device_index_that_does_not_exist_is_a_value_error(sphere):
    V, F = sphere
    for index in (-5, -2, 2 ** 70):
        with pytest.raises(ValueError, match=rf"device must be in \[-1, 2147483647\], got {index}"):
            meshsal.saliency(V, F, device=index)
        with pytest.raises(ValueError, match=rf"device must be in \[-1, 2147483647\], got {index}"):
            meshsal.Device(index)
    with pytest.raises(TypeError, match="device must be an integer, got bool"):
        meshsal.Device(True)
    # One beyond the machine's devices: refused, whatever the backend (auto ran on the CPU).
    for backend in ("auto", "gpu", "cpu"):
        with pytest.raises(ValueError, match=r"no Vulkan device 1000000 \("):
            meshsal.saliency(V, F, backend=backend, device=10 ** 6)
    with pytest.raises(ValueError, match=r"no Vulkan device 1000000 \("):
        meshsal.best_view(V, F, np.ones(len(V)), device=10 ** 6)
    with pytest.raises(ValueError, match=r"no Vulkan device 1000000 \("):
        meshsal.Device(10 ** 6)


def test_a_deeply_nested_gltf_is_an_error_not_a_crash(tmp_path):
    # 20,000 levels of extras overflowed the JSON conversion's stack and killed the
    # interpreter; now load() raises meshsal.Error, and the interpreter goes on.
    deep = tmp_path / "deep.gltf"
    deep.write_text('{"asset":{"version":"2.0","extras":' + "[" * 20000 + "]" * 20000 + "}}")
    code = textwrap.dedent(f"""
        import meshsal
        try:
            meshsal.load({str(deep)!r})
        except meshsal.Error as e:
            print("refused:", e)
    """)
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=os.environ.copy())
    assert r.returncode == 0, r.stderr
    assert "its JSON nests deeper than 64 levels" in r.stdout
