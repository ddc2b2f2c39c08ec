// meshsal: vertices along a Morton (Z-order) curve, so that vertices near each other in
// space are near each other in memory. A scan subdivided in memory or by another tool
// appends its new vertices far from their neighbours; every pass over the triangles or
// the cells then misses the cache at each vertex (the fast method's stages ran 2-3x slower
// on such a scan than on the same vertices in curve order).
#pragma once
#include <cstdint>
#include <vector>

#include "core/mesh_points.h"
#include "meshsal/meshsal.h"

namespace meshsal {

// The 21 low bits of x spread to every third bit (bit i to bit 3i).
uint64_t spread_bits_21(uint32_t x);

constexpr int kMortonBits = 10;  // steps per axis: 2^10

// The vertices along the curve: order[i] is the vertex at curve position i, code[i] its
// 30-bit Morton code (ascending).
struct MortonOrder {
  std::vector<uint32_t> order;
  std::vector<uint32_t> code;
};

// The vertex indices sorted by the 30-bit Morton code of their position quantised to 2^10
// steps per axis over `box` (positions outside it are clamped; ties keep index order).
// 2^10 steps order a scan's neighbourhoods as well as 2^21 (a few vertices a step on a
// surface) and sort in 3 passes instead of 6. Linear (radix sort on `threads`). Over the
// same box, any subset of the vertices (a tile) comes out in the same relative order.
MortonOrder morton_order(const Mesh& mesh, const BoundingBox& box, unsigned threads = 0);

// A mesh of the same surface with its vertices renumbered (positions and triangles only):
// vertex i of the result is vertex order[i] of `mesh`. The triangles keep their corner
// order; with `face_key` (one key below 2^24 per NEW vertex) they are sorted, stably, by
// the smallest key of their corners, else they keep their order. `inverse` (may be null)
// receives the new index of each old vertex.
Mesh renumbered_mesh(const Mesh& mesh, const std::vector<uint32_t>& order,
                     const std::vector<uint32_t>& face_key = {}, std::vector<uint32_t>* inverse = nullptr,
                     unsigned threads = 0);

}  // namespace meshsal
