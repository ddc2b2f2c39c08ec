#include "numpy_in.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdint>
#include <limits>

#include "arg_values.h"

namespace meshsal_py {

namespace {

// Any object numpy understands (a list, a trimesh TrackedArray, an Open3D Vector3dVector
// after np.asarray) as an ndarray; an ndarray itself is returned as it is (no copy).
py::array as_array(const py::handle& obj, const char* name) {
  if (py::isinstance<py::array>(obj)) return py::reinterpret_borrow<py::array>(obj);
  if (obj.is_none()) throw py::type_error(std::string(name) + " must be an array, got None");
  py::module_ np = py::module_::import("numpy");
  try {
    return np.attr("asarray")(obj);
  } catch (py::error_already_set&) {
    throw py::type_error(std::string(name) + " must be an array, got " +
                         std::string(py::str(obj.get_type().attr("__name__"))));
  }
}

std::string dtype_name(const py::array& a) { return std::string(py::str(a.dtype())); }

// The same values in the machine's byte order: a big-endian array ('>f8', from a file) is
// converted, the common native one passed through untouched.
py::array native_order(const py::array& a) {
  if (a.dtype().attr("isnative").cast<bool>()) return a;
  return a.attr("astype")(a.dtype().attr("newbyteorder")("="));
}

void check_rows_of_3(const py::array& a, const char* name) {
  if (a.ndim() != 2 || a.shape(1) != 3) {
    std::string shape = "(";
    for (py::ssize_t i = 0; i < a.ndim(); ++i) shape += (i ? ", " : "") + std::to_string(a.shape(i));
    shape += a.ndim() == 1 ? ",)" : ")";
    throw py::value_error(std::string(name) + " must have shape (n, 3), got " + shape);
  }
}

template <class T>
void read_vertices(const py::array& a, std::vector<double>& out) {
  auto v = a.unchecked<T, 2>();  // strided access: views need no copy
  const py::ssize_t n = v.shape(0);
  out.resize(size_t(n) * 3);
  for (py::ssize_t i = 0; i < n; ++i)
    for (py::ssize_t k = 0; k < 3; ++k) {
      const T x = v(i, k);
      if (!std::isfinite(x))
        throw py::value_error("vertices: vertex " + std::to_string(i) + " has a non-finite coordinate (" +
                              std::to_string(double(x)) + ")");
      const float f = static_cast<float>(x);
      if (!std::isfinite(f))  // a float64 beyond float32's range (the library's precision)
        throw py::value_error("vertices: vertex " + std::to_string(i) + " has a coordinate beyond float32's range (" +
                              std::to_string(double(x)) + ")");
      out[size_t(i) * 3 + size_t(k)] = double(x);
    }
}

template <class T>
void read_faces(const py::array& a, size_t vertex_count, std::vector<uint32_t>& out) {
  auto f = a.unchecked<T, 2>();
  const py::ssize_t m = f.shape(0);
  out.resize(size_t(m) * 3);
  for (py::ssize_t i = 0; i < m; ++i)
    for (py::ssize_t k = 0; k < 3; ++k) {
      const T x = f(i, k);
      // Compared in the index's own type: no sign or width conversion can hide a bad value.
      bool negative = false;
      if constexpr (std::is_signed_v<T>) negative = x < 0;
      if (negative || static_cast<unsigned long long>(x) >= vertex_count)
        throw py::value_error("faces: index " + std::to_string(x) + " in face " + std::to_string(i) +
                              " is out of range for " + std::to_string(vertex_count) + " vertices");
      out[size_t(i) * 3 + size_t(k)] = static_cast<uint32_t>(x);
    }
}

// Raises MemoryError when copying `bytes` would not fit in this machine's memory.
void check_fits_memory(double bytes, const std::string& what) {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return;
  const double memory = double(pages) * double(page);
  if (bytes <= memory) return;
  char buf[128];
  std::snprintf(buf, sizeof buf, " need %.1f GiB as the library's arrays, more than this machine's %.1f GiB",
                bytes / 1073741824.0, memory / 1073741824.0);
  PyErr_SetString(PyExc_MemoryError, (what + buf).c_str());
  throw py::error_already_set();
}

}  // namespace

meshsal::Mesh mesh_from_arrays(const py::handle& vertices_obj, const py::handle& faces_obj) {
  py::array vertices = as_array(vertices_obj, "vertices");
  py::array faces = as_array(faces_obj, "faces");
  const char kind_v = vertices.dtype().kind();
  if (!(kind_v == 'f' && (vertices.itemsize() == 4 || vertices.itemsize() == 8)))
    throw py::type_error("vertices must be float32 or float64, got " + dtype_name(vertices));
  const char kind_f = faces.dtype().kind();
  if (kind_f != 'i' && kind_f != 'u')
    throw py::type_error("faces must be an integer array (int32, int64, uint32, ...), got " + dtype_name(faces));
  check_rows_of_3(vertices, "vertices");
  check_rows_of_3(faces, "faces");
  vertices = native_order(vertices);
  faces = native_order(faces);
  if (vertices.shape(0) > py::ssize_t(std::numeric_limits<uint32_t>::max()))
    throw py::value_error("vertices: more than 2^32 - 1 vertices");
  if (faces.shape(0) > py::ssize_t(std::numeric_limits<uint32_t>::max()))
    throw py::value_error("faces: more than 2^32 - 1 faces");
  // The shape can claim more than memory holds (a broadcast array's rows cost nothing):
  // say so before asking for it, instead of a bad_alloc after a long wait.
  check_fits_memory(36.0 * double(vertices.shape(0)) + 12.0 * double(faces.shape(0)),
                    std::to_string(vertices.shape(0)) + " vertices and " + std::to_string(faces.shape(0)) + " faces");

  meshsal::Mesh mesh;
  // Read in double, localized once the faces are known (the origin is the centre of the
  // mesh points): meshsal::make_mesh's rule, so Python and the loaders agree.
  std::vector<double> xyz;
  if (vertices.itemsize() == 4) read_vertices<float>(vertices, xyz);
  else read_vertices<double>(vertices, xyz);
  const size_t n = xyz.size() / 3;
  const bool is_signed = kind_f == 'i';
  switch (faces.itemsize()) {
    case 1: is_signed ? read_faces<int8_t>(faces, n, mesh.triangles) : read_faces<uint8_t>(faces, n, mesh.triangles); break;
    case 2: is_signed ? read_faces<int16_t>(faces, n, mesh.triangles) : read_faces<uint16_t>(faces, n, mesh.triangles); break;
    case 4: is_signed ? read_faces<int32_t>(faces, n, mesh.triangles) : read_faces<uint32_t>(faces, n, mesh.triangles); break;
    case 8: is_signed ? read_faces<int64_t>(faces, n, mesh.triangles) : read_faces<uint64_t>(faces, n, mesh.triangles); break;
    default: throw py::type_error("faces: unsupported integer dtype " + dtype_name(faces));
  }
  meshsal::set_model_positions(mesh, xyz.data(), n);
  meshsal::validate_mesh(mesh);  // empty mesh, only zero-area triangles: meshsal.Error
  return mesh;
}

bool float32_vertices(const py::handle& vertices) {
  return py::isinstance<py::array>(vertices) && py::reinterpret_borrow<py::array>(vertices).dtype().kind() == 'f' &&
         py::reinterpret_borrow<py::array>(vertices).itemsize() == 4;
}

std::vector<double> vertex_values(const py::handle& obj, size_t count, const char* name) {
  py::array a = as_array(obj, name);
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    throw py::type_error(std::string(name) + " must be a real array, got " + dtype_name(a));
  if (a.ndim() != 1 || size_t(a.shape(0)) != count)
    throw py::value_error(std::string(name) + " must have shape (" + std::to_string(count) +
                          ",), one value per vertex, got " + std::to_string(a.ndim()) + "-D with " +
                          std::to_string(a.size()) + " values");
  // float64 in any layout: numpy converts (only when the dtype or strides need it).
  py::array_t<double, py::array::forcecast> d(a);
  auto v = d.unchecked<1>();
  std::vector<double> out(count);
  for (size_t i = 0; i < count; ++i) {
    out[i] = v(py::ssize_t(i));
    if (!std::isfinite(out[i]))
      throw py::value_error(std::string(name) + ": value " + std::to_string(i) + " is not finite");
  }
  return out;
}

std::vector<double> scales_from(const py::handle& scales) {
  if (py::isinstance<py::str>(scales)) return meshsal::parse_scales(scales.cast<std::string>());
  // More than the library's 16 are read only to be refused by its check.
  std::vector<double> out;
  for (const py::object& s : sequence_items(scales, "scales", "a sequence of numbers or a str such as '2,3,4,5,6'", meshsal::kMaxScaleCount))
    out.push_back(number_arg(s, "scales"));
  return out;
}

}  // namespace meshsal_py
