#include "view/visibility.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "meshsal/meshsal.h"
#include "core/mesh_points.h"
#include "core/parallel.h"

namespace meshsal {

void check_visibility_options(const VisibilityOptions& o) {
  if (o.resolution < kMinImageSize || o.resolution > kMaxImageSize)
    throw Error("resolution must be between " + std::to_string(kMinImageSize) + " and " +
                std::to_string(kMaxImageSize) + ", got " + std::to_string(o.resolution));
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
    // U sums the score over visible points: a negative one would make hiding a point pay.
    if (is_point[i] && score[i] < 0)
      throw Error("score of vertex " + std::to_string(i) + " is " + std::to_string(score[i]) +
                  ": a view score (a saliency, |curvature|) is >= 0");
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

// One triangle set up for the rasteriser rule shared with shaders/visibility_raster.comp
// (same float expressions): a pixel is covered when its centre is inside or on the triangle.
struct RasterTriangle {
  const float *a, *b, *c;
  float s, inv;
  int x0, x1, y0, y1;  // pixels whose centre lies in the bounding box, clipped to the image
};

// False for a degenerate triangle or one whose box holds no pixel centre.
static inline bool setup_triangle(const float* a, const float* b, const float* c, int res, RasterTriangle& t) {
  float area = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
  if (!(std::fabs(area) > 1e-12f)) return false;
  t.a = a, t.b = b, t.c = c;
  t.s = area > 0 ? 1.0f : -1.0f;
  t.inv = 1.0f / std::fabs(area);
  // Pixels whose centre x + 0.5 lies in the bounding box (tiny triangles often have none).
  int x0 = -ifloor(0.5f - min3(a[0], b[0], c[0]));  // ceil(min - 0.5)
  int x1 = ifloor(max3(a[0], b[0], c[0]) - 0.5f);
  int y0 = -ifloor(0.5f - min3(a[1], b[1], c[1]));
  int y1 = ifloor(max3(a[1], b[1], c[1]) - 0.5f);
  t.x0 = x0 < 0 ? 0 : x0;
  t.y0 = y0 < 0 ? 0 : y0;
  t.x1 = x1 > res - 1 ? res - 1 : x1;
  t.y1 = y1 > res - 1 ? res - 1 : y1;
  return t.x0 <= t.x1 && t.y0 <= t.y1;
}

// Per 8x8 tile of the z-buffer: how many of its pixels hold a depth, and an upper bound of
// those depths (only ever raised, so it stays an upper bound as depths drop).
struct DepthTiles {
  static constexpr int kShift = 3, kSide = 1 << kShift;
  int across = 0;
  std::vector<uint16_t> filled;
  std::vector<float> max_depth;
  void reset(int res) {
    across = (res + kSide - 1) >> kShift;
    filled.assign(size_t(across) * across, 0);
    max_depth.assign(size_t(across) * across, 0.0f);
  }
};

// A large triangle of one view: its projected corners and min_depth_bound.
struct LargeTriangle {
  float bound;
  float p[9];
};

// Per-thread buffers of raster_depth, kept across views.
struct RasterScratch {
  std::vector<LargeTriangle> large;
  DepthTiles tiles;
};

// Rasterises t over the pixels [x0, x1] x [y0, y1] (inside t's box) with z < zbuf.
static inline void raster_rect(const RasterTriangle& t, int x0, int x1, int y0, int y1, int res, float* zbuf,
                               DepthTiles* tiles) {
  const float *a = t.a, *b = t.b, *c = t.c;
  const float s = t.s, inv = t.inv;
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
      if (z < dst) {
        if (tiles) {
          const size_t k = size_t(y >> DepthTiles::kShift) * tiles->across + size_t(x >> DepthTiles::kShift);
          tiles->filled[k] += std::isinf(dst);
          tiles->max_depth[k] = std::max(tiles->max_depth[k], z);
        }
        dst = z;
      }
    }
  }
}

// The plain rasteriser: every triangle over its whole box. The oracle of raster_depth.
static void raster_depth_plain(const Mesh& mesh, const std::vector<float>& proj, int res, float* zbuf) {
  const uint32_t* t = mesh.triangles.data();
  RasterTriangle r{};
  for (size_t f = 0; f < mesh.triangle_count(); ++f)
    if (setup_triangle(&proj[3 * size_t(t[3 * f])], &proj[3 * size_t(t[3 * f + 1])],
                       &proj[3 * size_t(t[3 * f + 2])], res, r))
      raster_rect(r, r.x0, r.x1, r.y0, r.y1, res, zbuf, nullptr);
}

// A triangle whose box covers at least this many pixels goes through the tile test.
constexpr int kLargeTrianglePixels = 256;

// A lower bound of every depth the rule computes for t: the minimum vertex depth, less the
// worst rounding of the weights (each within ~8 ulp of the box area, their sum against the
// triangle's area) and of the products and the sum, times the largest vertex depth. A float
// rounded from it stays below every computed depth (those are floats above it).
static float min_depth_bound(const RasterTriangle& t) {
  const float* p[3] = {t.a, t.b, t.c};
  const float w = max3(p[0][0], p[1][0], p[2][0]) - min3(p[0][0], p[1][0], p[2][0]) + 1.0f;
  const float h = max3(p[0][1], p[1][1], p[2][1]) - min3(p[0][1], p[1][1], p[2][1]) + 1.0f;
  const double u = std::ldexp(1.0, -24);
  const double slack = 64 * u * double(w) * double(h) * double(t.inv) + 32 * u;
  const double lo = min3(p[0][2], p[1][2], p[2][2]);
  const double hi = max3(std::fabs(p[0][2]), std::fabs(p[1][2]), std::fabs(p[2][2]));
  return float(lo - slack * hi);
}

