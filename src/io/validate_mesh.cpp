// meshsal: sanity checks every loaded mesh goes through (see mesh_io.h).
// Unreferenced vertices and non-manifold or open surfaces are allowed: real scans have them.
#include <cmath>
#include <string>

#include "core/first_index_where.h"
#include "meshsal/meshsal.h"
#include "core/vec3.h"
#include "core/welded_view.h"

namespace meshsal {

void validate_mesh(const Mesh& mesh) {
  if (mesh.positions.size() % 3 != 0) throw Error("positions array length is not a multiple of 3");
  if (mesh.triangles.size() % 3 != 0) throw Error("triangles array length is not a multiple of 3");
  const size_t nv = mesh.vertex_count();
  if (nv == 0) throw Error("mesh has no vertices");
  if (mesh.triangle_count() == 0) throw Error("mesh has no faces");
  const float* xyz = mesh.positions.data();
  if (const size_t i = first_index_where(mesh.positions.size(), [&](size_t j) { return !std::isfinite(xyz[j]); });
      i < mesh.positions.size())
    throw Error("vertex " + std::to_string(i / 3) + " has a non-finite coordinate (" +
                std::to_string(mesh.positions[i]) + ")");
  const uint32_t* corners = mesh.triangles.data();
  if (const size_t i = first_index_where(mesh.triangles.size(), [&](size_t j) { return corners[j] >= nv; });
      i < mesh.triangles.size())
    throw Error("triangle " + std::to_string(i / 3) + " uses vertex index " +
                std::to_string(mesh.triangles[i]) + " but the mesh has only " +
                std::to_string(nv) + " vertices");
  for (const VertexAttribute& a : mesh.attributes)
    if (a.values.size() != nv)
      throw Error("attribute '" + a.name + "' has " + std::to_string(a.values.size()) +
                  " values for " + std::to_string(nv) + " vertices");
  check_position_vertex(mesh);
  if (!mesh.triangle_material.empty()) {
    if (mesh.triangle_material.size() != mesh.triangle_count())
      throw Error("triangle_material has " + std::to_string(mesh.triangle_material.size()) + " entries for " +
                  std::to_string(mesh.triangle_count()) + " triangles");
    for (size_t t = 0; t < mesh.triangle_material.size(); ++t)
      if (mesh.triangle_material[t] >= mesh.materials.size())
        throw Error("triangle " + std::to_string(t) + " has material " + std::to_string(mesh.triangle_material[t]) +
                    " but the mesh has " + std::to_string(mesh.materials.size()) + " materials");
  }
  const float* p = mesh.positions.data();
  for (size_t t = 0; t < mesh.triangles.size(); t += 3) {
    const float* a = p + 3 * size_t(mesh.triangles[t]);
    const float* b = p + 3 * size_t(mesh.triangles[t + 1]);
    const float* c = p + 3 * size_t(mesh.triangles[t + 2]);
    double u[3], v[3];
    for (int k = 0; k < 3; ++k) {
      u[k] = double(b[k]) - a[k];
      v[k] = double(c[k]) - a[k];
    }
    double n[3];
    cross3(u, v, n);
    if (n[0] != 0 || n[1] != 0 || n[2] != 0) return;  // found a triangle with area
  }
  throw Error("every triangle has zero area (degenerate mesh)");
}

}  // namespace meshsal
