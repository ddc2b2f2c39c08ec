#include "core/model_frame.h"

namespace meshsal {

void carry_model_frame(const Mesh& in, const std::vector<uint32_t>& from, Mesh& out) {
  for (int k = 0; k < 3; ++k) out.origin[k] = in.origin[k];
  out.double_positions = in.double_positions;
  out.source_positions.clear();
  if (in.source_positions.size() != in.positions.size()) return;
  out.source_positions.resize(3 * from.size());
  for (size_t i = 0; i < from.size(); ++i)
    for (int k = 0; k < 3; ++k)
      out.source_positions[3 * i + k] = from[i] != UINT32_MAX
                                            ? in.source_positions[3 * size_t(from[i]) + k]
                                            : double(out.positions[3 * i + k]) + out.origin[k];
}

Mesh in_frame(const Mesh& mesh, const double origin[3]) {
  Mesh out = mesh;
  if (origin[0] == mesh.origin[0] && origin[1] == mesh.origin[1] && origin[2] == mesh.origin[2]) return out;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    double p[3];
    model_position(mesh, v, p);
    for (int k = 0; k < 3; ++k) out.positions[3 * v + k] = local_coordinate(p[k], origin[k]);
  }
  for (int k = 0; k < 3; ++k) out.origin[k] = origin[k];
  return out;
}

}  // namespace meshsal
