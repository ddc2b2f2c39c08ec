// meshsal Python module: library results out as numpy arrays without a copy. The vector is
// moved to the heap and owned by a capsule that numpy frees with the array.
#pragma once
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

namespace meshsal_py {

namespace py = pybind11;

// `values` as an array of `shape` (C order; the product of shape must be values.size()).
template <class T>
py::array_t<T> to_numpy(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(shape, owned->data(), owner);
}

template <class T>
py::array_t<T> to_numpy(std::vector<T>&& values) {
  const py::ssize_t n = py::ssize_t(values.size());
  return to_numpy(std::move(values), {n});
}

}  // namespace meshsal_py
