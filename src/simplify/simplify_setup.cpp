// meshsal (internal): the simplifier's setup (State::init), see simplify_state.h.
#include <algorithm>
#include <cmath>
#include <string>

#include "core/mesh_points.h"
#include "core/parallel.h"
#include "simplify/simplify.h"
#include "simplify/simplify_state.h"

namespace meshsal {
namespace detail {

namespace {

// The 10 low bits of x spread out to every third bit (bit i to bit 3i): interleaving three
// of them gives a 30-bit Morton code.
inline uint32_t spread_bits(uint32_t x) {
  x &= 0x3ffu;
  x = (x | (x << 16)) & 0x030000ffu;
  x = (x | (x << 8)) & 0x0300f00fu;
  x = (x | (x << 4)) & 0x030c30c3u;
  x = (x | (x << 2)) & 0x09249249u;
  return x;
}

}  // namespace

void State::init(const Mesh& mesh, const SimplifyOptions& options, const std::vector<double>* w,
                 std::vector<Entry>* edges) {
  take_input(mesh, options, w);
  order_vertices(mesh);
  build_fans_and_quadrics();
  std::vector<uint32_t> unique_edges_a, unique_edges_b;
  build_edges(options.border_weight, &unique_edges_a, &unique_edges_b);
  if (w) {
    plain.resize(nv);
    for (size_t v = 0; v < nv; ++v) plain[v] = {vert[v].q, vert[v].plane_weight};
  }
  if (w)
    for (size_t v = 0; v < nv; ++v) {
      vert[v].q *= (*w)[order[v]];
      vert[v].plane_weight *= (*w)[order[v]];
    }
  if (options.target_error > 0) max_error2 = options.target_error * options.target_error;
  take_locks_seams_and_attributes(mesh, options.lock_border);
  changed.assign(nv, 0);
  marks.reset(nv);
  for (size_t v = 0; v < nv; ++v) border_vertices += alive[v] && border[v];

  if (edges) {
    edges->resize(unique_edges_a.size());
    // Independent per edge: on all cores (a tenth of the whole run on one).
    parallel_for(unique_edges_a.size(), options.threads, 8192, [&](size_t begin, size_t end) {
      double tmp[3];
      for (size_t i = begin; i < end; ++i) {
        const uint32_t a = unique_edges_a[i], b = unique_edges_b[i];
        (*edges)[i] = make_entry(cost(a, b, tmp), a, b, 0);
      }
    });
  }
}

void State::take_input(const Mesh& mesh, const SimplifyOptions& options,
                       const std::vector<double>* w) {
  mesh_in = &mesh;
  nv = mesh.vertex_count();
  input_positions = mesh.positions.data();
  const size_t nt_in = mesh.triangle_count();
  for (size_t i = 0; i < mesh.triangles.size(); ++i)
    if (mesh.triangles[i] >= nv)
      throw Error("simplify: triangle " + std::to_string(i / 3) + " has a vertex index out of range");
  if (w) {
    if (w->size() != nv)
      throw Error("simplify: " + std::to_string(w->size()) + " vertex weights for a mesh of " +
                  std::to_string(nv) + " vertices");
    for (double x : *w)
      if (!(x >= 0) || !std::isfinite(x))
        throw Error("simplify: vertex weights must be finite and >= 0");
  }
  // Triangles with a repeated index are not part of the surface: drop them.
  // Each kept triangle's material goes with it (a collapse never changes it).
  const bool materials = !mesh.triangle_material.empty();
  if (materials && mesh.triangle_material.size() != nt_in)
    throw Error("simplify: triangle_material has " + std::to_string(mesh.triangle_material.size()) +
                " entries for " + std::to_string(nt_in) + " triangles");
  std::vector<uint32_t>& tri = fans.corners;
  tri.reserve(3 * nt_in);
  for (size_t t = 0; t < nt_in; ++t) {
    const uint32_t* v = &mesh.triangles[3 * t];
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) continue;
    tri.insert(tri.end(), v, v + 3);
    if (materials) tri_material.push_back(mesh.triangle_material[t]);
  }
  const size_t nt = tri.size() / 3;
  faces = nt;
  target = resolve_target_faces(options, nt);
  min_cos = options.min_normal_cos;
  record = options.record_collapses;
}

void State::order_vertices(const Mesh& mesh) {
  // Internal coordinates: centred on the bounding box and scaled to unit diagonal, so that
  // the relative tolerances below mean the same on every mesh.
  alive.assign(nv, 0);
  for (uint32_t v : fans.corners) alive[v] = 1;
  for (size_t i = 0; i < 3 * nv; ++i)
    if (alive[i / 3] && !std::isfinite(mesh.positions[i]))
      throw Error("simplify: vertex " + std::to_string(i / 3) + " is not finite");
  const BoundingBox box = bounding_box(mesh.positions.data(), nv, alive.data());
  const double* lo = box.min;
  const double* hi = box.max;
  const double diag = box.diagonal();
  for (int k = 0; k < 3; ++k) center[k] = 0.5 * (lo[k] + hi[k]);
  scale = diag > 0 ? 1 / diag : 1;
  // Internal vertex ids follow a Morton curve, so that the vertices of one neighbourhood sit
  // close together in memory: the collapse order jumps around the mesh, and this keeps each
  // collapse on few cache lines. Unreferenced vertices go last.
  order.resize(nv);
  {
    std::vector<uint32_t> code(nv);
    const double inv_ext[3] = {hi[0] > lo[0] ? 1 / (hi[0] - lo[0]) : 0, hi[1] > lo[1] ? 1 / (hi[1] - lo[1]) : 0,
                               hi[2] > lo[2] ? 1 / (hi[2] - lo[2]) : 0};
    for (size_t v = 0; v < nv; ++v) {
      uint64_t c = 0;
      if (alive[v]) {
        uint32_t q[3];
        for (int k = 0; k < 3; ++k)
          q[k] = uint32_t(std::min(1.0, std::max(0.0, (mesh.positions[3 * v + k] - lo[k]) * inv_ext[k])) * 1023.0);
        c = (spread_bits(q[0]) << 2) | (spread_bits(q[1]) << 1) | spread_bits(q[2]);
      } else {
        c = uint64_t(1) << 30;  // after every 30-bit code
      }
      code[v] = uint32_t(c);
      order[v] = uint32_t(v);
    }
    // Stable LSD radix sort on the 31-bit codes (11 + 10 + 10 bits): the order a stable
    // comparison sort gives, several times faster.
    std::vector<uint32_t> tmp(nv), count;
    for (int shift : {0, 11, 21}) {
      const uint32_t buckets = shift == 0 ? 2048 : 1024, mask = buckets - 1;
      count.assign(buckets + 1, 0);
      for (uint32_t v : order) ++count[((code[v] >> shift) & mask) + 1];
      for (uint32_t i = 0; i < buckets; ++i) count[i + 1] += count[i];
      for (uint32_t v : order) tmp[count[(code[v] >> shift) & mask]++] = v;
      order.swap(tmp);
    }
  }
  inv.resize(nv);
  for (size_t i = 0; i < nv; ++i) inv[order[i]] = uint32_t(i);
  for (uint32_t& v : fans.corners) v = inv[v];
  {
    std::vector<uint8_t> a2(nv);
    for (size_t i = 0; i < nv; ++i) a2[i] = alive[order[i]];
    alive.swap(a2);
  }
  vert.assign(nv, VertexRecord{});
  for (size_t i = 0; i < nv; ++i)
    for (int k = 0; k < 3; ++k)
      vert[i].p[k] = (mesh.positions[3 * size_t(order[i]) + k] - center[k]) * scale;
}

void State::build_fans_and_quadrics() {
  fans.build(nv);
  const std::vector<uint32_t>& tri = fans.corners;
  // Each vertex sums its triangles' quadrics in triangle order.
  for (size_t t = 0; t < tri.size() / 3; ++t) {
    const uint32_t* v = &tri[3 * t];
    const Quadric q = triangle_quadric(p(v[0]), p(v[1]), p(v[2]));
    const double area = q.a00 + q.a11 + q.a22;  // the trace: area times |n|^2
    for (int k = 0; k < 3; ++k) {
      vert[v[k]].q += q;
      vert[v[k]].plane_weight += area;
    }
  }
}

void State::build_edges(double border_weight, std::vector<uint32_t>* edge_a,
                        std::vector<uint32_t>* edge_b) {
  // Edges from the triangle runs: for each vertex a, its higher neighbours b, with the
  // number of triangles on (a, b) counted in per-vertex scratch (stamped with a, so nothing
  // is cleared between vertices). One triangle is a border edge, more than two a
  // non-manifold edge. Border quadrics are added in the order of (a, b), as a sort of all
  // edges would give. No branches in the fan loop: vertices are in Morton order, so the
  // scratch entries of a's neighbours are close in memory, and which of them was seen
  // before is a coin toss.
  border.assign(nv, 0);
  std::vector<uint32_t>& unique_edges_a = *edge_a;
  std::vector<uint32_t>& unique_edges_b = *edge_b;
  const std::vector<uint32_t>& tri = fans.corners;
  const size_t nt = tri.size() / 3;
  unique_edges_a.reserve(nt * 3 / 2 + 16);
  unique_edges_b.reserve(nt * 3 / 2 + 16);
  // Per neighbour u of a: the vertex a it was last seen from, the triangles on (a, u), and
  // the last of them with the corner where the edge starts: one record, one cache line.
  struct Seen {
    uint32_t from, count, tri, corner;
  };
  std::vector<Seen> seen(nv, Seen{UINT32_MAX, 0, 0, 0});
  std::vector<uint32_t> higher, border_b;
  for (uint32_t a = 0; a < nv; ++a) {
    const uint32_t deg_a = fans.fan_size(a);
    if (higher.size() < 2 * size_t(deg_a)) higher.resize(2 * size_t(deg_a));
    size_t n = 0;
    for (uint32_t t : fans.fan(a)) {
      const uint32_t* v = &tri[3 * size_t(t)];
      const uint32_t k = uint32_t(v[1] == a) + 2 * uint32_t(v[2] == a);
      const uint32_t u1 = v[(k + 1) % 3], u2 = v[(k + 2) % 3];
      // edge a -> u1 starts at corner k, edge u2 -> a at corner k + 2
      const uint32_t corner[2] = {k, (k + 2) % 3};
      const uint32_t ends[2] = {u1, u2};
      for (int e = 0; e < 2; ++e) {
        const uint32_t u = ends[e];
        Seen& s = seen[u];
        const bool fresh = s.from != a;
        s.from = a;
        s.count = fresh ? 1 : s.count + 1;
        s.tri = t;  // the triangle of a border edge (read only when it is the one)
        s.corner = corner[e];
        higher[n] = u;
        n += fresh & (u > a);
      }
    }
    border_b.clear();
    for (size_t i = 0; i < n; ++i) {
      const uint32_t b = higher[i], c = seen[b].count;
      if (c == 1) border_b.push_back(b);
      if (c > 2) border[a] = border[b] = 1;
      unique_edges_a.push_back(a);
      unique_edges_b.push_back(b);
    }
    std::sort(border_b.begin(), border_b.end());
    for (uint32_t b : border_b) {
      const uint32_t t = seen[b].tri, k = seen[b].corner;
      const uint32_t v0 = tri[3 * t + k], v1 = tri[3 * t + (k + 1) % 3], v2 = tri[3 * t + (k + 2) % 3];
      const Quadric q = border_quadric(p(v0), p(v1), p(v2), border_weight);
      vert[v0].q += q;
      vert[v1].q += q;
      vert[v0].plane_weight += q.a00 + q.a11 + q.a22;
      vert[v1].plane_weight += q.a00 + q.a11 + q.a22;
      border[a] = border[b] = 1;
    }
  }
}

void State::take_locks_seams_and_attributes(const Mesh& mesh, bool lock_border) {
  locked.assign(nv, 0);
  if (lock_border)
    for (size_t v = 0; v < nv; ++v) locked[v] = border[v];
  if (pinned) {
    if (pinned->size() != nv)
      throw Error("simplify: " + std::to_string(pinned->size()) + " pinned flags for a mesh of " +
                  std::to_string(nv) + " vertices");
    pin.resize(nv);
    for (size_t v = 0; v < nv; ++v) pin[v] = (*pinned)[order[v]] != 0;
    for (size_t v = 0; v < nv; ++v) locked[v] |= pin[v];
  }
  if (!mesh.position_vertex.empty()) seams.build(mesh.position_vertex, inv, fans.corners, lock_border, &locked);
  for (uint8_t x : locked) has_locks |= x != 0;
  attributes.take(mesh, order);
}

}  // namespace detail
}  // namespace meshsal
