// meshsal: visible score of view directions (SPEC 3), the CPU twin of the GPU path.
//
// For each view the depth of the whole mesh is rasterised into a res x res z-buffer
// (orthographic camera of camera.h, a pixel is covered when its centre lies inside or on
// the triangle, depth interpolated linearly, smaller = nearer, cleared to +inf). A mesh
// point is visible when its pixel floor(px), floor(py) lies inside the image and
//   depth(point) <= zbuffer(pixel) + depth_tol_px / res
// i.e. the tolerance is depth_tol_px pixel widths along the view axis (a pixel is 2R/res
// wide and depth spans 2R). A point whose pixel is empty (on the silhouette, between pixel
// centres) is tested against the smallest depth of the 3x3 pixels around it, and is visible
// if they are all empty, so points just behind a silhouette do not leak through.
// The tolerance absorbs the depth of the point's own triangles sampled up to 0.71 px away:
// a point stays visible while its normal is within about atan(tol / 0.71) of the view
// direction (70 degrees at the default 2 px); more grazing points, and points less than
// tol behind an occluder, are borderline by nature.
// U(view) = sum of score over visible mesh points.
#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "view/camera.h"
#include "meshsal/meshsal.h"

namespace meshsal {

// The test above for one point projected into a view whose z-buffer is `zbuf` (res x res):
// true when it is visible. tol = depth_tol_px / res. shaders/visibility_test.comp's
// visible() and shaders/exposure_test.comp's are its GPU twins.
inline bool passes_depth_test(const Projected& p, const float* zbuf, int res, float tol) {
  const float fres = float(res);
  if (!(p.px >= 0.0f && p.py >= 0.0f && p.px < fres && p.py < fres)) return false;
  const int x = int(p.px), y = int(p.py);
  if (x > res - 1 || y > res - 1) return false;
  float z = zbuf[size_t(y) * res + x];
  if (z == std::numeric_limits<float>::infinity()) {
    // The point fell on an empty pixel: it lies on the silhouette between pixel centres.
    // Test it against the nearest surface around (3x3), so that points just behind the
    // silhouette do not leak through.
    for (int yy = (y > 0 ? y - 1 : 0); yy <= (y < res - 1 ? y + 1 : y); ++yy)
      for (int xx = (x > 0 ? x - 1 : 0); xx <= (x < res - 1 ? x + 1 : x); ++xx)
        z = std::fmin(z, zbuf[size_t(yy) * res + xx]);
  }
  return p.depth <= z + tol;
}

// Checks resolution (kMinImageSize..kMaxImageSize) and tolerance (>= 0); throws Error otherwise.
void check_visibility_options(const VisibilityOptions& options);

// Per-vertex score for visibility sums: the given values on mesh points, 0 elsewhere.
// Throws Error when the size differs from the vertex count, a value is not finite, or a
// mesh point's is negative.
std::vector<float> visibility_weights(const Mesh& mesh, const std::vector<double>& score);

// The z-buffer of one view (res*res floats, +inf where empty), the CPU reference rasteriser.
// Its cost is bounded by the pixels and the triangles (large triangles nearest first, exact
// copies dropped, 8x8 tiles already covered nearer skipped), even for a stack of copies of
// one large triangle.
std::vector<float> depth_buffer_cpu(const Mesh& mesh, const ViewRows& view, int resolution);

// The same z-buffer from the plain rasteriser (every triangle over its whole bounding box),
// cost proportional to the triangles' pixel area: the oracle depth_buffer_cpu is tested
// against.
std::vector<float> depth_buffer_plain_cpu(const Mesh& mesh, const ViewRows& view, int resolution);

// 1 for the mesh points visible in one view.
std::vector<uint8_t> visible_vertices_cpu(const Mesh& mesh, const ViewFrame& frame,
                                          const ViewAngles& view,
                                          const VisibilityOptions& options);

// U for each view: sum of weights (visibility_weights) over the visible vertices.
std::vector<double> visible_score_cpu(const Mesh& mesh, const std::vector<float>& weights,
                                      const ViewFrame& frame,
                                      const std::vector<ViewAngles>& views,
                                      const VisibilityOptions& options);

}  // namespace meshsal
