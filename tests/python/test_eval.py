# meshsal.evaluate(): the same numbers as `meshsal eval --json` on the same files (both call
# the library's evaluate_files), and the scores of two arrays (evaluate_scores).
import math

import numpy as np
import pytest

import meshsal

from conftest import bumpy_sphere


def _files(tmp_path):
    V, F = bumpy_sphere(rings=16, segments=32)
    p = 2 + V[:, 0]
    g = np.maximum(0, V[:, 0] + 0.3 * V[:, 1])
    pred, gt = tmp_path / "pred.ply", tmp_path / "gt.ply"
    meshsal.save(pred, V, F, p)
    meshsal.save(gt, V, F, g)
    return V, F, pred, gt


def test_evaluate_matches_the_cli(tmp_path, cli):
    V, F, pred, gt = _files(tmp_path)
    for extra in ([], ["--smooth", "0.05"]):
        j = cli.json("eval", pred, gt, "--json", *extra)
        d = meshsal.evaluate(pred, gt, smooth=0.05 if extra else 0.0)
        for part in ("raw", "smoothed") if extra else ("raw",):
            for key in ("cc", "auc_20", "auc_5", "nss", "kld", "sim"):
                assert d[part][key] == pytest.approx(j[part][key], rel=1e-8), (part, key)
            for key in ("vertices", "positives_20", "positives_5", "nss_vertices"):
                assert d[part][key] == j[part][key]
        for key in ("vertices", "scored_vertices", "gt_source", "transfer", "notes", "smooth"):
            assert d[key] == j[key], key
        if not extra:
            assert d["smoothed"] is None and j["smoothed"] is None
    # Text rows with one that matches nothing: counted and listed the same way.
    rows = tmp_path / "gt.txt"
    lines = [f"{x!r} {y!r} {z!r} {v!r}" for (x, y, z), v in zip(V.tolist(), (V[:, 1] ** 2).tolist())]
    rows.write_text("\n".join(lines + ["9 9 9 1"]) + "\n")
    j = cli.json("eval", pred, rows, "--json")
    d = meshsal.evaluate(str(pred), str(rows))
    assert d["unmatched_rows"] == j["unmatched_rows"] == 1
    assert d["unmatched_lines"] == j["unmatched_lines"] == [len(V) + 1]
    assert d["raw"]["cc"] == pytest.approx(j["raw"]["cc"], rel=1e-8)
    # GT on a coarser sphere, carried by --transfer nearest.
    V2, F2 = bumpy_sphere(rings=8, segments=16)
    coarse = tmp_path / "coarse.ply"
    meshsal.save(coarse, V2, F2, np.maximum(0, V2[:, 1]))
    j = cli.json("eval", pred, coarse, "--transfer", "nearest", "--json")
    d = meshsal.evaluate(pred, coarse, transfer="nearest")
    assert d["transfer"] == j["transfer"] == "nearest"
    for key in ("cc", "auc_20", "auc_5", "nss", "kld", "sim"):
        assert d["raw"][key] == pytest.approx(j["raw"][key], rel=1e-8), key
    assert d["transfer_max_distance"] == pytest.approx(j["transfer_max_distance"], rel=1e-8)


def test_evaluate_arrays_and_errors(tmp_path):
    # p = 1 2 2 3 0, g = 0 5 1 5 0: worked out in tests/api/test_eval.cpp.
    s = meshsal.evaluate(np.array([1, 2, 2, 3, 0.0]), [0, 5, 1, 5, 0])
    assert s["cc"] == pytest.approx(9.4 / math.sqrt(5.2 * 26.8))
    assert s["auc_20"] == pytest.approx(5.5 / 6)
    assert s["positives_20"] == 2
    z = meshsal.evaluate([1.0, 2.0, 3.0], [0.0, 0.0, 0.0])
    assert z["cc"] is None and z["nss"] is None and z["kld"] is None and len(z["notes"]) == 4
    with pytest.raises(ValueError, match="not finite"):
        meshsal.evaluate([1.0, float("nan")], [1.0, 2.0])
    with pytest.raises(ValueError, match="apply to files"):
        meshsal.evaluate([1.0, 2.0], [1.0, 2.0], smooth=0.1)
    V, F, pred, gt = _files(tmp_path)
    with pytest.raises(meshsal.Error, match="no per-vertex attribute 'nope'"):
        meshsal.evaluate(pred, gt, attribute="nope")
    with pytest.raises(meshsal.FileNotFoundError):
        meshsal.evaluate(pred, tmp_path / "missing.ply")
    with pytest.raises(ValueError, match="transfer must be"):
        meshsal.evaluate(pred, gt, transfer="farthest")
