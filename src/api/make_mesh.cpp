#include "meshsal/meshsal.h"

namespace meshsal {

Mesh make_mesh(const float* positions, size_t vertex_count, const uint32_t* indices,
               size_t index_count) {
  if (index_count % 3 != 0)
    throw Error("index count " + std::to_string(index_count) + " is not a multiple of 3");
  if ((vertex_count && !positions) || (index_count && !indices))
    throw Error("make_mesh: null array with a non-zero count");
  Mesh mesh;
  mesh.positions.assign(positions, positions + 3 * vertex_count);
  mesh.triangles.assign(indices, indices + index_count);
  validate_mesh(mesh);
  return mesh;
}

}  // namespace meshsal
