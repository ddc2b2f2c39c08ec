#include "core/adjacency.h"

#include <algorithm>
#include <cmath>

namespace meshsal {

static double triangle_area(const float* p, uint32_t a, uint32_t b, uint32_t c) {
  double e1[3], e2[3];
  for (int k = 0; k < 3; ++k) {
    e1[k] = double(p[3 * b + k]) - p[3 * a + k];
    e2[k] = double(p[3 * c + k]) - p[3 * a + k];
  }
  double nx = e1[1] * e2[2] - e1[2] * e2[1];
  double ny = e1[2] * e2[0] - e1[0] * e2[2];
  double nz = e1[0] * e2[1] - e1[1] * e2[0];
  return 0.5 * std::sqrt(nx * nx + ny * ny + nz * nz);
}

Adjacency build_adjacency(const Mesh& mesh) {
  const size_t n = mesh.vertex_count();
  const size_t nt = mesh.triangle_count();
  const uint32_t* t = mesh.triangles.data();

  // Counting sort of the directed half-edges (both directions of every triangle edge) by source.
  std::vector<uint32_t> count(n + 1, 0);
  for (size_t f = 0; f < nt; ++f)
    for (int e = 0; e < 3; ++e) {
      uint32_t a = t[3 * f + e], b = t[3 * f + (e + 1) % 3];
      if (a == b) continue;
      count[a + 1]++;
      count[b + 1]++;
    }
  for (size_t v = 0; v < n; ++v) count[v + 1] += count[v];
  std::vector<uint32_t> fill(count.begin(), count.end() - 1);
  std::vector<std::pair<uint32_t, double>> half(count[n]);
  for (size_t f = 0; f < nt; ++f) {
    uint32_t tri[3] = {t[3 * f], t[3 * f + 1], t[3 * f + 2]};
    double area = triangle_area(mesh.positions.data(), tri[0], tri[1], tri[2]);
    for (int e = 0; e < 3; ++e) {
      uint32_t a = tri[e], b = tri[(e + 1) % 3];
      if (a == b) continue;
      half[fill[a]++] = {b, area};
      half[fill[b]++] = {a, area};
    }
  }

  // Sort each vertex's list and merge duplicates, summing the areas of an edge's triangles.
  Adjacency adj;
  adj.offsets.assign(n + 1, 0);
  adj.neighbors.reserve(half.size() / 2);
  adj.edge_area.reserve(half.size() / 2);
  for (size_t v = 0; v < n; ++v) {
    auto begin = half.begin() + count[v], end = half.begin() + count[v + 1];
    std::sort(begin, end, [](const auto& x, const auto& y) { return x.first < y.first; });
    for (auto it = begin; it != end; ++it) {
      if (adj.neighbors.size() > adj.offsets[v] && adj.neighbors.back() == it->first)
        adj.edge_area.back() += it->second;
      else {
        adj.neighbors.push_back(it->first);
        adj.edge_area.push_back(it->second);
      }
    }
    adj.offsets[v + 1] = uint32_t(adj.neighbors.size());
  }
  return adj;
}

}  // namespace meshsal
