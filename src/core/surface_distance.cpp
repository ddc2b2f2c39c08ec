// meshsal: point-to-surface distances over a triangle BVH, Hausdorff / RMS / salient error.
#include "core/model_frame.h"
#include "core/surface_distance.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <string>

#include "meshsal/meshsal.h"
#include "core/mesh_points.h"
#include "core/parallel.h"
#include "core/vec3.h"
#include "core/cancel.h"

namespace meshsal {

namespace {

double point_segment_distance_sq(const double p[3], const double a[3], const double b[3]) {
  const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double ap[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
  const double l2 = dot3(ab, ab);
  double t = l2 > 0 ? dot3(ap, ab) / l2 : 0;
  t = std::min(1.0, std::max(0.0, t));
  const double d[3] = {ap[0] - t * ab[0], ap[1] - t * ab[1], ap[2] - t * ab[2]};
  return dot3(d, d);
}

void check_mesh(const Mesh& mesh, const char* what) {
  if (mesh.triangle_count() == 0) throw Error(std::string(what) + " has no triangles");
  for (uint32_t v : mesh.triangles)
    if (v >= mesh.vertex_count())
      throw Error(std::string(what) + " has a vertex index out of range");
}

void corner(const Mesh& m, uint32_t v, double out[3]) {
  for (int k = 0; k < 3; ++k) out[k] = m.positions[3 * size_t(v) + k];
}

}  // namespace

double point_triangle_distance_sq(const double p[3], const double a[3], const double b[3],
                                  const double c[3]) {
  const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double ap[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
  const double d1 = dot3(ab, ap), d2 = dot3(ac, ap);
  if (d1 <= 0 && d2 <= 0) return dot3(ap, ap);
  const double bp[3] = {p[0] - b[0], p[1] - b[1], p[2] - b[2]};
  const double d3 = dot3(ab, bp), d4 = dot3(ac, bp);
  if (d3 >= 0 && d4 <= d3) return dot3(bp, bp);
  const double cp[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
  const double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
  if (d6 >= 0 && d5 <= d6) return dot3(cp, cp);
  const double vc = d1 * d4 - d3 * d2;
  const double vb = d5 * d2 - d1 * d6;
  const double va = d3 * d6 - d5 * d4;
  const double sum = va + vb + vc;
  // A degenerate triangle (sum = |ab x ac|^2 = 0) is its three edges.
  if (!(sum > 0))
    return std::min({point_segment_distance_sq(p, a, b), point_segment_distance_sq(p, b, c),
                     point_segment_distance_sq(p, a, c)});
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return point_segment_distance_sq(p, a, b);
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return point_segment_distance_sq(p, a, c);
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return point_segment_distance_sq(p, b, c);
  const double v = vb / sum, w = vc / sum;
  const double q[3] = {a[0] + ab[0] * v + ac[0] * w - p[0], a[1] + ab[1] * v + ac[1] * w - p[1],
                       a[2] + ab[2] * v + ac[2] * w - p[2]};
  return dot3(q, q);
}

TriangleBvh build_triangle_bvh(const Mesh& mesh) {
  check_mesh(mesh, "surface");
  const size_t nt = mesh.triangle_count();
  TriangleBvh bvh;
  bvh.order.resize(nt);
  std::iota(bvh.order.begin(), bvh.order.end(), 0u);
  std::vector<double> cen(3 * nt);
  for (size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k)
      cen[3 * t + k] = (double(mesh.positions[3 * size_t(mesh.triangles[3 * t]) + k]) +
                        mesh.positions[3 * size_t(mesh.triangles[3 * t + 1]) + k] +
                        mesh.positions[3 * size_t(mesh.triangles[3 * t + 2]) + k]) / 3;
  bvh.nodes.reserve(2 * (nt / 2 + 1));
  // Iterative build: (node, begin, end) work items.
  struct Item { uint32_t node, begin, end; };
  std::vector<Item> work;
  bvh.nodes.push_back({});
  work.push_back({0, 0, uint32_t(nt)});
  while (!work.empty()) {
    const Item it = work.back();
    work.pop_back();
    TriangleBvh::Node node;
    double clo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, chi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (int k = 0; k < 3; ++k) { node.lo[k] = HUGE_VAL; node.hi[k] = -HUGE_VAL; }
    for (uint32_t i = it.begin; i < it.end; ++i) {
      const uint32_t t = bvh.order[i];
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k) {
          const double x = mesh.positions[3 * size_t(mesh.triangles[3 * size_t(t) + c]) + k];
          node.lo[k] = std::min(node.lo[k], x);
          node.hi[k] = std::max(node.hi[k], x);
        }
      for (int k = 0; k < 3; ++k) {
        clo[k] = std::min(clo[k], cen[3 * t + k]);
        chi[k] = std::max(chi[k], cen[3 * t + k]);
      }
    }
    const uint32_t n = it.end - it.begin;
    if (n <= 4) {
      node.first = it.begin;
      node.count = n;
      bvh.nodes[it.node] = node;
      continue;
    }
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (chi[k] - clo[k] > chi[axis] - clo[axis]) axis = k;
    const uint32_t mid = it.begin + n / 2;
    std::nth_element(bvh.order.begin() + it.begin, bvh.order.begin() + mid,
                     bvh.order.begin() + it.end, [&](uint32_t x, uint32_t y) {
                       return cen[3 * size_t(x) + axis] < cen[3 * size_t(y) + axis];
                     });
    node.first = uint32_t(bvh.nodes.size());
    node.count = 0;
    bvh.nodes[it.node] = node;
    bvh.nodes.push_back({});
    bvh.nodes.push_back({});
    work.push_back({node.first, it.begin, mid});
    work.push_back({node.first + 1, mid, it.end});
  }
  bvh.corners.resize(9 * nt);
  for (size_t i = 0; i < nt; ++i)
    for (int c = 0; c < 3; ++c)
      corner(mesh, mesh.triangles[3 * size_t(bvh.order[i]) + c], &bvh.corners[9 * i + 3 * c]);
  return bvh;
}

static inline double box_distance_sq(const TriangleBvh::Node& n, const double p[3]) {
  double d = 0;
  for (int k = 0; k < 3; ++k) {
    const double e = p[k] < n.lo[k] ? n.lo[k] - p[k] : (p[k] > n.hi[k] ? p[k] - n.hi[k] : 0);
    d += e * e;
  }
  return d;
}

double surface_distance(const TriangleBvh& bvh, const double p[3]) {
  double best = HUGE_VAL;
  uint32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const TriangleBvh::Node& n = bvh.nodes[stack[--top]];
    if (box_distance_sq(n, p) >= best) continue;
    if (n.count > 0) {
      for (uint32_t i = n.first; i < n.first + n.count; ++i) {
        const double* c = &bvh.corners[9 * size_t(i)];
        best = std::min(best, point_triangle_distance_sq(p, c, c + 3, c + 6));
      }
      continue;
    }
    const double dl = box_distance_sq(bvh.nodes[n.first], p);
    const double dr = box_distance_sq(bvh.nodes[n.first + 1], p);
    // Push the farther child first so that the nearer one is searched first.
    if (dl < dr) {
      if (dr < best) stack[top++] = n.first + 1;
      if (dl < best) stack[top++] = n.first;
    } else {
      if (dl < best) stack[top++] = n.first;
      if (dr < best) stack[top++] = n.first + 1;
    }
  }
  return std::sqrt(best);
}

ClosestTriangle closest_triangle(const TriangleBvh& bvh, const double p[3]) {
  // As surface_distance, but boxes at exactly the best distance are searched too, so that
  // of equally close triangles the lowest index wins whatever the tree's order.
  double best = HUGE_VAL;
  uint32_t best_t = UINT32_MAX;
  std::vector<uint32_t> stack{0};
  while (!stack.empty()) {
    const TriangleBvh::Node& n = bvh.nodes[stack.back()];
    stack.pop_back();
    if (box_distance_sq(n, p) > best) continue;
    if (n.count > 0) {
      for (uint32_t i = n.first; i < n.first + n.count; ++i) {
        const double* c = &bvh.corners[9 * size_t(i)];
        const double d = point_triangle_distance_sq(p, c, c + 3, c + 6);
        if (d < best || (d == best && bvh.order[i] < best_t)) best = d, best_t = bvh.order[i];
      }
      continue;
    }
    const double dl = box_distance_sq(bvh.nodes[n.first], p);
    const double dr = box_distance_sq(bvh.nodes[n.first + 1], p);
    if (dl < dr) {
      if (dr <= best) stack.push_back(n.first + 1);
      if (dl <= best) stack.push_back(n.first);
    } else {
      if (dl <= best) stack.push_back(n.first);
      if (dr <= best) stack.push_back(n.first + 1);
    }
  }
  return {std::sqrt(best), best_t};
}

double surface_distance_bruteforce(const Mesh& mesh, const double p[3]) {
  check_mesh(mesh, "surface");
  double best = HUGE_VAL;
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    double a[3], b[3], c[3];
    corner(mesh, mesh.triangles[3 * t], a);
    corner(mesh, mesh.triangles[3 * t + 1], b);
    corner(mesh, mesh.triangles[3 * t + 2], c);
    best = std::min(best, point_triangle_distance_sq(p, a, b, c));
  }
  return std::sqrt(best);
}

std::vector<double> sample_surface(const Mesh& mesh, size_t face_samples) {
  check_mesh(mesh, "surface");
  std::vector<uint8_t> used(mesh.vertex_count(), 0);
  for (uint32_t v : mesh.triangles) used[v] = 1;
  std::vector<double> pts;
  for (size_t v = 0; v < used.size(); ++v)
    if (used[v])
      for (int k = 0; k < 3; ++k) pts.push_back(mesh.positions[3 * v + k]);
  const size_t nt = mesh.triangle_count();
  std::vector<double> area(nt);
  double total = 0;
  for (size_t t = 0; t < nt; ++t) {
    double a[3], b[3], c[3];
    corner(mesh, mesh.triangles[3 * t], a);
    corner(mesh, mesh.triangles[3 * t + 1], b);
    corner(mesh, mesh.triangles[3 * t + 2], c);
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3];
    cross3(u, w, n);
    area[t] = 0.5 * std::sqrt(dot3(n, n));
    total += area[t];
  }
  if (!(total > 0) || face_samples == 0) return pts;
  pts.reserve(pts.size() + 3 * (face_samples + 1));
  const double g = 1.32471795724474602596;  // plastic number: the R2 sequence
  const double a1 = 1 / g, a2 = 1 / (g * g);
  double cum = 0;
  size_t emitted = 0, seq = 0;
  for (size_t t = 0; t < nt; ++t) {
    cum += area[t] / total * double(face_samples);
    const size_t upto = std::min(face_samples, size_t(std::floor(cum + 1e-9)));
    if (upto <= emitted) continue;
    double a[3], b[3], c[3];
    corner(mesh, mesh.triangles[3 * t], a);
    corner(mesh, mesh.triangles[3 * t + 1], b);
    corner(mesh, mesh.triangles[3 * t + 2], c);
    for (; emitted < upto; ++emitted, ++seq) {
      double u = std::fmod(0.5 + a1 * double(seq), 1.0), v = std::fmod(0.5 + a2 * double(seq), 1.0);
      if (u + v > 1) { u = 1 - u; v = 1 - v; }
      for (int k = 0; k < 3; ++k) pts.push_back(a[k] + u * (b[k] - a[k]) + v * (c[k] - a[k]));
    }
  }
  return pts;
}

