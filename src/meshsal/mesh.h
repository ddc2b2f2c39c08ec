// meshsal: the triangle mesh as flat arrays (meshoptimizer style).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace meshsal {

struct Mesh {
  std::vector<float> positions;     // x,y,z per vertex, in input order
  std::vector<uint32_t> triangles;  // 3 vertex indices per triangle (polygons fan-split on load)

  size_t vertex_count() const { return positions.size() / 3; }
  size_t triangle_count() const { return triangles.size() / 3; }
};

}  // namespace meshsal
