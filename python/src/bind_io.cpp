// meshsal Python module: load() and the device list.
#include <string>

#include "bindings.h"
#include "meshsal/meshsal.h"
#include "numpy_out.h"

namespace meshsal_py {

namespace {

// A path as the OS takes it: str, bytes or os.PathLike (pathlib.Path), encoded as
// os.fsencode does. A NUL byte cannot be in a path: refused as open() refuses it, instead
// of the name being cut at it.
std::string path_bytes(const py::object& path) {
  py::object encoded;
  try {
    encoded = py::module_::import("os").attr("fsencode")(path);
  } catch (py::error_already_set&) {
    throw py::type_error("path must be str, bytes or os.PathLike, got " +
                         std::string(py::str(path.get_type().attr("__name__"))));
  }
  std::string bytes = encoded.cast<std::string>();
  if (bytes.find('\0') != std::string::npos) throw py::value_error("path: embedded null byte");
  return bytes;
}

py::object load(const py::object& path_obj, bool properties, unsigned long long max_input_bytes) {
  const std::string path = path_bytes(path_obj);
  meshsal::Mesh mesh;
  meshsal::VertexProperties props;
  {
    py::gil_scoped_release unlocked;
    meshsal::LoadOptions options;
    options.max_input_bytes = max_input_bytes;
    mesh = meshsal::load_mesh(path, properties ? &props : nullptr, options);
  }
  const py::ssize_t n = py::ssize_t(mesh.vertex_count()), m = py::ssize_t(mesh.triangle_count());
  py::array vertices = model_vertices(mesh, true);
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

Reads a mesh file (path: str, bytes or pathlib.Path) as `meshsal saliency` does: .obj, .ply (ascii, binary), .off, .stl, each
optionally .gz; polygons fan-triangulated, STL corners welded. Returns the vertices V
(n, 3) as the file has them: float32 when every coordinate is a float32 value (binary float
PLY, STL), else float64 (text files' decimals, double PLYs, survey coordinates), and the faces F, uint32
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
