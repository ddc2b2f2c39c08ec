// meshsal: glTF node transforms (gltf_frame.h).
#include "io/gltf_frame.h"

#include <cmath>

namespace meshsal {

Frame identity_frame() { return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; }

Frame trs_frame(const double t[3], const double q[4], const double s[3]) {
  double x = q[0], y = q[1], z = q[2], w = q[3];
  const double len = std::sqrt(x * x + y * y + z * z + w * w);
  if (len > 0) x /= len, y /= len, z /= len, w /= len;
  const double r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),    // column 0
                       2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),    // column 1
                       2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y)};  // column 2
  Frame m = identity_frame();
  for (int c = 0; c < 3; ++c)
    for (int row = 0; row < 3; ++row) m[4 * c + row] = r[3 * c + row] * s[c];
  for (int row = 0; row < 3; ++row) m[12 + row] = t[row];
  return m;
}

Frame multiply(const Frame& a, const Frame& b) {
  Frame m{};
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      double sum = 0;
      for (int k = 0; k < 4; ++k) sum += a[4 * k + r] * b[4 * c + k];
      m[4 * c + r] = sum;
    }
  return m;
}

double determinant3(const Frame& m) {
  return m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) + m[8] * (m[1] * m[6] - m[5] * m[2]);
}

namespace {
// The inverse of the upper 3x3 (column-major 3x3 in a Frame's layout); false when singular.
bool invert3(const Frame& m, Frame& inv) {
  const double det = determinant3(m);
  if (det == 0 || !std::isfinite(det)) return false;
  auto at = [&](int r, int c) { return m[4 * c + r]; };
  inv = identity_frame();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      // cofactor of (c, r) / det: the adjugate's (r, c)
      const int r0 = (c + 1) % 3, r1 = (c + 2) % 3, c0 = (r + 1) % 3, c1 = (r + 2) % 3;
      inv[4 * c + r] = (at(r0, c0) * at(r1, c1) - at(r0, c1) * at(r1, c0)) / det;
    }
  return true;
}
}  // namespace

Frame inverse_affine(const Frame& m) {
  Frame inv;
  if (!invert3(m, inv)) return Frame{};
  const double t[3] = {m[12], m[13], m[14]};
  for (int r = 0; r < 3; ++r) inv[12 + r] = -(inv[r] * t[0] + inv[4 + r] * t[1] + inv[8 + r] * t[2]);
  return inv;
}

Frame normal_matrix(const Frame& m) {
  Frame inv;
  if (!invert3(m, inv)) return identity_frame();
  Frame n = identity_frame();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) n[4 * c + r] = inv[4 * r + c];
  return n;
}

void transform_point(const Frame& m, const double p[3], double out[3]) {
  for (int r = 0; r < 3; ++r) out[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
}

void transform_direction(const Frame& m, const double d[3], double out[3]) {
  for (int r = 0; r < 3; ++r) out[r] = m[r] * d[0] + m[4 + r] * d[1] + m[8 + r] * d[2];
}

double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

double linear_to_srgb(double c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055; }

}  // namespace meshsal
