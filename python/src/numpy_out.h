// meshsal Python module: library results out as numpy arrays without a copy. The vector is
// moved to the heap and owned by a capsule that numpy frees with the array.
#pragma once
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "meshsal/meshsal.h"

namespace meshsal_py {

namespace py = pybind11;

// `values` as an array of `shape` (C order; the product of shape must be values.size()).
template <class T>
py::array_t<T> to_numpy(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(shape, owned->data(), owner);
}

// A mesh's vertices as an (n, 3) array in the model's own coordinates (meshsal::model_positions).
// `exact`: float64 unless every coordinate is a float32 value (a binary float PLY or STL), so
// that what load() returns is what the file said (a text file's decimals stay doubles, and
// saliency() of them equals the CLI's on the file). Otherwise (a result): float64 where
// float32 would not hold them (meshsal::positions_need_double: float64 input, a double PLY,
// a scan at survey coordinates), else float32.
// `wide_input`: the caller's vertices were float64, so are the results.
inline py::array model_vertices(const meshsal::Mesh& mesh, bool exact = false, bool wide_input = false) {
  const py::ssize_t n = py::ssize_t(mesh.vertex_count());
  std::vector<double> xyz = meshsal::model_positions(mesh);
  bool wide = wide_input || meshsal::positions_need_double(mesh);
  for (size_t i = 0; exact && !wide && i < xyz.size(); ++i) wide = double(float(xyz[i])) != xyz[i];
  if (wide) return to_numpy(std::move(xyz), {n, 3});
  std::vector<float> narrow(xyz.begin(), xyz.end());
  return to_numpy(std::move(narrow), {n, 3});
}

template <class T>
py::array_t<T> to_numpy(std::vector<T>&& values) {
  const py::ssize_t n = py::ssize_t(values.size());
  return to_numpy(std::move(values), {n});
}

}  // namespace meshsal_py
