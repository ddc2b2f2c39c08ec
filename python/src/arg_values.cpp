#include "arg_values.h"

#include <cmath>
#include <limits>

namespace meshsal_py {

namespace {

// True for True/False and numpy's bool_ (a bool array's items): never a number here.
bool is_bool(const py::handle& value) {
  if (PyBool_Check(value.ptr())) return true;
  if (!py::hasattr(value, "dtype")) return false;
  const py::object kind = value.attr("dtype").attr("kind");
  return py::isinstance<py::str>(kind) && kind.cast<std::string>() == "b";
}

// An array of one or more dimensions (one value is a scalar or a 0-d array).
bool is_array_of_values(const py::handle& value) {
  return py::hasattr(value, "shape") && py::isinstance<py::tuple>(value.attr("shape")) &&
         py::len(value.attr("shape")) != 0;
}

bool is_zero_d_array(const py::handle& value) {
  return py::hasattr(value, "shape") && py::isinstance<py::tuple>(value.attr("shape")) &&
         py::len(value.attr("shape")) == 0 && py::hasattr(value, "ndim");
}

// The Python int of an integer argument (operator.index), or TypeError.
py::int_ index_of(const py::handle& value, const char* name) {
  if (is_bool(value) || PyFloat_Check(value.ptr()))
    throw py::type_error(std::string(name) + " must be an integer, got " + type_name(value));
  PyObject* index = PyNumber_Index(value.ptr());
  if (!index) {
    PyErr_Clear();
    throw py::type_error(std::string(name) + " must be an integer, got " + type_name(value));
  }
  return py::reinterpret_steal<py::int_>(index);
}

template <class T>
T bounded(const py::handle& value, const char* name, T lo, T hi) {
  const py::int_ i = index_of(value, name);
  // Compared as Python ints: 2**70 is no C++ integer, and must be named as given.
  if (i < py::int_(lo) || i > py::int_(hi))
    throw py::value_error(std::string(name) + " must be in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                          "], got " + std::string(py::str(py::object(i))));
  return i.cast<T>();
}

}  // namespace

bool is_integer(const py::handle& value) {
  if (is_bool(value)) return false;
  if (PyLong_Check(value.ptr())) return true;
  if (!py::hasattr(value, "dtype")) return false;
  const py::object kind = value.attr("dtype").attr("kind");
  return py::isinstance<py::str>(kind) && (kind.cast<std::string>() == "i" || kind.cast<std::string>() == "u");
}

std::string type_name(const py::handle& value) {
  return py::str(value.get_type().attr("__name__"));
}

long long integer_arg(const py::handle& value, const char* name, long long lo, long long hi) {
  return bounded<long long>(value, name, lo, hi);
}

uint64_t unsigned_arg(const py::handle& value, const char* name, uint64_t lo, uint64_t hi) {
  return bounded<unsigned long long>(value, name, lo, hi);
}

unsigned count_arg(const py::handle& value, const char* name) {
  return unsigned(bounded<unsigned long long>(value, name, 0, std::numeric_limits<unsigned>::max()));
}

double number_arg(const py::handle& value, const char* name) {
  if (is_bool(value) || py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value) ||
      !PyNumber_Check(value.ptr()))
    throw py::type_error(std::string(name) + " must be a number, got " + type_name(value));
  if (is_array_of_values(value))
    throw py::type_error(std::string(name) + " must be a single number, got " + type_name(value));
  PyObject* f = PyNumber_Float(value.ptr());
  if (!f) {
    const bool overflow = PyErr_ExceptionMatches(PyExc_OverflowError);
    if (!overflow) throw py::error_already_set();  // a number type whose float() failed: its own error
    PyErr_Clear();
    throw py::value_error(std::string(name) + " is out of range, got " + std::string(py::str(value)));
  }
  return py::reinterpret_steal<py::float_>(f).cast<double>();
}

std::vector<py::object> sequence_items(const py::handle& value, const char* name, const char* expected,
                                       size_t limit) {
  const auto refuse = [&] {
    throw py::type_error(std::string(name) + " must be " + expected + ", got " + type_name(value));
  };
  if (py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value) || PyByteArray_Check(value.ptr()) ||
      py::isinstance<py::dict>(value) || is_zero_d_array(value))
    refuse();
  PyObject* it = PyObject_GetIter(value.ptr());
  if (!it) {
    PyErr_Clear();
    refuse();
  }
  const py::object iterator = py::reinterpret_steal<py::object>(it);
  std::vector<py::object> items;
  while (items.size() <= limit) {
    PyObject* item = PyIter_Next(iterator.ptr());
    if (!item) {
      if (PyErr_Occurred()) throw py::error_already_set();  // the generator's own error
      break;
    }
    items.push_back(py::reinterpret_steal<py::object>(item));
  }
  return items;
}

}  // namespace meshsal_py
