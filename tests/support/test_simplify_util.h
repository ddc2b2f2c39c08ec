// Checks shared by the simplification tests: topology and geometry of a result mesh.
#pragma once
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "cli/synthetic.h"
#include "meshsal/meshsal.h"

namespace simplify_test {

struct Topology {
  size_t border_edges = 0;          // undirected edges in exactly one triangle
  size_t nonmanifold_edges = 0;     // in more than two triangles
  size_t repeated_directed = 0;     // directed edges used twice (inconsistent orientation)
  size_t nonmanifold_vertices = 0;  // (closed meshes) link is not a single cycle
  size_t repeated_index = 0;        // triangles with a repeated vertex index
  size_t unreferenced = 0;          // vertices used by no triangle
};

inline Topology topology(const meshsal::Mesh& m) {
  Topology r;
  std::map<std::pair<uint32_t, uint32_t>, int> directed, undirected;
  std::vector<std::vector<std::pair<uint32_t, uint32_t>>> link(m.vertex_count());
  std::vector<uint8_t> used(m.vertex_count(), 0);
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const uint32_t* v = &m.triangles[3 * t];
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) r.repeated_index++;
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = v[k], b = v[(k + 1) % 3], c = v[(k + 2) % 3];
      used[a] = 1;
      directed[{a, b}]++;
      undirected[{std::min(a, b), std::max(a, b)}]++;
      link[a].push_back({b, c});
    }
  }
  for (auto& [e, n] : directed)
    if (n > 1) r.repeated_directed++;
  for (auto& [e, n] : undirected) {
    if (n == 1) r.border_edges++;
    if (n > 2) r.nonmanifold_edges++;
  }
  for (size_t v = 0; v < m.vertex_count(); ++v) {
    if (!used[v]) { r.unreferenced++; continue; }
    // The link of an interior vertex: follow b -> c from any start, must visit all edges.
    std::map<uint32_t, uint32_t> next;
    for (auto& [b, c] : link[v]) next[b] = c;
    if (next.size() != link[v].size()) { r.nonmanifold_vertices++; continue; }
    uint32_t start = link[v][0].first, x = start;
    size_t steps = 0;
    do {
      auto it = next.find(x);
      if (it == next.end()) break;  // open fan (border vertex): not checked further
      x = it->second;
      ++steps;
    } while (x != start && steps <= link[v].size());
    if (x == start && steps != link[v].size()) r.nonmanifold_vertices++;
  }
  return r;
}

inline void triangle_normal(const meshsal::Mesh& m, size_t t, double n[3], double centroid[3]) {
  const float* p[3];
  for (int k = 0; k < 3; ++k) p[k] = &m.positions[3 * size_t(m.triangles[3 * t + k])];
  const double e1[3] = {double(p[1][0]) - p[0][0], double(p[1][1]) - p[0][1], double(p[1][2]) - p[0][2]};
  const double e2[3] = {double(p[2][0]) - p[0][0], double(p[2][1]) - p[0][1], double(p[2][2]) - p[0][2]};
  n[0] = e1[1] * e2[2] - e1[2] * e2[1];
  n[1] = e1[2] * e2[0] - e1[0] * e2[2];
  n[2] = e1[0] * e2[1] - e1[1] * e2[0];
  for (int k = 0; k < 3; ++k) centroid[k] = (double(p[0][k]) + p[1][k] + p[2][k]) / 3;
}

// Smallest ratio 2*area / longest_edge^2 over the triangles (0 = a degenerate triangle).
inline double min_shape_ratio(const meshsal::Mesh& m) {
  double worst = HUGE_VAL;
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    double n[3], c[3];
    triangle_normal(m, t, n, c);
    double l2 = 0;
    for (int k = 0; k < 3; ++k) {
      const float* a = &m.positions[3 * size_t(m.triangles[3 * t + k])];
      const float* b = &m.positions[3 * size_t(m.triangles[3 * t + (k + 1) % 3])];
      const double d[3] = {double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2]};
      l2 = std::max(l2, d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    }
    worst = std::min(worst, std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) / l2);
  }
  return worst;
}

// Signed volume (divergence theorem); positive for a closed mesh with outward normals.
inline double signed_volume(const meshsal::Mesh& m) {
  double vol = 0;
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const float* a = &m.positions[3 * size_t(m.triangles[3 * t])];
    const float* b = &m.positions[3 * size_t(m.triangles[3 * t + 1])];
    const float* c = &m.positions[3 * size_t(m.triangles[3 * t + 2])];
    vol += (double(a[0]) * (double(b[1]) * c[2] - double(b[2]) * c[1]) -
            double(a[1]) * (double(b[0]) * c[2] - double(b[2]) * c[0]) +
            double(a[2]) * (double(b[0]) * c[1] - double(b[1]) * c[0])) / 6;
  }
  return vol;
}

// A plane of n x n quads with a bump, an attribute "u" (0.5 x + 0.25) and two materials
// (left and right of x = 0): what carried attributes and materials are tested on.
inline meshsal::Mesh attributed_plane(int n) {
  meshsal::Mesh m = meshsal::make_plane_with_bump(2.0, n, 0.4, 0.3);
  meshsal::VertexAttribute u{"u", {}};
  for (size_t v = 0; v < m.vertex_count(); ++v) u.values.push_back(m.positions[3 * v] * 0.5f + 0.25f);
  m.attributes.push_back(u);
  m.materials = {"left", "right"};
  for (size_t t = 0; t < m.triangle_count(); ++t)
    m.triangle_material.push_back(m.positions[3 * size_t(m.triangles[3 * t])] < 0 ? 0 : 1);
  return m;
}

}  // namespace simplify_test
