#include "mesh_args.h"

#include <cmath>
#include <cstdio>

#include "numpy_in.h"
#include "numpy_out.h"

namespace meshsal_py {

namespace {

// attributes={name: (n,) values}: per-vertex channels as the CLI carries OBJ vt/vn and PLY
// properties ("u", "v", "nx", "ny", "nz", "quality", ...), stored as float32.
void take_attributes(const py::object& attributes, meshsal::Mesh& mesh) {
  if (attributes.is_none()) return;
  if (!py::isinstance<py::dict>(attributes))
    throw py::type_error("attributes must be a dict of name -> per-vertex array, got " +
                         std::string(py::str(attributes.get_type().attr("__name__"))));
  for (auto item : py::reinterpret_borrow<py::dict>(attributes)) {
    if (!py::isinstance<py::str>(item.first))
      throw py::type_error("attributes: names must be str, got " +
                           std::string(py::str(item.first.get_type().attr("__name__"))));
    const std::string name = item.first.cast<std::string>();
    if (name.empty() || name.find_first_of(" \t\r\n") != std::string::npos || name == "x" || name == "y" ||
        name == "z")
      throw py::value_error("attributes: bad name '" + name + "' (no spaces; not x, y or z)");
    const std::string what = "attributes['" + name + "']";
    const std::vector<double> v = vertex_values(item.second, mesh.vertex_count(), what.c_str());
    mesh.attributes.push_back({name, std::vector<float>(v.begin(), v.end())});
  }
}

// position_vertex: for each vertex the lowest vertex at the same position (load(...,
// attributes=True) gives it for a mesh split at UV seams); None = no vertex is split.
void take_position_vertex(const py::object& position_vertex, meshsal::Mesh& mesh) {
  if (position_vertex.is_none()) return;
  const size_t n = mesh.vertex_count();
  const std::vector<double> v = vertex_values(position_vertex, n, "position_vertex");
  mesh.position_vertex.resize(n);
  for (size_t i = 0; i < n; ++i) {
    if (!(v[i] >= 0 && v[i] <= double(i) && v[i] == std::floor(v[i])))
    {
      char got[32];
      std::snprintf(got, sizeof got, "%.17g", v[i]);  // 2, not 2.000000
      throw py::value_error("position_vertex: entry " + std::to_string(i) + " must be a whole number in [0, " +
                            std::to_string(i) + "], got " + got);
    }
    mesh.position_vertex[i] = uint32_t(v[i]);
  }
  meshsal::validate_mesh(mesh);  // each entry stands for itself: else meshsal.Error
}

}  // namespace

py::dict attributes_dict(std::vector<meshsal::VertexAttribute>&& attributes) {
  py::dict d;
  for (meshsal::VertexAttribute& a : attributes) d[py::str(a.name)] = to_numpy(std::move(a.values));
  return d;
}

py::object position_vertex_array(std::vector<uint32_t>&& position_vertex) {
  if (position_vertex.empty()) return py::none();
  return to_numpy(std::move(position_vertex));
}

meshsal::Mesh mesh_with_attributes(const py::object& vertices, const py::object& faces,
                                   const py::object& attributes, const py::object& position_vertex) {
  meshsal::Mesh mesh = mesh_from_arrays(vertices, faces);
  take_attributes(attributes, mesh);
  take_position_vertex(position_vertex, mesh);
  return mesh;
}

}  // namespace meshsal_py

namespace meshsal_py {

const char* const kAttributesDoc = R"(
Attribute arguments (what load(path, attributes=True) returns besides V and F):
  attributes       dict name -> (n,) per-vertex values (stored as float32): OBJ texture
                   coordinates 'u', 'v' and normals 'nx', 'ny', 'nz', PLY vertex properties
                   under their names. None: none.
  position_vertex  (n,) integers: for a mesh split at UV seams, the lowest vertex at the
                   same position as each vertex (itself where not split). None: no split.)";

}  // namespace meshsal_py
