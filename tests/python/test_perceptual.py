# model= (the CLI's --model): saliency() gives the bytes `meshsal saliency --model` writes and
# the cues by name, and every function that computes S takes it (simplify, best_view, render,
# saliency_file), with the library's refusals as ValueError.
import numpy as np
import pytest

import meshsal

from conftest import bumpy_sphere


def test_saliency_model_equals_the_cli(tmp_path, cli):
    V, F = bumpy_sphere(rings=24, segments=48)
    src = tmp_path / "in.ply"
    meshsal.save(src, V, F)
    V, F = meshsal.load(src)  # the positions as the command line reads them
    r = meshsal.saliency(V, F, model="perceptual", up="z", backend="cpu")
    assert r.model == "perceptual"
    assert sorted(r.cues) == ["coarse", "exposure_centre", "height", "rarity"]
    assert r.saliency.max() == pytest.approx(1.0)
    out = tmp_path / "s.ply"
    cli("saliency", src, "-o", out, "--model", "perceptual", "--up", "z", "--backend", "cpu", "-q")
    _, _, props = meshsal.load(out, properties=True)
    assert np.array_equal(props["quality"], r.saliency.astype(np.float32))
    # saliency_file is the CLI's pipeline: the same bytes.
    out2 = tmp_path / "s2.ply"
    meshsal.saliency_file(src, out2, model="perceptual", up="z", backend="cpu")
    assert out2.read_bytes() == out.read_bytes()


def test_every_function_that_computes_s_takes_the_model():
    V, F = bumpy_sphere(rings=16, segments=32)
    h = meshsal.saliency(V, F, model="height", up="y")
    assert h.model == "height"
    assert list(h.cues) == ["height"]
    assert h.saliency[np.argmax(V[:, 1])] == 1.0 and h.saliency[np.argmin(V[:, 1])] == 0.0
    assert meshsal.saliency(V, F).model == "lee2005" and meshsal.saliency(V, F).cues == {}
    s = meshsal.simplify(V, F, ratio=0.3, model="perceptual")
    plain = meshsal.simplify(V, F, ratio=0.3)
    assert len(s.faces) > 0 and not np.array_equal(s.faces, plain.faces)
    v = meshsal.best_view(V, F, model="height", restarts=2)
    assert v["visible_score"] != meshsal.best_view(V, F, restarts=2)["visible_score"]
    img = meshsal.render(V, F, model="height", size=64)
    assert img.shape == (64, 64, 3)
    assert not np.array_equal(img, meshsal.render(V, F, size=64))
    with pytest.raises(ValueError, match="model must be lee2005, perceptual"):
        meshsal.saliency(V, F, model="itti")
    with pytest.raises(ValueError, match="in one piece"):
        meshsal.saliency(V, F, model="perceptual", tiles=4)
