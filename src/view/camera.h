// meshsal: the orthographic view camera of viewpoint selection (SPEC 3) and of the pictures.
//
// Direction of a view, theta = longitude, phi = latitude, y up:
//   d(theta, phi) = (cos phi sin theta, sin phi, cos phi cos theta)
// so (0, 0) looks from +z (the front of y-up scans such as the bunny), theta = pi/2 from +x,
// phi = pi/2 from above. d points from the mesh towards the viewer; the camera looks along -d
// at the centre c of the bounding box of the mesh points and frames the bounding sphere
// (radius R = half the bbox diagonal) exactly: the image square is [-R, R]^2.
//   right = (cos theta, 0, -sin theta)      (always horizontal, so the poles are fine)
//   up    = d x right
// A point p maps to normalised coordinates
//   x = (p-c).right / R,  y = (p-c).up / R,  z = (p-c).d / R      (all in [-1, 1])
// and to pixel coordinates of a res x res image (pixel centres at i + 0.5, row 0 on top)
//   px = (x + 1) res / 2,  py = (1 - y) res / 2,  depth = max(0, (1 - z) / 2)
// depth is 0 at the viewer side of the bounding sphere and 1 at its far side.
#pragma once
#include <string>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {

// Centre, radius and up axis that every view of one mesh shares. The formulas above are in
// the frame's own coordinates (y up); axes[k] is where its unit vector k lies in the mesh's
// coordinates (identity for y up). --up z turns the camera, never the mesh, so every path
// that projects through view_rows (the GPU visibility shaders too) sees the same turn.
struct ViewFrame {
  double centre[3] = {0, 0, 0};
  double radius = 1;
  double axes[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
};

// Bounding-box centre and half diagonal of the mesh points, with `up` as the frame's up axis.
// Throws Error on an empty mesh.
ViewFrame frame_mesh(const Mesh& mesh, UpAxis up = UpAxis::Y);

// Sets frame.axes for `up`: a rotation (right-handed) taking +y to `up`. For z up, theta 0
// looks from -y (the front of z-up scans), for -z from +y, x from +z... (see camera.cpp).
void set_up_axis(ViewFrame& frame, UpAxis up);

// Direction and basis in the frame's own coordinates (y up).
void view_direction(const ViewAngles& a, double d[3]);
ViewAngles direction_angles(const double d[3]);  // d need not be unit length
void view_basis(const ViewAngles& a, double right[3], double up[3], double d[3]);

// The same in the mesh's coordinates (frame.axes applied).
void view_direction(const ViewFrame& frame, const ViewAngles& a, double d[3]);
void view_basis(const ViewFrame& frame, const ViewAngles& a, double right[3], double up[3], double d[3]);
// Angles in `frame` of a direction given in the mesh's coordinates.
ViewAngles direction_angles(const ViewFrame& frame, const double d[3]);

// The affine map p -> (x, y, z) above as three float rows (x = row.xyz . p + row.w), the
// form the GPU shaders get, so that the CPU twin projects with the very same numbers.
struct ViewRows {
  float row[3][4];
};
ViewRows view_rows(const ViewFrame& frame, const ViewAngles& a);

// Projection of one point with the rows, float arithmetic in a fixed order (the shaders
// use the same expressions).
struct Projected {
  float px, py, depth;
};
inline Projected project(const ViewRows& v, float x, float y, float z, float half_res) {
  float nx = v.row[0][0] * x + v.row[0][1] * y + v.row[0][2] * z + v.row[0][3];
  float ny = v.row[1][0] * x + v.row[1][1] * y + v.row[1][2] * z + v.row[1][3];
  float nz = v.row[2][0] * x + v.row[2][1] * y + v.row[2][2] * z + v.row[2][3];
  float d = (1.0f - nz) * 0.5f;
  return {(nx + 1.0f) * half_res, (1.0f - ny) * half_res, d > 0.0f ? d : 0.0f};
}

}  // namespace meshsal
