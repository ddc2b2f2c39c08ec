#include "core/mesh_points.h"

#include <cmath>

#include "meshsal/meshsal.h"

namespace meshsal {

std::vector<uint8_t> referenced_vertices(const Mesh& mesh) {
  std::vector<uint8_t> is_point(mesh.vertex_count(), 0);
  for (uint32_t v : mesh.triangles) is_point[v] = 1;
  return is_point;
}

double BoundingBox::diagonal() const {
  double dx = max[0] - min[0], dy = max[1] - min[1], dz = max[2] - min[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

BoundingBox mesh_points_bbox(const Mesh& mesh, const std::vector<uint8_t>& is_point) {
  BoundingBox box{{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
  bool any = false;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    if (!is_point[v]) continue;
    any = true;
    for (int a = 0; a < 3; ++a) {
      double x = mesh.positions[3 * v + a];
      box.min[a] = std::min(box.min[a], x);
      box.max[a] = std::max(box.max[a], x);
    }
  }
  if (!any) throw Error("mesh has no vertex referenced by a triangle");
  return box;
}

double scale_unit(const Mesh& mesh, const std::vector<uint8_t>& is_point, double eps_frac) {
  if (!(eps_frac > 0) || !std::isfinite(eps_frac))
    throw Error("eps fraction must be a positive number");
  double eps = eps_frac * mesh_points_bbox(mesh, is_point).diagonal();
  if (!(eps > 0) || !std::isfinite(eps))
    throw Error("mesh points all coincide: the bounding box has zero size");
  return eps;
}

}  // namespace meshsal
