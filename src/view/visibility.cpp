#include "view/visibility.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "meshsal/meshsal.h"
#include "core/mesh_points.h"
#include "core/parallel.h"

namespace meshsal {

void check_visibility_options(const VisibilityOptions& o) {
  if (o.resolution < 16 || o.resolution > 8192)
    throw Error("resolution must be between 16 and 8192, got " + std::to_string(o.resolution));
  if (!(o.depth_tol_px >= 0) || !std::isfinite(o.depth_tol_px))
    throw Error("depth tolerance must be a finite number >= 0");
}

std::vector<float> visibility_weights(const Mesh& mesh, const std::vector<double>& score) {
  if (score.size() != mesh.vertex_count())
    throw Error("score has " + std::to_string(score.size()) + " values for " +
                std::to_string(mesh.vertex_count()) + " vertices");
  std::vector<uint8_t> is_point = referenced_vertices(mesh);
  std::vector<float> w(score.size(), 0.0f);
  for (size_t i = 0; i < score.size(); ++i) {
    if (!std::isfinite(score[i])) throw Error("score of vertex " + std::to_string(i) + " is not finite");
    if (is_point[i]) w[i] = float(score[i]);
  }
  return w;
}

// Projects all vertices of one view (px, py, depth per vertex).
static void project_all(const Mesh& mesh, const ViewRows& view, int res, std::vector<float>& out) {
  size_t n = mesh.vertex_count();
  out.resize(3 * n);
  const float half = 0.5f * float(res);
  const float* p = mesh.positions.data();
  for (size_t i = 0; i < n; ++i) {
    Projected q = project(view, p[3 * i], p[3 * i + 1], p[3 * i + 2], half);
    out[3 * i] = q.px;
    out[3 * i + 1] = q.py;
    out[3 * i + 2] = q.depth;
  }
}

// Inline floor/min/max (positions are finite; these equal GLSL floor/min/max there).
static inline int ifloor(float v) {
  int i = int(v);
  return float(i) > v ? i - 1 : i;
}
static inline float min3(float a, float b, float c) { return a < b ? (a < c ? a : c) : (b < c ? b : c); }
static inline float max3(float a, float b, float c) { return a > b ? (a > c ? a : c) : (b > c ? b : c); }

// The rasteriser rule shared with shaders/visibility_raster.comp (same float expressions).
static void raster_depth(const Mesh& mesh, const std::vector<float>& proj, int res, float* zbuf) {
  const uint32_t* t = mesh.triangles.data();
  for (size_t f = 0; f < mesh.triangle_count(); ++f) {
    const float* a = &proj[3 * size_t(t[3 * f])];
    const float* b = &proj[3 * size_t(t[3 * f + 1])];
    const float* c = &proj[3 * size_t(t[3 * f + 2])];
    float area = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
    if (!(std::fabs(area) > 1e-12f)) continue;
    float s = area > 0 ? 1.0f : -1.0f;
    float inv = 1.0f / std::fabs(area);
    // Pixels whose centre x + 0.5 lies in the bounding box (tiny triangles often have none).
    int x0 = -ifloor(0.5f - min3(a[0], b[0], c[0]));  // ceil(min - 0.5)
    int x1 = ifloor(max3(a[0], b[0], c[0]) - 0.5f);
    int y0 = -ifloor(0.5f - min3(a[1], b[1], c[1]));
    int y1 = ifloor(max3(a[1], b[1], c[1]) - 0.5f);
    x0 = x0 < 0 ? 0 : x0;
    y0 = y0 < 0 ? 0 : y0;
    x1 = x1 > res - 1 ? res - 1 : x1;
    y1 = y1 > res - 1 ? res - 1 : y1;
    for (int y = y0; y <= y1; ++y) {
      float cy = float(y) + 0.5f;
      for (int x = x0; x <= x1; ++x) {
        float cx = float(x) + 0.5f;
        float w0 = s * ((c[0] - b[0]) * (cy - b[1]) - (c[1] - b[1]) * (cx - b[0]));
        float w1 = s * ((a[0] - c[0]) * (cy - c[1]) - (a[1] - c[1]) * (cx - c[0]));
        float w2 = s * ((b[0] - a[0]) * (cy - a[1]) - (b[1] - a[1]) * (cx - a[0]));
        if (w0 < 0.0f || w1 < 0.0f || w2 < 0.0f) continue;
        float z = (w0 * a[2] + w1 * b[2] + w2 * c[2]) * inv;
        float& dst = zbuf[size_t(y) * res + x];
        if (z < dst) dst = z;
      }
    }
  }
}

std::vector<float> depth_buffer_cpu(const Mesh& mesh, const ViewRows& view, int res) {
  std::vector<float> proj;
  project_all(mesh, view, res, proj);
  std::vector<float> zbuf(size_t(res) * res, std::numeric_limits<float>::infinity());
  raster_depth(mesh, proj, res, zbuf.data());
  return zbuf;
}

// Calls visit(i) for every vertex that passes the image and depth test.
template <class Visit>
static void test_vertices(const std::vector<float>& proj, const std::vector<float>& zbuf, int res,
                          float tol, Visit visit) {
  size_t n = proj.size() / 3;
  const float fres = float(res);
  for (size_t i = 0; i < n; ++i) {
    float px = proj[3 * i], py = proj[3 * i + 1];
    if (!(px >= 0.0f && py >= 0.0f && px < fres && py < fres)) continue;
    int x = int(px), y = int(py);
    if (x > res - 1 || y > res - 1) continue;
    float z = zbuf[size_t(y) * res + x];
    if (std::isinf(z)) {
      // The point fell on an empty pixel: it lies on the silhouette between pixel centres.
      // Test it against the nearest surface around (3x3), so that points just behind the
      // silhouette do not leak through.
      for (int yy = (y > 0 ? y - 1 : 0); yy <= (y < res - 1 ? y + 1 : y); ++yy)
        for (int xx = (x > 0 ? x - 1 : 0); xx <= (x < res - 1 ? x + 1 : x); ++xx)
          z = std::fmin(z, zbuf[size_t(yy) * res + xx]);
    }
    if (proj[3 * i + 2] <= z + tol) visit(i);
  }
}

std::vector<uint8_t> visible_vertices_cpu(const Mesh& mesh, const ViewFrame& frame,
                                          const ViewAngles& view, const VisibilityOptions& o) {
  check_visibility_options(o);
  ViewRows rows = view_rows(frame, view);
  std::vector<float> proj;
  project_all(mesh, rows, o.resolution, proj);
  std::vector<float> zbuf(size_t(o.resolution) * o.resolution, std::numeric_limits<float>::infinity());
  raster_depth(mesh, proj, o.resolution, zbuf.data());
  std::vector<uint8_t> is_point = referenced_vertices(mesh);
  std::vector<uint8_t> vis(mesh.vertex_count(), 0);
  float tol = float(o.depth_tol_px / o.resolution);
  test_vertices(proj, zbuf, o.resolution, tol, [&](size_t i) { vis[i] = is_point[i]; });
  return vis;
}

std::vector<double> visible_score_cpu(const Mesh& mesh, const std::vector<float>& weights,
                                      const ViewFrame& frame, const std::vector<ViewAngles>& views,
                                      const VisibilityOptions& o) {
  check_visibility_options(o);
  if (weights.size() != mesh.vertex_count()) throw Error("visibility weights do not match the mesh");
  std::vector<double> U(views.size(), 0.0);
  const int res = o.resolution;
  const float tol = float(o.depth_tol_px / res);
  // Chunks of several views: each chunk allocates its own z-buffer once.
  size_t chunk = std::max<size_t>(1, views.size() / (8 * size_t(resolve_threads(o.threads))));
  parallel_for(views.size(), o.threads, chunk, [&](size_t begin, size_t end) {
    std::vector<float> proj;
    std::vector<float> zbuf(size_t(res) * res);
    for (size_t v = begin; v < end; ++v) {
      project_all(mesh, view_rows(frame, views[v]), res, proj);
      std::fill(zbuf.begin(), zbuf.end(), std::numeric_limits<float>::infinity());
      raster_depth(mesh, proj, res, zbuf.data());
      double sum = 0;
      test_vertices(proj, zbuf, res, tol, [&](size_t i) { sum += weights[i]; });
      U[v] = sum;
    }
  });
  return U;
}

}  // namespace meshsal
