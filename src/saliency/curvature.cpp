#include "saliency/curvature.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <vector>

#include "core/cancel.h"
#include "core/morton_order.h"
#include "core/parallel.h"
#include "saliency/cpu_dispatch.h"

namespace meshsal {

namespace {

// The hot loops below are written once and compiled twice, for baseline x86-64 and for
// AVX2 (cpu_dispatch.h); both copies give the same bits.

// Un-normalised normal of triangle t: its length is twice the area (area weighting).
inline void face_normal(const float* p, const uint32_t* t, double fn[3]) {
  double e1[3], e2[3];
  for (int k = 0; k < 3; ++k) {
    e1[k] = double(p[3 * t[1] + k]) - p[3 * t[0] + k];
    e2[k] = double(p[3 * t[2] + k]) - p[3 * t[0] + k];
  }
  fn[0] = e1[1] * e2[2] - e1[2] * e2[1];
  fn[1] = e1[2] * e2[0] - e1[0] * e2[2];
  fn[2] = e1[0] * e2[1] - e1[1] * e2[0];
}

inline bool owns(uint32_t v, size_t lo, size_t hi) { return v >= lo && v < hi; }

// The triangles a body visits, in index order: those in [begin, end) and those of the
// sorted list `extra` outside it (mean_curvature_morton's ranges: their own block of the
// Morton-sorted triangles and the few that cross into another range). {0, all, none}:
// every triangle.
struct TriangleSpan {
  size_t begin, end;
  const uint32_t* extra = nullptr;
  size_t extra_count = 0;
};

TriangleSpan all_triangles(const Mesh& mesh) { return {0, mesh.triangle_count(), nullptr, 0}; }

// Calls visit(f) for the span's triangles in increasing order, and checks for cancellation
// every 65,536 of them.
template <class Visit>
inline void for_each_triangle(const TriangleSpan& s, Visit&& visit) {
  size_t seen = 0;
  auto one = [&](size_t f) {
    if ((++seen & 0xffff) == 0) throw_if_cancelled();
    visit(f);
  };
  size_t x = 0;
  for (; x < s.extra_count && s.extra[x] < s.begin; ++x) one(s.extra[x]);
  for (size_t f = s.begin; f < s.end; ++f) one(f);
  for (; x < s.extra_count; ++x)
    if (s.extra[x] >= s.end) one(s.extra[x]);
}

// Sums the face normals into normals[] (zeroed; vertex v at 3 (v - base)) for the vertices
// [lo, hi) and normalises them: each vertex's sum runs in triangle order, whoever owns it.
inline void vertex_normals_body(const Mesh& mesh, const TriangleSpan& span, size_t lo, size_t hi,
                                double* normals, size_t base) {
  const float* p = mesh.positions.data();
  for_each_triangle(span, [&](size_t f) {
    const uint32_t* t = &mesh.triangles[3 * f];
    if (!owns(t[0], lo, hi) && !owns(t[1], lo, hi) && !owns(t[2], lo, hi)) return;
    double fn[3];
    face_normal(p, t, fn);
    for (int c = 0; c < 3; ++c)
      if (owns(t[c], lo, hi))
        for (int k = 0; k < 3; ++k) normals[3 * (t[c] - base) + k] += fn[k];
  });
  for (size_t v = lo; v < hi; ++v) {
    double* nv = &normals[3 * (v - base)];
    double len = std::sqrt(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]);
    if (len > 0 && std::isfinite(len)) {
      nv[0] /= len, nv[1] /= len, nv[2] /= len;
    } else {
      nv[0] = nv[1] = nv[2] = 0.0;
    }
  }
}

// The term of edge (i, j) in vertex i's curvature sum: k_ij |T_ij|^2, with 0 where the edge
// has zero length or is parallel to N_i.
inline double edge_term(const float* p, const double* ni, uint32_t i, uint32_t j) {
  double d[3] = {double(p[3 * j]) - p[3 * i], double(p[3 * j + 1]) - p[3 * i + 1],
                 double(p[3 * j + 2]) - p[3 * i + 2]};
  double len2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  if (!(len2 > 0)) return 0.0;
  double nd = ni[0] * d[0] + ni[1] * d[1] + ni[2] * d[2];
  double tangential2 = len2 - nd * nd;  // |(I - N N^T)(v_i - v_j)|^2
  if (!(tangential2 > 1e-12 * len2)) return 0.0;
  return 2.0 * nd / len2;
}

// Taubin 1995 as SPEC 1 fixes it: H_i = sum_j w_ij k_ij |T_ij|^2, where |T_ij|^2 is 1 unless
// the edge is of zero length or parallel to N_i (then the term adds 0).
inline double vertex_mean_curvature(const Mesh& mesh, const Adjacency& adj,
                                    const double* normals, size_t i) {
  const float* p = mesh.positions.data();
  const double* ni = &normals[3 * i];
  double total_area = 0.0, sum = 0.0;
  for (uint32_t e = adj.offsets[i]; e < adj.offsets[i + 1]; ++e) {
    const double w = adj.edge_area[e];
    total_area += w;
    const double k = edge_term(p, ni, uint32_t(i), adj.neighbors[e]);
    if (k != 0.0) sum += w * k;
  }
  return total_area > 0 ? sum / total_area : 0.0;
}

inline void mean_curvature_body(const Mesh& mesh, const Adjacency& adj, const double* normals,
                                size_t begin, size_t end, double* H) {
  for (size_t i = begin; i < end; ++i) H[i] = vertex_mean_curvature(mesh, adj, normals, i);
}

// The same sums taken over the triangles (mean_curvature_faces): a triangle of area A
// gives each corner i, for each of its two edges (i, j), A to the area and A k_ij to the
// sum; an edge's areas are thus added per triangle instead of first per edge. Triangles
// with a repeated corner have area 0 and add nothing, as the 1-rings skip them.
inline void curvature_sums_body(const Mesh& mesh, const TriangleSpan& span, const double* normals,
                                size_t lo, size_t hi, double* sum, double* area, size_t base) {
  const float* p = mesh.positions.data();
  for_each_triangle(span, [&](size_t f) {
    const uint32_t* t = &mesh.triangles[3 * f];
    if (!owns(t[0], lo, hi) && !owns(t[1], lo, hi) && !owns(t[2], lo, hi)) return;
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return;
    double fn[3];
    face_normal(p, t, fn);
    // The area as build_adjacency() takes it.
    const double A = 0.5 * std::sqrt(fn[0] * fn[0] + fn[1] * fn[1] + fn[2] * fn[2]);
    for (int c = 0; c < 3; ++c) {
      const uint32_t i = t[c];
      if (!owns(i, lo, hi)) continue;
      const size_t at = i - base;
      const double* ni = &normals[3 * at];
      area[at] += A + A;
      const double k1 = edge_term(p, ni, i, t[(c + 1) % 3]), k2 = edge_term(p, ni, i, t[(c + 2) % 3]);
      if (k1 != 0.0) sum[at] += A * k1;
      if (k2 != 0.0) sum[at] += A * k2;
    }
  });
  for (size_t at = 0; at < hi - lo; ++at) {
    const size_t i = lo - base + at;
    sum[i] = area[i] > 0 ? sum[i] / area[i] : 0.0;
  }
}

MESHSAL_TARGET_BASELINE void vertex_normals_baseline(const Mesh& mesh, const TriangleSpan& span, size_t lo,
                                                     size_t hi, double* normals, size_t base) {
  vertex_normals_body(mesh, span, lo, hi, normals, base);
}
MESHSAL_TARGET_BASELINE void mean_curvature_baseline(const Mesh& mesh, const Adjacency& adj,
                                                     const double* normals, size_t begin,
                                                     size_t end, double* H) {
  mean_curvature_body(mesh, adj, normals, begin, end, H);
}
MESHSAL_TARGET_BASELINE void curvature_sums_baseline(const Mesh& mesh, const TriangleSpan& span,
                                                     const double* normals, size_t lo, size_t hi,
                                                     double* sum, double* area, size_t base) {
  curvature_sums_body(mesh, span, normals, lo, hi, sum, area, base);
}
#if MESHSAL_HAVE_AVX2_COPIES
MESHSAL_TARGET_AVX2 void vertex_normals_avx2(const Mesh& mesh, const TriangleSpan& span, size_t lo,
                                             size_t hi, double* normals, size_t base) {
  vertex_normals_body(mesh, span, lo, hi, normals, base);
}
MESHSAL_TARGET_AVX2 void mean_curvature_avx2(const Mesh& mesh, const Adjacency& adj,
                                             const double* normals, size_t begin, size_t end,
                                             double* H) {
  mean_curvature_body(mesh, adj, normals, begin, end, H);
}
MESHSAL_TARGET_AVX2 void curvature_sums_avx2(const Mesh& mesh, const TriangleSpan& span,
                                             const double* normals, size_t lo, size_t hi, double* sum,
                                             double* area, size_t base) {
  curvature_sums_body(mesh, span, normals, lo, hi, sum, area, base);
}
#endif

}  // namespace

