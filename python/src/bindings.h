// meshsal Python module: each bind_*.cpp adds one group of functions to the module.
#pragma once
#include <pybind11/pybind11.h>

namespace meshsal_py {

namespace py = pybind11;

void bind_io(py::module_& m);        // load, save, devices
void bind_saliency(py::module_& m);  // saliency
void bind_simplify(py::module_& m);  // simplify
void bind_view(py::module_& m);      // best_view, render
void bind_heap(py::module_& m);      // keep_freed_memory
void bind_device(py::module_& m);    // Device, release_cached_devices
void bind_out_of_core(py::module_& m);  // saliency_file, simplify_file
void bind_eval(py::module_& m);      // evaluate

}  // namespace meshsal_py
