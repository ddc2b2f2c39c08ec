"""meshsal: mesh saliency (Lee, Varshney, Jacobs 2005) over numpy arrays.

    import meshsal
    V, F = meshsal.load("bunny.obj")          # float32 (n, 3), uint32 (m, 3)
    r = meshsal.saliency(V, F)                # r.saliency, r.curvature: float64 (n,)
    meshsal.save("bunny_saliency.ply", V, F, r.saliency)   # as `meshsal saliency` writes it
    V2, F2 = meshsal.simplify(V, F, ratio=0.1)
    view = meshsal.best_view(V, F, r.saliency)
    image = meshsal.render(V, F, r.saliency, best=True)   # uint8 (512, 512, 3)

Arrays from trimesh (mesh.vertices, mesh.faces) or Open3D (np.asarray(mesh.vertices),
np.asarray(mesh.triangles)) go straight in. Every function releases the GIL while it
computes; the library's errors raise meshsal.Error (a ValueError and a RuntimeError); a
missing file meshsal.FileNotFoundError and an unreadable one meshsal.PermissionError
(subclasses of meshsal.Error and of the built-in ones). A wrong keyword or argument type
raises a short TypeError that names the argument (never an input array).
Importing it changes nothing process-wide: keep_freed_memory() (the C heap keeps freed memory
for the next call, as the meshsal command does) is the program's choice.
"""
from . import _meshsal
from ._meshsal import (  # noqa: F401
    Device,
    Error,
    FileNotFoundError,
    PermissionError,
    SaliencyResult,
    SimplifyResult,
    version,
    __version__,
)
from ._arguments import short_type_errors as _short_type_errors

# The functions, each wrapped so that a call with a wrong keyword or argument type raises a
# short TypeError instead of pybind11's, which prints every argument (arrays included).
best_view = _short_type_errors(_meshsal.best_view)
built_with_vulkan = _short_type_errors(_meshsal.built_with_vulkan)
defaults = _short_type_errors(_meshsal.defaults)
devices = _short_type_errors(_meshsal.devices)
evaluate = _short_type_errors(_meshsal.evaluate)
keep_freed_memory = _short_type_errors(_meshsal.keep_freed_memory)
load = _short_type_errors(_meshsal.load)
release_cached_devices = _short_type_errors(_meshsal.release_cached_devices)
render = _short_type_errors(_meshsal.render)
saliency = _short_type_errors(_meshsal.saliency)
saliency_file = _short_type_errors(_meshsal.saliency_file)
save = _short_type_errors(_meshsal.save)
simplify = _short_type_errors(_meshsal.simplify)
simplify_file = _short_type_errors(_meshsal.simplify_file)

# FileNotFoundError and PermissionError are left out: `from meshsal import *` would hide
# the built-in ones (which they subclass).
__all__ = ["Device", "Error", "SaliencyResult", "SimplifyResult", "best_view", "built_with_vulkan",
           "defaults", "devices", "evaluate", "keep_freed_memory", "load", "release_cached_devices", "render", "saliency",
           "saliency_file", "save", "simplify", "simplify_file", "version", "__version__"]

