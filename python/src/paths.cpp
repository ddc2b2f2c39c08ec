#include "paths.h"

#include <pybind11/eval.h>

#include <cerrno>
#include <cstring>

namespace meshsal_py {

namespace {

// The two classes (add_path_errors): references kept for the life of the process, as the
// module keeps meshsal.Error's.
PyObject* not_found_class = nullptr;
PyObject* permission_class = nullptr;

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

}  // namespace

std::string path_bytes(const py::object& path) {
  // A NUL byte cannot be in a path: refused as open() refuses it, instead of the name being
  // cut at it.
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

void add_path_errors(py::module_& m, const py::object& error) {
  py::dict scope;
  scope["Error"] = error;
  py::exec(R"(
class FileNotFoundError(Error, FileNotFoundError):
    """A mesh file (or the folder of an output) that does not exist: a meshsal.Error and a
    FileNotFoundError (errno ENOENT, filename set), with the library's one-line message."""
    __module__ = "meshsal"

    def __str__(self):
        return str(self.args[0]) if self.args else ""


class PermissionError(Error, PermissionError):
    """A file that may not be read, or a folder that may not be written: a meshsal.Error and
    a PermissionError (errno EACCES or EPERM, filename set), with the library's message."""
    __module__ = "meshsal"

    def __str__(self):
        return str(self.args[0]) if self.args else ""
)", scope);
  m.attr("FileNotFoundError") = scope["FileNotFoundError"];
  m.attr("PermissionError") = scope["PermissionError"];
  not_found_class = py::object(scope["FileNotFoundError"]).release().ptr();
  permission_class = py::object(scope["PermissionError"]).release().ptr();
}

void raise_file_error(const meshsal::Error& e, const py::object& path) {
  const std::string message = e.what();
  // The library ends a failed open, stat or write with strerror(errno), and says so of an
  // output's folder that is missing or not writable ("... is not writable (strerror)").
  int err = 0;
  for (int candidate : {ENOENT, ENOTDIR, EACCES, EPERM, EROFS})
    if (ends_with(message, std::string(": ") + std::strerror(candidate)) ||
        ends_with(message, std::string("(") + std::strerror(candidate) + ")"))
      err = candidate;
  if (err == 0 && ends_with(message, "' does not exist") && message.find(": cannot write: folder '") != std::string::npos)
    err = ENOENT;
  if (err == 0) throw e;  // meshsal.Error (the module's translator)
  const py::handle cls = err == ENOENT || err == ENOTDIR ? not_found_class : permission_class;
  py::object exc = cls(message);
  exc.attr("errno") = err;
  exc.attr("strerror") = std::strerror(err);
  exc.attr("filename") = path;
  PyErr_SetObject(cls.ptr(), exc.ptr());
  throw py::error_already_set();
}

}  // namespace meshsal_py
