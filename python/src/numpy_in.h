// meshsal Python module: numpy arrays in. Checks shape, dtype and values with messages that
// name the argument, and fills the library's Mesh in one pass (the public API holds a mesh
// as std::vector, so one copy is unavoidable; no intermediate numpy copy is ever made:
// float64, int64 and non-contiguous views are converted while they are read).
#pragma once
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "meshsal/meshsal.h"

namespace meshsal_py {

namespace py = pybind11;

// (n, 3) float32/float64 vertices and (m, 3) integer faces (int8..int64, uint8..uint64) into
// a validated Mesh. TypeError for a wrong type or dtype, ValueError for a wrong shape, a
// non-finite coordinate (or one beyond float32's range), an index out of range; the
// library's own checks (no triangle of non-zero area) raise meshsal.Error.
meshsal::Mesh mesh_from_arrays(const py::handle& vertices, const py::handle& faces);

// True for a float32 numpy array (results then come back in float32 where that holds them);
// float64 arrays, lists and the rest give float64 results.
bool float32_vertices(const py::handle& vertices);

// A per-vertex float array (any real dtype, 1-D, `count` values, finite) as doubles.
// `name` starts the error messages.
std::vector<double> vertex_values(const py::handle& values, size_t count, const char* name);

// Scales given as a sequence of numbers or as a string "2,3,4,5,6" (meshsal::parse_scales).
std::vector<double> scales_from(const py::handle& scales);

}  // namespace meshsal_py
