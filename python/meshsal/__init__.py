"""meshsal: mesh saliency (Lee, Varshney, Jacobs 2005) over numpy arrays.

    import meshsal
    V, F = meshsal.load("bunny.obj")          # float32 (n, 3), uint32 (m, 3)
    r = meshsal.saliency(V, F)                # r.saliency, r.curvature: float64 (n,)
    V2, F2 = meshsal.simplify(V, F, ratio=0.1)
    view = meshsal.best_view(V, F, r.saliency)
    image = meshsal.render(V, F, r.saliency, best=True)   # uint8 (512, 512, 3)

Arrays from trimesh (mesh.vertices, mesh.faces) or Open3D (np.asarray(mesh.vertices),
np.asarray(mesh.triangles)) go straight in. Every function releases the GIL while it
computes; the library's errors raise meshsal.Error (a ValueError and a RuntimeError).
Importing it makes the C heap keep freed memory for reuse (see keep_freed_memory).
"""
from ._meshsal import (  # noqa: F401
    Error,
    SaliencyResult,
    SimplifyResult,
    best_view,
    built_with_vulkan,
    devices,
    keep_freed_memory,
    load,
    render,
    saliency,
    simplify,
    version,
    __version__,
)

__all__ = ["Error", "SaliencyResult", "SimplifyResult", "best_view", "built_with_vulkan",
           "devices", "keep_freed_memory", "load", "render", "saliency", "simplify", "version",
           "__version__"]

keep_freed_memory(True)
