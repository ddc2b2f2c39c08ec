// meshsal Python module: load() and the device list.
#include <cctype>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "arg_values.h"
#include <pybind11/stl.h>

#include "bindings.h"
#include "meshsal/meshsal.h"
#include "mesh_args.h"
#include "numpy_in.h"
#include "numpy_out.h"
#include "paths.h"

namespace meshsal_py {

namespace {

py::object load(const py::object& path_obj, bool properties, bool attributes, const py::object& max_input_bytes) {
  const std::string path = path_bytes(path_obj);
  meshsal::LoadOptions options;
  options.max_input_bytes = unsigned_arg(max_input_bytes, "max_input_bytes", 0, std::numeric_limits<uint64_t>::max());
  options.attributes = attributes;
  if (properties && attributes)
    throw py::value_error("give properties=True or attributes=True, not both (attributes has the PLY's "
                          "properties too)");
  meshsal::Mesh mesh;
  meshsal::VertexProperties props;
  try {
    py::gil_scoped_release unlocked;
    if (properties) {
      meshsal::LoadedMesh read = meshsal::read_mesh(path, options);
      mesh = std::move(read.mesh);
      props = std::move(read.properties);
    } else {
      mesh = meshsal::load_mesh(path, options);
    }
  } catch (const meshsal::Cancelled&) {
    throw;
  } catch (const meshsal::Error& e) {
    raise_file_error(e, path_obj);
  }
  const py::ssize_t m = py::ssize_t(mesh.triangle_count());
  py::array vertices = model_vertices(mesh, true);
  py::array faces = to_numpy(std::move(mesh.triangles), {m, 3});
  if (attributes)
    return py::make_tuple(vertices, faces, attributes_dict(std::move(mesh.attributes)),
                          position_vertex_array(std::move(mesh.position_vertex)));
  if (!properties) return py::make_tuple(vertices, faces);
  py::dict d;
  for (auto& [name, values] : props) d[py::str(name)] = to_numpy(std::move(values));
  return py::make_tuple(vertices, faces, d);
}

void save(const py::object& path_obj, const py::object& vertices, const py::object& faces,
          const py::object& saliency, const py::object& attributes, const py::object& position_vertex) {
  const std::string path = path_bytes(path_obj);
  // The library's check of every front end's outputs, before the arrays are read: a name
  // the writers know (the format comes from it), a place they can write.
  try {
    std::vector<std::string> formats;
    for (const meshsal::MeshFormat& f : meshsal::mesh_formats()) formats.push_back(f.suffix);
    meshsal::check_outputs({{path, "path", formats}}, {});
  } catch (const meshsal::Error& e) {
    raise_file_error(e, path_obj);
  }
  meshsal::Mesh mesh = mesh_with_attributes(vertices, faces, attributes, position_vertex);
  std::vector<double> s;
  if (!saliency.is_none()) s = vertex_values(saliency, mesh.vertex_count(), "saliency");
  try {
    py::gil_scoped_release unlocked;
    meshsal::write_mesh(path, mesh, s);
  } catch (const meshsal::Error& e) {
    raise_file_error(e, path_obj);
  }
}

// The defaults every front end shares: the library's meshsal::Request, as option values.
py::dict defaults() {
  const meshsal::Request r;
  py::dict d;
  d["method"] = meshsal::method_name(r.saliency.method);
  d["model"] = meshsal::model_name(r.saliency.model);
  d["backend"] = meshsal::backend_name(r.saliency.backend);
  d["precision"] = meshsal::precision_name(r.saliency.precision);
  d["eps_frac"] = r.saliency.eps_frac;
  d["scales"] = py::cast(r.saliency.scales);
  d["threads"] = r.saliency.threads;
  d["device"] = r.saliency.device;
  d["weights"] = meshsal::weighting_name(r.weighting);
  d["weight_floor"] = r.weight_options.floor;
  d["restarts"] = r.viewpoint.optimiser.restarts;
  d["seed"] = r.viewpoint.optimiser.seed;
  d["resolution"] = r.viewpoint.visibility.resolution;
  d["depth_tol"] = r.viewpoint.visibility.depth_tol_px;
  d["size"] = r.style.size;
  d["max_faces"] = r.page.max_faces;
  return d;
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
  m.def("load", &load, py::arg("path"), py::kw_only(), py::arg("properties").noconvert() = false,
        py::arg("attributes").noconvert() = false, py::arg("max_input_bytes") = 0ULL,
        R"(load(path, *, properties=False, attributes=False, max_input_bytes=0)
    -> (V, F), (V, F, props) or (V, F, attributes, position_vertex)

Reads a mesh file as `meshsal saliency` does: .obj, .ply (ascii, binary), .off, .stl,
.gltf, .glb, each optionally .gz (glTF: the default scene's triangles, node transforms
applied); polygons fan-triangulated, STL corners welded. Returns the vertices V
(n, 3) as the file has them: float32 when every coordinate is a float32 value (binary float
PLY, STL), else float64 (text files' decimals, double PLYs, survey coordinates), and the
faces F, uint32 (m, 3), both owned by numpy without a copy.

  path             str, bytes or os.PathLike (pathlib.Path)
  properties       also return a dict of the PLY's scalar vertex properties (e.g.
                   'quality', the saliency `meshsal saliency` writes) as float32 arrays
  attributes       read the mesh as `meshsal simplify` does: also return its per-vertex
                   attributes (dict name -> float32 (n,): OBJ vt as 'u', 'v' and vn as
                   'nx', 'ny', 'nz', PLY vertex properties under their names) and its seam
                   map position_vertex (uint32 (n,), or None when no vertex is split: an
                   OBJ v used with different vt/vn becomes one vertex per combination).
                   simplify() and save() take both back
  max_input_bytes  bounds a gzipped file's inflated size and what a pipe may deliver (0:
                   the library's default limits; the environment variable
                   MESHSAL_MAX_INPUT is the meshsal command's and is not read here)

A file that does not exist raises meshsal.FileNotFoundError, one that may not be read
meshsal.PermissionError (subclasses of the built-in ones, with errno and filename); a bad
file meshsal.Error with the CLI's message.)");
  m.def("save", &save, py::arg("path"), py::arg("vertices"), py::arg("faces"), py::arg("saliency") = py::none(),
        py::kw_only(), py::arg("attributes") = py::none(), py::arg("position_vertex") = py::none(),
        (std::string(R"(save(path, vertices, faces, saliency=None, *, attributes=None, position_vertex=None)

Writes a mesh with the library's writers, the bytes the CLI writes for the same mesh:

  path             str, bytes or os.PathLike ending in .ply (binary little-endian PLY),
                   .glb or .gltf (glTF 2.0), .obj (v with r g b colours, vt, vn and f
                   lines), .off (COFF with colours) or .stl (binary): the format the name
                   gives (another ending raises meshsal.Error before anything is read);
                   checked as the CLI checks its -o, then written to a temporary file and
                   renamed, so a failure never leaves a half-written file
  vertices, faces  as in saliency()
  saliency         S per vertex: written as `meshsal saliency -o OUT` writes it; PLY: the
                   property quality = S and red/green/blue its colour scale; glTF:
                   _SALIENCY and COLOR_0; OBJ and OFF: its colours only; STL: refused

With attributes (e.g. a SimplifyResult's .attributes and .position_vertex) a PLY gets
them as vertex properties (red/green/blue/alpha as uchar) and an OBJ its texture
coordinates (u v) and normals (nx ny nz): save(p, r.vertices, r.faces,
attributes=r.attributes, position_vertex=r.position_vertex) writes what `meshsal simplify
-o p` writes. A missing folder raises meshsal.FileNotFoundError, one that may not be
written meshsal.PermissionError, other failures meshsal.Error.
)") + kAttributesDoc).c_str());
  m.def("defaults", &defaults,
        R"(defaults() -> dict

The defaults every front end shares (the library's meshsal::Request: the command line's
options and these functions' keyword arguments take them): method, backend, precision,
eps_frac, scales, threads, device, weights, weight_floor, restarts, seed, resolution,
depth_tol, size, max_faces.)");
  m.def("built_with_vulkan", &meshsal::built_with_vulkan,
        "built_with_vulkan() -> bool\n\nTrue when this module has the Vulkan backend (backend='gpu').");
  m.def("devices", &devices,
        R"(devices() -> list of dict

The Vulkan devices, as `meshsal devices --json` lists them (the same keys): index (the `device` argument), name,
type ('discrete', 'integrated', 'virtual', 'cpu', 'other'), device_local_bytes,
api_version, has_compute. Raises meshsal.Error without Vulkan.)");
}

}  // namespace meshsal_py
