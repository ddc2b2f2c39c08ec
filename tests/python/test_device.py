"""meshsal.Device: a Vulkan device held across calls (device= of every function), released
by close() or a with block; release_cached_devices() empties the cache of calls without one."""
import numpy as np
import pytest

import meshsal


def vulkan_devices():
    if not meshsal.built_with_vulkan():
        pytest.skip("built without Vulkan")
    try:
        devs = meshsal.devices()
    except meshsal.Error:
        pytest.skip("no Vulkan driver")
    if not devs:
        pytest.skip("no Vulkan device")
    return devs


def test_device_runs_every_function_and_matches_the_index(sphere):
    V, F = sphere
    devs = vulkan_devices()
    with meshsal.Device(0) as gpu:
        assert isinstance(gpu, meshsal.Device)
        assert gpu.is_open and gpu.index == 0
        assert gpu.name == devs[0]["name"] and gpu.type == devs[0]["type"]
        assert gpu.name in repr(gpu)
        held = meshsal.saliency(V, F, device=gpu)  # backend 'auto' runs on the Device given
        assert held.backend == gpu.name
        assert "device setup" not in held.stages   # opened by Device(0), not by the call
        by_index = meshsal.saliency(V, F, backend="gpu", device=0)
        np.testing.assert_array_equal(held.saliency, by_index.saliency)
        fast = meshsal.saliency(V, F, device=gpu, method="fast")
        assert fast.backend == gpu.name and fast.method == "fast"
        view = meshsal.best_view(V, F, held.saliency, device=gpu, backend="gpu", restarts=2, resolution=64)
        assert view["device"] == "vulkan: " + gpu.name
        s = meshsal.simplify(V, F, ratio=0.5, device=gpu)
        assert s.device == gpu.name
        image = meshsal.render(V, F, held.saliency, best=True, device=gpu, backend="gpu", size=64)
        assert image.shape == (64, 64, 3)
        with pytest.raises(meshsal.Error, match="cpu backend"):
            meshsal.saliency(V, F, device=gpu, backend="cpu")
    assert not gpu.is_open and "closed" in repr(gpu)
    with pytest.raises(meshsal.Error, match="was closed"):
        meshsal.saliency(V, F, device=gpu)
    gpu.close()  # idempotent
    meshsal.release_cached_devices()


def test_device_argument_types(sphere):
    V, F = sphere
    for bad in ["0", 1.5, None, True]:
        with pytest.raises(TypeError, match="device must be an int"):
            meshsal.saliency(V, F, device=bad, backend="cpu")
    assert meshsal.saliency(V, F, device=np.int64(-1), backend="cpu").backend.startswith("cpu")


def test_bad_index_and_docstrings():
    devs = vulkan_devices()
    with pytest.raises(meshsal.Error):
        meshsal.Device(len(devs) + 5)
    assert "with meshsal.Device" in meshsal.Device.__doc__
    assert "release_cached_devices" in meshsal.release_cached_devices.__doc__
    assert "meshsal.Device" in meshsal.saliency.__doc__
    # The fast method runs on Vulkan too (the docstring once said CPU only).
    assert "Vulkan device, as backend says" in meshsal.saliency.__doc__
