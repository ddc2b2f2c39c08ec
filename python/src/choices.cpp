#include "choices.h"

#include <cmath>

#include <pybind11/pybind11.h>

namespace meshsal_py {

namespace py = pybind11;

meshsal::Backend parse_backend(const std::string& name) {
  if (name == "auto") return meshsal::Backend::Auto;
  if (name == "cpu") return meshsal::Backend::Cpu;
  if (name == "gpu") return meshsal::Backend::Gpu;
  throw py::value_error("backend must be 'auto', 'cpu' or 'gpu', got '" + name + "'");
}

meshsal::UpAxis parse_up(const std::string& t) {
  if (t == "y" || t == "+y") return meshsal::UpAxis::Y;
  if (t == "-y") return meshsal::UpAxis::MinusY;
  if (t == "z" || t == "+z") return meshsal::UpAxis::Z;
  if (t == "-z") return meshsal::UpAxis::MinusZ;
  if (t == "x" || t == "+x") return meshsal::UpAxis::X;
  if (t == "-x") return meshsal::UpAxis::MinusX;
  throw py::value_error("up must be 'x', 'y', 'z', '-x', '-y' or '-z', got '" + t + "'");
}

namespace {

// Images of the frame's x, y, z unit vectors in the mesh's coordinates, per up axis (the
// library's camera table; tests compare the angles with `meshsal viewpoint --up`).
const double kAxes[6][3][3] = {
    {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}},    // y
    {{1, 0, 0}, {0, -1, 0}, {0, 0, -1}},  // -y
    {{1, 0, 0}, {0, 0, 1}, {0, -1, 0}},   // z
    {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}},   // -z
    {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},   // x
    {{0, 1, 0}, {-1, 0, 0}, {0, 0, 1}},   // -x
};

const double (&axes_of(meshsal::UpAxis up))[3][3] {
  switch (up) {
    case meshsal::UpAxis::Y: return kAxes[0];
    case meshsal::UpAxis::MinusY: return kAxes[1];
    case meshsal::UpAxis::Z: return kAxes[2];
    case meshsal::UpAxis::MinusZ: return kAxes[3];
    case meshsal::UpAxis::X: return kAxes[4];
    default: return kAxes[5];
  }
}

void direction_of(const meshsal::ViewAngles& a, double d[3]) {
  d[0] = std::cos(a.phi) * std::sin(a.theta);
  d[1] = std::sin(a.phi);
  d[2] = std::cos(a.phi) * std::cos(a.theta);
}

meshsal::ViewAngles angles_of(const double d[3]) {
  const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(n > 0)) return {};
  double y = d[1] / n;
  y = y > 1 ? 1 : (y < -1 ? -1 : y);
  meshsal::ViewAngles a;
  a.phi = std::asin(y);
  a.theta = (d[0] == 0 && d[2] == 0) ? 0.0 : std::atan2(d[0], d[2]);
  return a;
}

}  // namespace

meshsal::ViewAngles angles_for_up(const meshsal::ViewAngles& y_up, meshsal::UpAxis up, double direction[3]) {
  // The search's frame is y up: its direction is already in mesh coordinates.
  direction_of(y_up, direction);
  const auto& ax = axes_of(up);
  double local[3];
  for (int i = 0; i < 3; ++i)
    local[i] = ax[i][0] * direction[0] + ax[i][1] * direction[1] + ax[i][2] * direction[2];
  return angles_of(local);
}

}  // namespace meshsal_py

namespace meshsal_py {

meshsal::Method parse_method(const std::string& name) {
  if (name == "exact") return meshsal::Method::Exact;
  if (name == "fast") return meshsal::Method::Fast;
  if (name == "auto") return meshsal::Method::Auto;
  throw py::value_error("method must be 'exact', 'fast' or 'auto', got '" + name + "'");
}

meshsal::Precision parse_precision(const std::string& name) {
  if (name == "auto") return meshsal::Precision::Auto;
  if (name == "mixed") return meshsal::Precision::Mixed;
  if (name == "double") return meshsal::Precision::Double;
  throw py::value_error("precision must be 'auto', 'mixed' or 'double', got '" + name + "'");
}

}  // namespace meshsal_py