std::vector<double> vertex_normals(const Mesh& mesh, unsigned threads) {
  std::vector<double> normals(3 * mesh.vertex_count(), 0.0);
  auto body = vertex_normals_baseline;
#if MESHSAL_HAVE_AVX2_COPIES
  if (cpu_path() == CpuPath::avx2) body = vertex_normals_avx2;
#endif
  parallel_for_owned(mesh.vertex_count(), threads,
                     [&](size_t lo, size_t hi) { body(mesh, all_triangles(mesh), lo, hi, normals.data(), 0); });
  return normals;
}

std::vector<double> mean_curvature(const Mesh& mesh, const Adjacency& adjacency,
                                   const std::vector<double>& normals, unsigned threads) {
  std::vector<double> H(mesh.vertex_count(), 0.0);
  auto body = mean_curvature_baseline;
#if MESHSAL_HAVE_AVX2_COPIES
  if (cpu_path() == CpuPath::avx2) body = mean_curvature_avx2;
#endif
  parallel_for(H.size(), threads, 4096, [&](size_t begin, size_t end) {
    body(mesh, adjacency, normals.data(), begin, end, H.data());
  });
  return H;
}

void mean_curvature_at(const Mesh& mesh, const std::vector<uint32_t>& vertices, double* H, unsigned threads) {
  const size_t nv = mesh.vertex_count();
  std::vector<uint8_t> wanted(nv, 0);
  for (uint32_t v : vertices) wanted[v] = 1;
  // The triangles that hold a listed vertex, in order, and every vertex they name.
  std::vector<uint32_t> tris;
  std::vector<uint32_t> index(nv, UINT32_MAX);
  for (size_t f = 0; f < mesh.triangle_count(); ++f) {
    const uint32_t* t = &mesh.triangles[3 * f];
    if (!wanted[t[0]] && !wanted[t[1]] && !wanted[t[2]]) continue;
    tris.insert(tris.end(), t, t + 3);
    for (int c = 0; c < 3; ++c) index[t[c]] = 0;
  }
  for (uint32_t v : vertices) index[v] = 0;
  // Renumbered in increasing order: neighbour lists sort as in the whole mesh.
  Mesh part;
  for (size_t v = 0; v < nv; ++v)
    if (index[v] == 0) {
      index[v] = uint32_t(part.vertex_count());
      part.positions.insert(part.positions.end(), &mesh.positions[3 * v], &mesh.positions[3 * v + 3]);
    }
  part.triangles.reserve(tris.size());
  for (uint32_t v : tris) part.triangles.push_back(index[v]);
  const std::vector<double> h =
      mean_curvature(part, build_adjacency(part, threads), vertex_normals(part, threads), threads);
  for (uint32_t v : vertices) H[v] = h[index[v]];
}

