// meshsal: error quadrics for Garland-Heckbert simplification.
#include "simplify/quadric.h"
#include "core/vec3.h"

#include <cmath>

namespace meshsal {

Quadric plane_quadric(const double n[3], double d, double w) {
  Quadric q;
  q.a00 = w * n[0] * n[0]; q.a01 = w * n[0] * n[1]; q.a02 = w * n[0] * n[2];
  q.a11 = w * n[1] * n[1]; q.a12 = w * n[1] * n[2]; q.a22 = w * n[2] * n[2];
  q.b0 = w * n[0] * d; q.b1 = w * n[1] * d; q.b2 = w * n[2] * d;
  q.c = w * d * d;
  return q;
}

Quadric triangle_quadric(const double p0[3], const double p1[3], const double p2[3]) {
  const double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
  const double e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
  double n[3];
  cross3(e1, e2, n);
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(len > 0)) return Quadric{};
  n[0] /= len; n[1] /= len; n[2] /= len;
  const double d = -(n[0] * p0[0] + n[1] * p0[1] + n[2] * p0[2]);
  return plane_quadric(n, d, 0.5 * len);  // weight = triangle area
}

Quadric border_quadric(const double p0[3], const double p1[3], const double p2[3],
                       double weight) {
  const double e[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
  const double e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
  double fn[3], n[3];
  cross3(e, e2, fn);    // triangle normal
  cross3(e, fn, n);    // in the triangle's plane, perpendicular to the edge
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(len > 0)) return Quadric{};
  n[0] /= len; n[1] /= len; n[2] /= len;
  const double d = -(n[0] * p0[0] + n[1] * p0[1] + n[2] * p0[2]);
  const double elen2 = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
  return plane_quadric(n, d, weight * elen2);
}

double optimal_placement(const Quadric& q, const double p0[3], const double p1[3],
                         double out[3], bool* used_fallback) {
  // Cofactors of the symmetric A.
  const double c00 = q.a11 * q.a22 - q.a12 * q.a12;
  const double c01 = q.a02 * q.a12 - q.a01 * q.a22;
  const double c02 = q.a01 * q.a12 - q.a02 * q.a11;
  const double det = q.a00 * c00 + q.a01 * c01 + q.a02 * c02;
  const double t = (q.a00 + q.a11 + q.a22) / 3;
  if (t > 0 && std::fabs(det) > 1e-6 * t * t * t) {
    const double c11 = q.a00 * q.a22 - q.a02 * q.a02;
    const double c12 = q.a01 * q.a02 - q.a00 * q.a12;
    const double c22 = q.a00 * q.a11 - q.a01 * q.a01;
    const double inv = -1.0 / det;  // x = -A^{-1} b
    out[0] = inv * (c00 * q.b0 + c01 * q.b1 + c02 * q.b2);
    out[1] = inv * (c01 * q.b0 + c11 * q.b1 + c12 * q.b2);
    out[2] = inv * (c02 * q.b0 + c12 * q.b1 + c22 * q.b2);
    if (std::isfinite(out[0]) && std::isfinite(out[1]) && std::isfinite(out[2])) {
      if (used_fallback) *used_fallback = false;
      return q.error(out);
    }
  }
  if (used_fallback) *used_fallback = true;
  const double mid[3] = {(p0[0] + p1[0]) / 2, (p0[1] + p1[1]) / 2, (p0[2] + p1[2]) / 2};
  const double* cand[3] = {p0, p1, mid};
  double best = q.error(p0);
  int bi = 0;
  for (int i = 1; i < 3; ++i) {
    const double e = q.error(cand[i]);
    if (e < best) { best = e; bi = i; }
  }
  out[0] = cand[bi][0]; out[1] = cand[bi][1]; out[2] = cand[bi][2];
  return best;
}

}  // namespace meshsal
