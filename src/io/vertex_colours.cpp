// meshsal: the vertex colours the text writers (OBJ, OFF) write: S's on the pictures' scale,
// else the mesh's own.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/mesh_points.h"
#include "io/colormap.h"
#include "io/mesh_io_internal.h"

namespace meshsal {

std::vector<uint8_t> vertex_colour_bytes(const Mesh& mesh) {
  const VertexAttribute* c[3] = {find_attribute(mesh, "red"), find_attribute(mesh, "green"), find_attribute(mesh, "blue")};
  std::vector<uint8_t> rgb;
  if (!c[0] || !c[1] || !c[2]) return rgb;
  const size_t n = mesh.vertex_count();
  rgb.resize(3 * n);
  for (size_t v = 0; v < n; ++v)
    for (int k = 0; k < 3; ++k) {
      const float x = v < c[k]->values.size() ? c[k]->values[v] : 0.0f;
      rgb[3 * v + size_t(k)] = uint8_t(x >= 255 ? 255 : x > 0 ? std::lround(x) : 0);  // NaN -> 0, as write_ply
    }
  return rgb;
}

std::vector<uint8_t> written_colours(const std::string& path, const Mesh& mesh, const std::vector<double>* saliency) {
  if (!saliency) return vertex_colour_bytes(mesh);
  if (saliency->size() != mesh.vertex_count())
    throw Error(path + ": cannot write: " + std::to_string(saliency->size()) + " saliency values for " +
                std::to_string(mesh.vertex_count()) + " vertices");
  return colormap_values(*saliency, referenced_vertices(mesh));
}

}  // namespace meshsal