namespace {

struct DirectionStats { double max = 0, rms = 0; };

// Distances of all points to the surface, in parallel.
std::vector<double> distances(const std::vector<double>& pts, const TriangleBvh& bvh,
                              unsigned threads) {
  const size_t n = pts.size() / 3;
  std::vector<double> d(n);
  // parallel_for: a thread that cannot be started means fewer threads, not std::terminate.
  parallel_for(n, n < 4096 ? 1 : threads, 1024, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) d[i] = surface_distance(bvh, &pts[3 * i]);
  });
  return d;
}

DirectionStats stats(const std::vector<double>& d) {
  DirectionStats s;
  double sum = 0;
  for (double x : d) { s.max = std::max(s.max, x); sum += x * x; }
  s.rms = d.empty() ? 0 : std::sqrt(sum / double(d.size()));
  return s;
}

// Indices of the top `fraction` of mesh points by saliency (ties: lower index first).
std::vector<uint32_t> salient_vertices(const Mesh& mesh, const std::vector<double>& saliency,
                                       double fraction) {
  if (saliency.size() != mesh.vertex_count())
    throw Error("saliency has " + std::to_string(saliency.size()) + " values for a mesh of " +
                std::to_string(mesh.vertex_count()) + " vertices");
  if (!(fraction > 0 && fraction <= 1)) throw Error("salient fraction must be in (0, 1]");
  std::vector<uint8_t> used(mesh.vertex_count(), 0);
  for (uint32_t v : mesh.triangles) used[v] = 1;
  std::vector<uint32_t> idx;
  for (size_t v = 0; v < used.size(); ++v)
    if (used[v]) idx.push_back(uint32_t(v));
  const size_t k = std::max<size_t>(1, size_t(std::ceil(fraction * double(idx.size()))));
  std::partial_sort(idx.begin(), idx.begin() + std::min(k, idx.size()), idx.end(),
                    [&](uint32_t x, uint32_t y) {
                      return saliency[x] != saliency[y] ? saliency[x] > saliency[y] : x < y;
                    });
  idx.resize(std::min(k, idx.size()));
  return idx;
}

}  // namespace

