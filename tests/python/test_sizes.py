# Issue 36 (9): a size given as a str (memory_limit="700M") is read by the library's
# parse_memory_size, as the CLI's --memory-limit: the same errors, before the input is read.
import pytest

import meshsal


@pytest.mark.parametrize("size", ["0.5", "100", "0", "abc", "inf", "-1", "0x10M", "1e3M", "16777216T", "0.0001K"])
def test_bad_sizes_are_refused_before_the_input_is_read(size, tmp_path):
    missing = tmp_path / "missing.ply"
    with pytest.raises(meshsal.Error, match="memory size"):
        meshsal.saliency_file(missing, tmp_path / "s.ply", memory_limit=size)
    with pytest.raises(meshsal.Error, match="memory size"):
        meshsal.simplify_file(missing, tmp_path / "t.ply", ratio=0.5, memory_limit=size)


def test_a_bare_number_under_1m_suggests_the_unit(tmp_path):
    with pytest.raises(meshsal.Error, match=r"'100' is 100 bytes: give a unit, e\.g\. 100M"):
        meshsal.saliency_file(tmp_path / "missing.ply", tmp_path / "s.ply", memory_limit="100")