std::vector<double> mean_curvature_faces(const Mesh& mesh, const std::vector<double>& normals,
                                         unsigned threads) {
  std::vector<double> H(mesh.vertex_count(), 0.0);
  std::vector<double> area(mesh.vertex_count(), 0.0);
  auto body = curvature_sums_baseline;
#if MESHSAL_HAVE_AVX2_COPIES
  if (cpu_path() == CpuPath::avx2) body = curvature_sums_avx2;
#endif
  parallel_for_owned(mesh.vertex_count(), threads, [&](size_t lo, size_t hi) {
    body(mesh, all_triangles(mesh), normals.data(), lo, hi, H.data(), area.data(), 0);
  });
  return H;
}

namespace {

// For each of `ranges` vertex ranges [n r / ranges, n (r + 1) / ranges): the triangles that
// touch it, as a span (TriangleSpan) holding them all. A triangle with every corner in one
// range widens that range's block; one with corners in two ranges goes to the shared list
// of crossing triangles, which every range visits (in index order with its block, so each
// vertex still sees its triangles in index order). On Morton-sorted triangles a range's
// block is the stretch of its own cells, and few triangles cross.
std::vector<TriangleSpan> range_spans(const Mesh& mesh, size_t ranges, unsigned threads,
                                      std::vector<uint32_t>* crossing) {
  const size_t n = mesh.vertex_count(), nt = mesh.triangle_count();
  const uint32_t* t = mesh.triangles.data();
  const double scale = double(ranges) / double(n);
  auto range_of = [&](uint32_t v) {
    size_t r = std::min(ranges - 1, size_t(double(v) * scale));
    while (r + 1 < ranges && n * (r + 1) / ranges <= v) ++r;
    while (r > 0 && n * r / ranges > v) --r;
    return r;
  };
  // Per chunk of triangles: each range's first and last whole triangle, the crossing ones.
  struct Chunk {
    size_t begin;
    std::vector<size_t> first, last;
    std::vector<uint32_t> cross;
  };
  std::vector<Chunk> chunks;
  std::mutex lock;
  parallel_for(nt, threads, 1 << 16, [&](size_t begin, size_t end) {
    Chunk c{begin, std::vector<size_t>(ranges, SIZE_MAX), std::vector<size_t>(ranges, 0), {}};
    for (size_t f = begin; f < end; ++f) {
      const uint32_t* tf = &t[3 * f];
      const size_t a = range_of(std::min({tf[0], tf[1], tf[2]})), b = range_of(std::max({tf[0], tf[1], tf[2]}));
      if (a != b) {
        c.cross.push_back(uint32_t(f));
      } else {
        c.first[a] = std::min(c.first[a], f);
        c.last[a] = f;
      }
    }
    std::lock_guard<std::mutex> hold(lock);
    chunks.push_back(std::move(c));
  });
  std::sort(chunks.begin(), chunks.end(), [](const Chunk& x, const Chunk& y) { return x.begin < y.begin; });
  std::vector<size_t> first(ranges, SIZE_MAX), last(ranges, 0);
  crossing->clear();
  for (const Chunk& c : chunks) {
    for (size_t r = 0; r < ranges; ++r)
      if (c.first[r] != SIZE_MAX) first[r] = std::min(first[r], c.first[r]), last[r] = std::max(last[r], c.last[r]);
    crossing->insert(crossing->end(), c.cross.begin(), c.cross.end());
  }
  std::vector<TriangleSpan> spans(ranges);
  for (size_t r = 0; r < ranges; ++r)
    spans[r] = {first[r] == SIZE_MAX ? 0 : first[r], first[r] == SIZE_MAX ? 0 : last[r] + 1, crossing->data(),
                crossing->size()};
  return spans;
}

}  // namespace