double salient_region_error(const Mesh& mesh, const std::vector<double>& saliency,
                            const TriangleBvh& surface, double fraction, size_t* count) {
  const std::vector<uint32_t> idx = salient_vertices(mesh, saliency, fraction);
  double sum = 0;
  for (uint32_t v : idx) {
    double p[3];
    corner(mesh, v, p);
    sum += surface_distance(surface, p);
  }
  if (count) *count = idx.size();
  return idx.empty() ? 0 : sum / double(idx.size());
}

SurfaceComparison compare_surfaces(const Mesh& original, const Mesh& simplified_in,
                                   const std::vector<double>& saliency_values,
                                   const CompareOptions& options) {
  const std::vector<double>* saliency = saliency_values.empty() ? nullptr : &saliency_values;
  const CancelScope cancel(options.cancel);
  check_mesh(original, "the original mesh");
  check_mesh(simplified_in, "the simplified mesh");
  // Two files have two origins: distances are taken in the original's local frame.
  const Mesh simplified = in_frame(simplified_in, original.origin);
  if (saliency && saliency->size() != original.vertex_count())
    throw Error("saliency has " + std::to_string(saliency->size()) +
                " values but the original mesh has " + std::to_string(original.vertex_count()) +
                " vertices");
  SurfaceComparison r;
  r.diagonal = mesh_points_bbox(original, referenced_vertices(original)).diagonal();
  const TriangleBvh simp_bvh = build_triangle_bvh(simplified);
  const TriangleBvh orig_bvh = build_triangle_bvh(original);
  const std::vector<double> fwd_pts = sample_surface(original, options.face_samples);
  const std::vector<double> bwd_pts = sample_surface(simplified, options.face_samples);
  const std::vector<double> fwd = distances(fwd_pts, simp_bvh, options.threads);
  const std::vector<double> bwd = distances(bwd_pts, orig_bvh, options.threads);
  const DirectionStats f = stats(fwd), b = stats(bwd);
  r.forward_max = f.max;
  r.forward_rms = f.rms;
  r.backward_max = b.max;
  r.backward_rms = b.rms;
  r.hausdorff = std::max(f.max, b.max);
  r.rms = std::max(f.rms, b.rms);
  r.forward_samples = fwd.size();
  r.backward_samples = bwd.size();
  if (saliency)
    r.salient_error = salient_region_error(original, *saliency, simp_bvh,
                                           options.salient_fraction, &r.salient_vertices);
  return r;
}

}  // namespace meshsal
