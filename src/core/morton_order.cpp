#include "core/morton_order.h"

#include <algorithm>
#include <cmath>

#include "core/counting_sort.h"
#include "core/parallel.h"
#include "core/radix_sort.h"

namespace meshsal {

uint64_t spread_bits_21(uint32_t x) {
  uint64_t v = x & 0x1fffffu;
  v = (v | (v << 32)) & 0x1f00000000ffffull;
  v = (v | (v << 16)) & 0x1f0000ff0000ffull;
  v = (v | (v << 8)) & 0x100f00f00f00f00full;
  v = (v | (v << 4)) & 0x10c30c30c30c30c3ull;
  v = (v | (v << 2)) & 0x1249249249249249ull;
  return v;
}

MortonOrder morton_order(const Mesh& mesh, const BoundingBox& box, unsigned threads) {
  constexpr int kBits = kMortonBits;
  const size_t n = mesh.vertex_count();
  const float* p = mesh.positions.data();
  const double* lo = box.min;
  double scale[3];
  // 2^10 steps per axis order a scan's neighbourhoods as well as 2^21 (a few vertices
  // per step on a surface, kept in index order) and sort in 3 passes instead of 6.
  for (int a = 0; a < 3; ++a)
    scale[a] = box.max[a] > box.min[a] ? double((1u << kBits) - 1) / (box.max[a] - box.min[a]) : 0.0;
  MortonOrder m;
  std::vector<uint32_t>& key = m.code;
  std::vector<uint32_t>& order = m.order;
  key.resize(n);
  order.resize(n);
  parallel_for(n, threads, 1 << 15, [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; ++v) {
      uint32_t code = 0;
      for (int a = 0; a < 3; ++a) {
        // Clamped to the box (non-finite positions, rejected before saliency, land at 0).
        const double q = (double(p[3 * v + a]) - lo[a]) * scale[a];
        const double c = q >= 0 ? std::min(q, double((1u << kBits) - 1)) : 0.0;
        code |= uint32_t(spread_bits_21(uint32_t(c)) << a);
      }
      key[v] = code;
      order[v] = uint32_t(v);
    }
  });
  radix_sort(key, order, (uint64_t(1) << (3 * kBits)) - 1, threads);
  return m;
}

Mesh renumbered_mesh(const Mesh& mesh, const std::vector<uint32_t>& order,
                     const std::vector<uint32_t>& face_key, std::vector<uint32_t>* inverse, unsigned threads) {
  const size_t n = mesh.vertex_count();
  if (order.size() != n) throw Error("internal: a renumbering needs one entry per vertex");
  std::vector<uint32_t> local;
  std::vector<uint32_t>& new_of = inverse ? *inverse : local;
  new_of.assign(n, 0);
  Mesh out;
  out.positions.resize(3 * n);
  parallel_for(n, threads, 1 << 15, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      if (i + 32 < end) __builtin_prefetch(&mesh.positions[3 * size_t(order[i + 32])]);  // scattered reads
      new_of[order[i]] = uint32_t(i);
      for (int a = 0; a < 3; ++a) out.positions[3 * i + a] = mesh.positions[3 * size_t(order[i]) + a];
    }
  });
  // The triangles by the smallest face_key of their corners (a counting sort, stable).
  const size_t nt = mesh.triangle_count();
  const uint32_t* t = mesh.triangles.data();
  out.triangles.resize(mesh.triangles.size());
  if (face_key.empty()) {
    parallel_for(mesh.triangles.size(), threads, 1 << 15, [&](size_t begin, size_t end) {
      for (size_t c = begin; c < end; ++c) out.triangles[c] = new_of[t[c]];
    });
  } else {
    if (face_key.size() != n) throw Error("internal: a face key needs one entry per vertex");
    uint32_t top = 0;
    for (uint32_t k : face_key) top = std::max(top, k);
    if (top >= (1u << 24)) throw Error("internal: face keys must be below 2^24");
    // Each triangle's key, in 16 bits where they fit (mean_curvature_morton's 15-bit cells:
    // 2 bytes per triangle instead of 4 at the curvature's peak).
    auto sort_by = [&](auto key) {
      parallel_for(nt, threads, 1 << 14, [&](size_t begin, size_t end) {
        for (size_t f = begin; f < end; ++f) {
          if (f + 16 < end)
            for (int c = 0; c < 3; ++c) __builtin_prefetch(&new_of[t[3 * (f + 16) + c]]);
          key[f] = std::min({face_key[new_of[t[3 * f]]], face_key[new_of[t[3 * f + 1]]], face_key[new_of[t[3 * f + 2]]]});
        }
      });
      // A stable counting sort on a share of the triangles per thread.
      const size_t shares = std::max<size_t>(1, std::min<size_t>(resolve_threads(threads), nt >> 16));
      std::vector<size_t> counters;
      counting_sort_place(
          nt, size_t(top) + 1, shares, counters, [&](size_t f) { return size_t(key[f]); },
          [&](size_t f, size_t to) {
            for (int c = 0; c < 3; ++c) out.triangles[3 * to + c] = new_of[t[3 * f + c]];
          });
    };
    if (top < (1u << 16)) {
      std::vector<uint16_t> key(nt);
      sort_by(key.data());
    } else {
      std::vector<uint32_t> key(nt);
      sort_by(key.data());
    }
  }
  for (int a = 0; a < 3; ++a) out.origin[a] = mesh.origin[a];
  return out;
}

}  // namespace meshsal
