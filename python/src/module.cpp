// meshsal Python module (_meshsal, wrapped by the package meshsal): the library's public
// header over numpy arrays. meshsal::Error becomes meshsal.Error, a subclass of both
// ValueError (bad input, its usual cause) and RuntimeError (a failed device), with the
// library's one-line message.
#include <pybind11/pybind11.h>

#include "bindings.h"
#include "meshsal/meshsal.h"
#include "interrupt.h"
#include "paths.h"

namespace py = pybind11;

namespace {
PyObject* error_class = nullptr;  // meshsal.Error; the module keeps a reference to it
}

PYBIND11_MODULE(_meshsal, m) {
  m.doc() = "meshsal: mesh saliency (Lee, Varshney, Jacobs 2005), saliency-guided simplification, "
            "best viewpoints and pictures, over numpy arrays.";
  py::tuple bases = py::make_tuple(py::handle(PyExc_ValueError), py::handle(PyExc_RuntimeError));
  PyObject* error = PyErr_NewExceptionWithDoc(
      "meshsal.Error",
      "Raised by the meshsal library for bad input (a malformed file, an option out of range, "
      "an invalid mesh) or a failed device; the message is the library's one line.",
      bases.ptr(), nullptr);
  if (!error) throw py::error_already_set();
  error_class = error;
  m.attr("Error") = py::reinterpret_steal<py::object>(error);
  meshsal_py::add_path_errors(m, m.attr("Error"));  // meshsal.FileNotFoundError, PermissionError
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const meshsal::Cancelled&) {
      meshsal_py::translate_cancelled();  // Ctrl-C stopped the call (interrupt.h)
    } catch (const meshsal::Error& e) {
      PyErr_SetString(error_class, e.what());
    }
  });
  m.attr("version") = MESHSAL_VERSION;               // 400 for 0.4.0, as the C header's
  m.attr("__version__") = MESHSAL_VERSION_STRING;   // "0.4.0", the project's one version
  py::options options;
  options.disable_function_signatures();  // each docstring starts with its own signature
  meshsal_py::bind_io(m);
  meshsal_py::bind_saliency(m);
  meshsal_py::bind_simplify(m);
  meshsal_py::bind_view(m);
  meshsal_py::bind_heap(m);
  meshsal_py::bind_device(m);
  meshsal_py::bind_out_of_core(m);
  meshsal_py::bind_eval(m);
}
