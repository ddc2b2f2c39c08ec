// meshsal: split vertices at UV seams found by position (seam_twins.h).
#include "io/seam_twins.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <numeric>

namespace meshsal {

namespace {

// The position's bits, -0 read as +0, for exact comparison.
std::array<uint32_t, 3> position_key(const Mesh& mesh, uint32_t v) {
  std::array<uint32_t, 3> key;
  for (int k = 0; k < 3; ++k) {
    const float x = mesh.positions[3 * size_t(v) + k] == 0.0f ? 0.0f : mesh.positions[3 * size_t(v) + k];
    std::memcpy(&key[k], &x, 4);
  }
  return key;
}

bool same_attributes(const Mesh& mesh, uint32_t a, uint32_t b) {
  for (const VertexAttribute& at : mesh.attributes)
    if (!(at.values[a] == at.values[b])) return false;
  return true;
}

}  // namespace

void find_seam_twins(Mesh& mesh) {
  mesh.position_vertex.clear();
  const size_t n = mesh.vertex_count();
  if (mesh.attributes.empty() || n < 2) return;
  // Vertices sorted by position, then index: each group is one run, lowest vertex first.
  std::vector<uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::vector<std::array<uint32_t, 3>> keys(n);
  for (size_t v = 0; v < n; ++v) keys[v] = position_key(mesh, uint32_t(v));
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return keys[a] != keys[b] ? keys[a] < keys[b] : a < b;
  });
  std::vector<uint32_t> pv(n);
  std::iota(pv.begin(), pv.end(), 0u);
  bool any = false;
  for (size_t i = 0; i < n;) {
    size_t j = i + 1;
    while (j < n && keys[order[j]] == keys[order[i]]) ++j;
    bool split = false;
    for (size_t k = i + 1; k < j && !split; ++k) split = !same_attributes(mesh, order[i], order[k]);
    if (split) {
      for (size_t k = i; k < j; ++k) pv[order[k]] = order[i];
      any = true;
    }
    i = j;
  }
  if (any) mesh.position_vertex = std::move(pv);
}

}  // namespace meshsal
