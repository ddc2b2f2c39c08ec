// meshsal Python module: a mesh's per-vertex attributes and seam map in and out, as
// load(..., attributes=True) gives them and simplify() and save() take them: the CLI carries
// OBJ vt/vn and PLY vertex properties through simplification the same way.
#pragma once
#include <cstdint>
#include <vector>

#include <pybind11/pybind11.h>

#include "meshsal/meshsal.h"

namespace meshsal_py {

namespace py = pybind11;

// mesh_from_arrays(vertices, faces), then `attributes` (None, or a dict name -> (n,) real
// values, kept as float32 in Mesh::attributes) and `position_vertex` (None, or (n,) whole
// numbers: Mesh::position_vertex). TypeError / ValueError name the argument; the
// library's check of position_vertex raises meshsal.Error.
meshsal::Mesh mesh_with_attributes(const py::object& vertices, const py::object& faces,
                                   const py::object& attributes, const py::object& position_vertex);

// Mesh::attributes as a dict name -> float32 (n,) array (no copy).
py::dict attributes_dict(std::vector<meshsal::VertexAttribute>&& attributes);

// Mesh::position_vertex as a uint32 (n,) array, or None when empty (no vertex is split).
py::object position_vertex_array(std::vector<uint32_t>&& position_vertex);

// The docstring lines that describe attributes= and position_vertex=.
extern const char* const kAttributesDoc;

}  // namespace meshsal_py
