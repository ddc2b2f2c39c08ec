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

std::vector<double> take_vertex_attribute(Mesh& mesh, const std::string& name) {
  std::vector<double> out;
  for (auto it = mesh.attributes.begin(); it != mesh.attributes.end(); ++it)
    if (it->name == name) {
      out.assign(it->values.begin(), it->values.end());
      mesh.attributes.erase(it);
      break;
    }
  return out;
}

}  // namespace meshsal
