#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {
namespace {

template <typename Real>
Mesh make_mesh_from(const Real* positions, size_t vertex_count, const uint32_t* indices, size_t index_count) {
  if (index_count % 3 != 0)
    throw Error("index count " + std::to_string(index_count) + " is not a multiple of 3");
  if ((vertex_count && !positions) || (index_count && !indices))
    throw Error("make_mesh: null array with a non-zero count");
  Mesh mesh;
  mesh.triangles.assign(indices, indices + index_count);
  const std::vector<double> xyz(positions, positions + 3 * vertex_count);
  set_model_positions(mesh, xyz.data(), vertex_count);
  validate_mesh(mesh);
  return mesh;
}

}  // namespace

Mesh make_mesh(const float* positions, size_t vertex_count, const uint32_t* indices, size_t index_count) {
  return make_mesh_from(positions, vertex_count, indices, index_count);
}

Mesh make_mesh(const double* positions, size_t vertex_count, const uint32_t* indices, size_t index_count) {
  return make_mesh_from(positions, vertex_count, indices, index_count);
}

}  // namespace meshsal
