#include "meshsal/meshsal.h"

namespace meshsal {

void set_vertex_attribute(Mesh& mesh, const std::string& name, const std::vector<double>& values) {
  if (values.size() != mesh.vertex_count())
    throw Error("attribute '" + name + "': " + std::to_string(values.size()) + " values for " +
                std::to_string(mesh.vertex_count()) + " vertices");
  std::vector<float> v(values.begin(), values.end());
  for (VertexAttribute& at : mesh.attributes)
    if (at.name == name) {
      at.values = std::move(v);
      return;
    }
  mesh.attributes.push_back({name, std::move(v)});
}

}  // namespace meshsal
