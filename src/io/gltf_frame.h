// meshsal (internal): 4x4 transforms of glTF nodes, column-major as glTF stores them, in
// double: node TRS to matrix, composition, and applying one to points and normals; and
// the sRGB transfer function for glTF's linear vertex colours.
#pragma once
#include <array>

namespace meshsal {

using Frame = std::array<double, 16>;  // column-major: element (row r, column c) at 4c + r

Frame identity_frame();
// translation t, rotation quaternion q (x, y, z, w; normalised here), scale s: T * R * S.
Frame trs_frame(const double t[3], const double q[4], const double s[3]);
Frame multiply(const Frame& a, const Frame& b);  // a * b
// The inverse of an affine transform (last row 0 0 0 1); an all-zero frame when singular.
Frame inverse_affine(const Frame& m);
// The inverse transpose of the upper 3x3 (normals transform with it), in the upper 3x3.
Frame normal_matrix(const Frame& m);
double determinant3(const Frame& m);  // of the upper 3x3: < 0 for a mirroring transform
void transform_point(const Frame& m, const double p[3], double out[3]);
void transform_direction(const Frame& m, const double d[3], double out[3]);  // upper 3x3 only

// glTF's vertex colours are linear; meshsal's colours (pictures, PLY red green blue) sRGB.
double srgb_to_linear(double c);
double linear_to_srgb(double c);

}  // namespace meshsal