// The same z-buffer as raster_depth_plain (the minimum is order-free and a skipped
// triangle provably writes nothing), at a cost bounded by the pixels and the triangles:
// large triangles go nearest first, an exact copy of the one before is dropped (it would
// compute the same depths), and an 8x8 tile already covered no deeper than the triangle's
// smallest possible depth is skipped. A stack of 100,000 copies of one large triangle costs
// one triangle's pixels, not 100,000 times them.
static void raster_depth(const Mesh& mesh, const std::vector<float>& proj, int res, float* zbuf,
                         RasterScratch& scratch) {
  const uint32_t* t = mesh.triangles.data();
  scratch.large.clear();
  RasterTriangle r{};
  for (size_t f = 0; f < mesh.triangle_count(); ++f) {
    const float* a = &proj[3 * size_t(t[3 * f])];
    const float* b = &proj[3 * size_t(t[3 * f + 1])];
    const float* c = &proj[3 * size_t(t[3 * f + 2])];
    if (!setup_triangle(a, b, c, res, r)) continue;
    if ((r.x1 - r.x0 + 1) * (r.y1 - r.y0 + 1) < kLargeTrianglePixels) {
      raster_rect(r, r.x0, r.x1, r.y0, r.y1, res, zbuf, nullptr);
      continue;
    }
    LargeTriangle l;
    l.bound = min_depth_bound(r);
    for (int k = 0; k < 3; ++k) l.p[k] = a[k], l.p[3 + k] = b[k], l.p[6 + k] = c[k];
    scratch.large.push_back(l);
  }
  if (scratch.large.empty()) return;
  std::sort(scratch.large.begin(), scratch.large.end(), [](const LargeTriangle& x, const LargeTriangle& y) {
    if (x.bound != y.bound) return x.bound < y.bound;
    return std::memcmp(x.p, y.p, sizeof x.p) < 0;
  });
  scratch.tiles.reset(res);
  DepthTiles& tiles = scratch.tiles;
  const int side = DepthTiles::kSide;
  for (size_t i = 0; i < scratch.large.size(); ++i) {
    const LargeTriangle& l = scratch.large[i];
    if (i > 0 && std::memcmp(l.p, scratch.large[i - 1].p, sizeof l.p) == 0) continue;
    if (!setup_triangle(l.p, l.p + 3, l.p + 6, res, r)) continue;  // (never: it passed before)
    for (int ty = r.y0 >> DepthTiles::kShift; ty <= r.y1 >> DepthTiles::kShift; ++ty)
      for (int tx = r.x0 >> DepthTiles::kShift; tx <= r.x1 >> DepthTiles::kShift; ++tx) {
        const size_t k = size_t(ty) * tiles.across + size_t(tx);
        const int pixels = std::min(side, res - tx * side) * std::min(side, res - ty * side);
        if (tiles.filled[k] == pixels && tiles.max_depth[k] <= l.bound) continue;
        raster_rect(r, std::max(r.x0, tx * side), std::min(r.x1, tx * side + side - 1), std::max(r.y0, ty * side),
                    std::min(r.y1, ty * side + side - 1), res, zbuf, &tiles);
      }
  }
}

std::vector<float> depth_buffer_cpu(const Mesh& mesh, const ViewRows& view, int res) {
  std::vector<float> proj;
  project_all(mesh, view, res, proj);
  std::vector<float> zbuf(size_t(res) * res, std::numeric_limits<float>::infinity());
  RasterScratch scratch;
  raster_depth(mesh, proj, res, zbuf.data(), scratch);
  return zbuf;
}

std::vector<float> depth_buffer_plain_cpu(const Mesh& mesh, const ViewRows& view, int res) {
  std::vector<float> proj;
  project_all(mesh, view, res, proj);
  std::vector<float> zbuf(size_t(res) * res, std::numeric_limits<float>::infinity());
  raster_depth_plain(mesh, proj, res, zbuf.data());
  return zbuf;
}

// Calls visit(i) for every vertex that passes the image and depth test.
template <class Visit>
static void test_vertices(const std::vector<float>& proj, const std::vector<float>& zbuf, int res,
                          float tol, Visit visit) {
  size_t n = proj.size() / 3;
  for (size_t i = 0; i < n; ++i)
    if (passes_depth_test({proj[3 * i], proj[3 * i + 1], proj[3 * i + 2]}, zbuf.data(), res, tol)) visit(i);
}

std::vector<uint8_t> visible_vertices_cpu(const Mesh& mesh, const ViewFrame& frame,
                                          const ViewAngles& view, const VisibilityOptions& o) {
  check_visibility_options(o);
  ViewRows rows = view_rows(frame, view);
  std::vector<float> proj;
  project_all(mesh, rows, o.resolution, proj);
  std::vector<float> zbuf(size_t(o.resolution) * o.resolution, std::numeric_limits<float>::infinity());
  RasterScratch scratch;
  raster_depth(mesh, proj, o.resolution, zbuf.data(), scratch);
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
    RasterScratch scratch;
    for (size_t v = begin; v < end; ++v) {
      project_all(mesh, view_rows(frame, views[v]), res, proj);
      std::fill(zbuf.begin(), zbuf.end(), std::numeric_limits<float>::infinity());
      raster_depth(mesh, proj, res, zbuf.data(), scratch);
      double sum = 0;
      test_vertices(proj, zbuf, res, tol, [&](size_t i) { sum += weights[i]; });
      U[v] = sum;
    }
  });
  return U;
}

}  // namespace meshsal
