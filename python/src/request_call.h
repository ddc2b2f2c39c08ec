// meshsal Python module: the library's one pipeline (meshsal::run_request) as the module
// calls it, and the shared argument readers of the calls that build a request.
#pragma once
#include <vector>

#include <pybind11/pybind11.h>

#include "meshsal/meshsal.h"

namespace meshsal_py {

namespace py = pybind11;

// run_request; its refusals of combinations (RequestError) as ValueError, in this module's
// argument names (target_faces for --target-faces N, ...).
meshsal::RequestResult run_in_python_terms(const meshsal::Request& request);

// lod=: a str as --lod reads it, or a sequence (list, tuple, range, array, generator) of
// ints (face counts) and floats (ratios); bytes are no str here (b'0.5' is three ints).
std::vector<meshsal::SimplifyOptions> lod_levels(const py::object& lod);

}  // namespace meshsal_py
