// meshsal: cross and dot products on the flat double[3] arrays the code works with, by GLM
// (the one copy of the vector maths the host code used to write out by hand). With
// -ffp-contract=off (CMakeLists.txt) they give the bits of the formulas they replaced:
// glm::cross forms the same two products per component and subtracts them in the same
// order, glm::dot adds the three products left to right.
#pragma once
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace meshsal {

inline glm::dvec3 dvec3_of(const double* p) { return glm::dvec3(p[0], p[1], p[2]); }

inline void cross3(const double u[3], const double v[3], double out[3]) {
  const glm::dvec3 c = glm::cross(dvec3_of(u), dvec3_of(v));
  out[0] = c.x;
  out[1] = c.y;
  out[2] = c.z;
}

inline double dot3(const double u[3], const double v[3]) { return glm::dot(dvec3_of(u), dvec3_of(v)); }

}  // namespace meshsal
