// meshsal Python module: file paths in (str, bytes or os.PathLike) and the errors of file
// access out as Python's: a file or folder that does not exist raises
// meshsal.FileNotFoundError, one that may not be read or written meshsal.PermissionError.
// Both are subclasses of meshsal.Error and of the built-in FileNotFoundError /
// PermissionError (errno and filename set), with the library's one-line message.
#pragma once
#include <string>

#include <pybind11/pybind11.h>

#include "meshsal/meshsal.h"

namespace meshsal_py {

namespace py = pybind11;

// The path as the OS takes it, encoded as os.fsencode does. TypeError for another type,
// ValueError for an embedded NUL byte.
std::string path_bytes(const py::object& path);

// Creates the two classes in module `m` (after meshsal.Error, `error`).
void add_path_errors(py::module_& m, const py::object& error);

// Raises the Python error of a failed load or save of `path`: meshsal.FileNotFoundError or
// meshsal.PermissionError when the library's message reports that errno, else meshsal.Error.
[[noreturn]] void raise_file_error(const meshsal::Error& e, const py::object& path);

}  // namespace meshsal_py
