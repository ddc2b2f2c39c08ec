#include "core/adjacency.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/parallel.h"
#include "core/vec3.h"

namespace meshsal {

static double triangle_area(const float* p, uint32_t a, uint32_t b, uint32_t c) {
  double e1[3], e2[3];
  for (int k = 0; k < 3; ++k) {
    e1[k] = double(p[3 * b + k]) - p[3 * a + k];
    e2[k] = double(p[3 * c + k]) - p[3 * a + k];
  }
  double n[3];
  cross3(e1, e2, n);
  return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

// Each vertex gathers its half-edges from the triangles around it, so the vertices are
// independent and run in parallel, and nothing of the size of all half-edges with their
// areas is held (that list was the largest buffer of a saliency run).
Adjacency build_adjacency(const Mesh& mesh, unsigned threads) {
  const size_t n = mesh.vertex_count();
  const size_t nt = mesh.triangle_count();
  const uint32_t* t = mesh.triangles.data();

  // The triangles around each vertex (CSR), each once per vertex, in triangle order. Each
  // thread owns a range of vertices and scans every triangle for its corners, so the lists
  // are the same whatever the thread count (done serially, this was a fifth of the
  // function's time on 2 cores: igea_loop2, 0.10 of 0.55 s).
  std::vector<uint32_t> around_start(n + 1, 0);
  // Calls at(corner, triangle) for each distinct corner in [lo, hi) of each triangle, in
  // triangle order.
  auto corners_in = [&](size_t lo, size_t hi, auto&& at) {
    for (size_t f = 0; f < nt; ++f) {
      const uint32_t* c = &t[3 * f];
      if (c[0] - lo < hi - lo) at(c[0], f);
      if (c[1] - lo < hi - lo && c[1] != c[0]) at(c[1], f);
      if (c[2] - lo < hi - lo && c[2] != c[0] && c[2] != c[1]) at(c[2], f);
    }
  };
  parallel_for_owned(n, threads, [&](size_t lo, size_t hi) {
    corners_in(lo, hi, [&](uint32_t v, size_t) { around_start[v + 1]++; });
  });
  for (size_t v = 0; v < n; ++v) around_start[v + 1] += around_start[v];
  std::vector<uint32_t> around(around_start[n]);
  std::vector<uint32_t> cursor(around_start.begin(), around_start.end() - 1);
  parallel_for_owned(n, threads, [&](size_t lo, size_t hi) {
    corners_in(lo, hi, [&](uint32_t v, size_t f) { around[cursor[v]++] = uint32_t(f); });
  });
  std::vector<uint32_t>().swap(cursor);

  std::vector<double> area(nt);
  parallel_for(nt, threads, 1 << 14, [&](size_t begin, size_t end) {
    for (size_t f = begin; f < end; ++f)
      area[f] = triangle_area(mesh.positions.data(), t[3 * f], t[3 * f + 1], t[3 * f + 2]);
  });

  // Vertex v's half-edges come from the triangles around it in triangle order: edge (a, b)
  // of a triangle gives a the neighbour b and b the neighbour a. Calls at(neighbour,
  // triangle) for each.
  auto half_edges = [&](size_t v, auto&& at) {
    for (uint32_t i = around_start[v]; i < around_start[v + 1]; ++i) {
      const uint32_t f = around[i];
      const uint32_t* c = &t[3 * f];
      for (int e = 0; e < 3; ++e) {
        const uint32_t a = c[e], b = c[(e + 1) % 3];
        if (a == b) continue;
        if (a == v) at(b, f);
        if (b == v) at(a, f);
      }
    }
  };

  // Two passes: the neighbour counts (hence the offsets), then the lists in place.
  Adjacency adj;
  adj.offsets.assign(n + 1, 0);
  // The counts: the distinct ends, from the indices alone (no areas loaded or moved).
  parallel_for(n, threads, 4096, [&](size_t begin, size_t end) {
    std::vector<uint32_t> ends;
    for (size_t v = begin; v < end; ++v) {
      ends.clear();
      half_edges(v, [&](uint32_t b, uint32_t) { ends.push_back(b); });
      std::sort(ends.begin(), ends.end());
      adj.offsets[v + 1] = uint32_t(std::unique(ends.begin(), ends.end()) - ends.begin());
    }
  });
  for (size_t v = 0; v < n; ++v) adj.offsets[v + 1] += adj.offsets[v];
  adj.neighbors.resize(adj.offsets[n]);
  adj.edge_area.resize(adj.offsets[n]);
  // The lists: the ends keyed by (neighbour, place among v's half-edges) and sorted, so that
  // an edge's areas are summed in triangle order (8-byte keys: sorting (neighbour, area)
  // pairs stably took twice as long).
  parallel_for(n, threads, 4096, [&](size_t begin, size_t end) {
    std::vector<uint64_t> keys;
    std::vector<double> areas;
    for (size_t v = begin; v < end; ++v) {
      keys.clear();
      areas.clear();
      half_edges(v, [&](uint32_t b, uint32_t f) {
        keys.push_back(uint64_t(b) << 32 | areas.size());
        areas.push_back(area[f]);
      });
      std::sort(keys.begin(), keys.end());
      uint32_t slot = adj.offsets[v];
      for (size_t k = 0; k < keys.size();) {
        const uint32_t b = uint32_t(keys[k] >> 32);
        double sum = areas[uint32_t(keys[k])];
        for (++k; k < keys.size() && uint32_t(keys[k] >> 32) == b; ++k) sum += areas[uint32_t(keys[k])];
        adj.neighbors[slot] = b;
        adj.edge_area[slot++] = sum;
      }
    }
  });
  return adj;
}

Adjacency build_adjacency_reference(const Mesh& mesh) {
  const size_t n = mesh.vertex_count();
  const uint32_t* t = mesh.triangles.data();
  struct Half {
    uint32_t from, to;
    size_t triangle;
    double area;
  };
  std::vector<Half> half;
  for (size_t f = 0; f < mesh.triangle_count(); ++f) {
    const double a = triangle_area(mesh.positions.data(), t[3 * f], t[3 * f + 1], t[3 * f + 2]);
    for (int e = 0; e < 3; ++e) {
      uint32_t x = t[3 * f + e], y = t[3 * f + (e + 1) % 3];
      if (x == y) continue;
      half.push_back({x, y, f, a});
      half.push_back({y, x, f, a});
    }
  }
  std::stable_sort(half.begin(), half.end(), [](const Half& x, const Half& y) {
    return std::make_pair(x.from, x.to) < std::make_pair(y.from, y.to);
  });
  Adjacency adj;
  adj.offsets.assign(n + 1, 0);
  for (size_t i = 0; i < half.size(); ++i) {
    if (i > 0 && half[i].from == half[i - 1].from && half[i].to == half[i - 1].to) {
      adj.edge_area.back() += half[i].area;
      continue;
    }
    adj.neighbors.push_back(half[i].to);
    adj.edge_area.push_back(half[i].area);
    adj.offsets[half[i].from + 1]++;
  }
  for (size_t v = 0; v < n; ++v) adj.offsets[v + 1] += adj.offsets[v];
  return adj;
}

}  // namespace meshsal
