#include "cli/subdivide.h"

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/model_frame.h"

namespace meshsal {

Mesh subdivide_midpoint(const Mesh& mesh) {
  const size_t nv = mesh.vertex_count(), nt = mesh.triangle_count();
  // Edge keys (low index << 32 | high index), sorted and deduplicated: the new vertex of an
  // edge is nv + its rank.
  std::vector<uint64_t> edges;
  edges.reserve(3 * nt);
  auto key = [](uint32_t a, uint32_t b) {
    return a < b ? (uint64_t(a) << 32 | b) : (uint64_t(b) << 32 | a);
  };
  for (size_t t = 0; t < nt; ++t)
    for (int c = 0; c < 3; ++c)
      edges.push_back(key(mesh.triangles[3 * t + c], mesh.triangles[3 * t + (c + 1) % 3]));
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  if (nv + edges.size() >= UINT32_MAX) throw Error("subdivision: more than 2^32 - 1 vertices");

  Mesh out;
  out.positions.reserve(3 * (nv + edges.size()));
  out.positions = mesh.positions;
  for (uint64_t e : edges) {
    const uint32_t a = uint32_t(e >> 32), b = uint32_t(e);
    for (int k = 0; k < 3; ++k)
      out.positions.push_back(0.5f * (mesh.positions[3 * a + k] + mesh.positions[3 * b + k]));
  }
  auto mid = [&](uint32_t a, uint32_t b) {
    return uint32_t(nv + (std::lower_bound(edges.begin(), edges.end(), key(a, b)) - edges.begin()));
  };
  out.triangles.resize(12 * nt);
  for (size_t t = 0; t < nt; ++t) {
    const uint32_t a = mesh.triangles[3 * t], b = mesh.triangles[3 * t + 1], c = mesh.triangles[3 * t + 2];
    const uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
    const uint32_t tri[12] = {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca};
    std::copy(tri, tri + 12, &out.triangles[12 * t]);
  }
  std::vector<uint32_t> from(out.vertex_count(), UINT32_MAX);  // the old vertices keep their source
  for (size_t v = 0; v < nv; ++v) from[v] = uint32_t(v);
  carry_model_frame(mesh, from, out);
  return out;
}

}  // namespace meshsal
