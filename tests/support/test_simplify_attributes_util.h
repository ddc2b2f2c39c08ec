// Test meshes with attributes: an icosphere written as OBJ text with spherical texture
// coordinates (a UV seam where u wraps from 1 to 0) and normals, and UV checks.
#pragma once
#include <cmath>
#include <string>
#include <vector>

#include "meshsal/meshsal.h"

namespace attr_test {

constexpr double kPi = 3.14159265358979323846;

// Spherical texture coordinates of a point on the unit sphere: u the longitude in [0, 1),
// v the colatitude in [0, 1].
inline void sphere_uv(const float* p, double* u, double* v) {
  double x = p[0], y = p[1], z = p[2];
  const double r = std::sqrt(x * x + y * y + z * z);
  *u = std::atan2(z, x) / (2 * kPi) + 0.5;
  if (*u >= 1) *u -= 1;
  *v = std::acos(std::max(-1.0, std::min(1.0, y / r))) / kPi;
}

// The mesh as OBJ text: v per vertex, vn = the unit position, vt per (vertex, side): a
// triangle whose corners' u spans more than half the range crosses the seam, and its
// corners with u < 0.5 take u + 1. Those vertices get two vt: the seam.
inline std::string seamed_sphere_obj(const meshsal::Mesh& m, size_t* seam_vertices = nullptr) {
  const size_t nv = m.vertex_count();
  std::string s = "# sphere with a UV seam\n";
  char line[160];
  for (size_t i = 0; i < nv; ++i) {
    const float* p = &m.positions[3 * i];
    std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", p[0], p[1], p[2]);
    s += line;
  }
  for (size_t i = 0; i < nv; ++i) {
    double u, v;
    sphere_uv(&m.positions[3 * i], &u, &v);
    std::snprintf(line, sizeof line, "vt %.9g %.9g\nvt %.9g %.9g\n", u, v, u + 1, v);
    s += line;
  }
  for (size_t i = 0; i < nv; ++i) {
    const float* p = &m.positions[3 * i];
    const double r = std::sqrt(double(p[0]) * p[0] + double(p[1]) * p[1] + double(p[2]) * p[2]);
    std::snprintf(line, sizeof line, "vn %.9g %.9g %.9g\n", p[0] / r, p[1] / r, p[2] / r);
    s += line;
  }
  std::vector<uint8_t> plain(nv, 0), shifted(nv, 0);
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    double u[3], v;
    for (int k = 0; k < 3; ++k) sphere_uv(&m.positions[3 * size_t(m.triangles[3 * t + k])], &u[k], &v);
    const double span = std::max({u[0], u[1], u[2]}) - std::min({u[0], u[1], u[2]});
    s += "f";
    for (int k = 0; k < 3; ++k) {
      const uint32_t i = m.triangles[3 * t + k];
      const bool shift = span > 0.5 && u[k] < 0.5;
      (shift ? shifted : plain)[i] = 1;
      std::snprintf(line, sizeof line, " %u/%u/%u", i + 1, 2 * i + 1 + (shift ? 1 : 0), i + 1);
      s += line;
    }
    s += "\n";
  }
  if (seam_vertices) {
    *seam_vertices = 0;
    for (size_t i = 0; i < nv; ++i) *seam_vertices += plain[i] && shifted[i];
  }
  return s;
}

inline const meshsal::VertexAttribute* find(const meshsal::Mesh& m, const std::string& name) {
  for (const meshsal::VertexAttribute& a : m.attributes)
    if (a.name == name) return &a;
  return nullptr;
}

}  // namespace attr_test