std::vector<double> mean_curvature_morton(const Mesh& mesh, const BoundingBox& box, unsigned threads) {
  MortonOrder m = morton_order(mesh, box, threads);
  // The triangles by the Morton cell (32 per axis) of their lowest-coded corner, ties in
  // input order: each vertex's triangles then come in an order that depends on the
  // positions and the input order alone, the same in a tile as in the whole mesh.
  for (uint32_t& c : m.code) c >>= 3 * (kMortonBits - 5);
  const Mesh curve = renumbered_mesh(mesh, m.order, m.code, nullptr, threads);
  std::vector<uint32_t>().swap(m.code);
  // vertex_normals and mean_curvature_faces on the copy, a range of vertices at a time with
  // the range's own normals and sums (instead of whole-mesh normals and sums, 40 bytes per
  // vertex on top of the copy), each range visiting only its block of the sorted triangles
  // and those that cross into it from another range (range_spans): the same bits, each
  // vertex summed in the copy's triangle order either way.
  auto normals_body = vertex_normals_baseline;
  auto sums_body = curvature_sums_baseline;
#if MESHSAL_HAVE_AVX2_COPIES
  if (cpu_path() == CpuPath::avx2) normals_body = vertex_normals_avx2, sums_body = curvature_sums_avx2;
#endif
  const size_t n = curve.vertex_count();
  // Ranges of 2^16 to 2^17 vertices, at least 16 a thread: each range's arrays are 40 bytes
  // a vertex, held by every thread at once (at most 2.5 bytes a vertex in all).
  const size_t ranges = std::max<size_t>({size_t(1), std::min<size_t>(16 * resolve_threads(threads), n >> 16),
                                          (n + (size_t(1) << 17) - 1) >> 17});
  std::vector<uint32_t> crossing;
  const std::vector<TriangleSpan> spans = range_spans(curve, ranges, threads, &crossing);
  std::vector<double> H(n);
  parallel_for(ranges, threads, 1, [&](size_t begin, size_t end) {
    for (size_t r = begin; r < end; ++r) {
      const size_t lo = n * r / ranges, hi = n * (r + 1) / ranges;
      std::vector<double> normals(3 * (hi - lo), 0.0), sum(hi - lo, 0.0), area(hi - lo, 0.0);
      normals_body(curve, spans[r], lo, hi, normals.data(), lo);
      sums_body(curve, spans[r], normals.data(), lo, hi, sum.data(), area.data(), lo);
      for (size_t i = lo; i < hi; ++i) H[m.order[i]] = sum[i - lo];
    }
  });
  return H;
}

}  // namespace meshsal
