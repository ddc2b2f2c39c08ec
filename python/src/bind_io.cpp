// meshsal Python module: load() and the device list.
#include <string>

#include "bindings.h"
#include "meshsal/meshsal.h"
#include "numpy_out.h"

namespace meshsal_py {

namespace {

py::object load(const std::string& path, bool properties, unsigned long long max_input_bytes) {
  meshsal::Mesh mesh;
  meshsal::VertexProperties props;
  {
    py::gil_scoped_release unlocked;
    meshsal::LoadOptions options;
    options.max_input_bytes = max_input_bytes;
    mesh = meshsal::load_mesh(path, properties ? &props : nullptr, options);
  }
  const py::ssize_t n = py::ssize_t(mesh.vertex_count()), m = py::ssize_t(mesh.triangle_count());
  py::array vertices = to_numpy(std::move(mesh.positions), {n, 3});
  py::array faces = to_numpy(std::move(mesh.triangles), {m, 3});
  if (!properties) return py::make_tuple(vertices, faces);
  py::dict d;
  for (auto& [name, values] : props) d[py::str(name)] = to_numpy(std::move(values));
  return py::make_tuple(vertices, faces, d);
}

py::list devices() {
  py::list out;
  for (const meshsal::DeviceInfo& d : meshsal::list_devices()) {
    py::dict e;
    e["index"] = d.index;
    e["name"] = d.name;
    e["type"] = d.type;
    e["device_local_bytes"] = d.device_local_bytes;
    e["api_version"] = d.api_version;
    e["has_compute"] = d.has_compute;
    out.append(e);
  }
  return out;
}

}  // namespace

void bind_io(py::module_& m) {
  m.def("load", &load, py::arg("path"), py::kw_only(), py::arg("properties") = false,
        py::arg("max_input_bytes") = 0ULL,
        R"(load(path, *, properties=False, max_input_bytes=0) -> (V, F) or (V, F, props)

Reads a mesh file as `meshsal saliency` does: .obj, .ply (ascii, binary), .off, .stl, each
optionally .gz; polygons fan-triangulated, STL corners welded. Returns the vertices V,
float32 (n, 3) (the library's own precision, so no conversion), and the faces F, uint32
(m, 3), both owned by numpy without a copy. With properties=True also a dict of the PLY's
scalar vertex properties (e.g. 'quality', the saliency `meshsal saliency` writes) as
float32 arrays. max_input_bytes bounds a gzipped file's inflated size (0: the default
limits, or MESHSAL_MAX_INPUT). Raises meshsal.Error with the CLI's message on bad input.)");
  m.def("built_with_vulkan", &meshsal::built_with_vulkan,
        "built_with_vulkan() -> bool\n\nTrue when this module has the Vulkan backend (backend='gpu').");
  m.def("devices", &devices,
        R"(devices() -> list of dict

The Vulkan devices, as `meshsal devices` lists them: index (the `device` argument), name,
type ('discrete', 'integrated', 'virtual', 'cpu', 'other'), device_local_bytes,
api_version, has_compute. Raises meshsal.Error without Vulkan.)");
}

}  // namespace meshsal_py
