#include "view/camera.h"

#include <cmath>

#include "core/mesh_points.h"
#include "core/vec3.h"

namespace meshsal {

ViewFrame frame_mesh(const Mesh& mesh, UpAxis up) {
  BoundingBox box = mesh_points_bbox(mesh, referenced_vertices(mesh));
  ViewFrame f;
  for (int k = 0; k < 3; ++k) f.centre[k] = 0.5 * (box.min[k] + box.max[k]);
  f.radius = 0.5 * box.diagonal();
  if (!(f.radius > 0)) f.radius = 1;  // a degenerate box still gets a usable camera
  set_up_axis(f, up);
  return f;
}

void set_up_axis(ViewFrame& f, UpAxis up) {
  // Images of the frame's x, y, z unit vectors; each set is a proper rotation (det +1).
  static const double kAxes[6][3][3] = {
      {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}},     // y
      {{1, 0, 0}, {0, -1, 0}, {0, 0, -1}},   // -y: half a turn about x
      {{1, 0, 0}, {0, 0, 1}, {0, -1, 0}},    // z: front (theta 0) at -y
      {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}},    // -z: front at +y
      {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},    // x
      {{0, 1, 0}, {-1, 0, 0}, {0, 0, 1}},    // -x
  };
  int k = up == UpAxis::Y ? 0 : up == UpAxis::MinusY ? 1 : up == UpAxis::Z ? 2
        : up == UpAxis::MinusZ ? 3 : up == UpAxis::X ? 4 : 5;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) f.axes[i][j] = kAxes[k][i][j];
}

UpAxis parse_up_axis(const std::string& t) {
  if (t == "y" || t == "+y") return UpAxis::Y;
  if (t == "-y") return UpAxis::MinusY;
  if (t == "z" || t == "+z") return UpAxis::Z;
  if (t == "-z") return UpAxis::MinusZ;
  if (t == "x" || t == "+x") return UpAxis::X;
  if (t == "-x") return UpAxis::MinusX;
  throw Error("up must be x, y, z, -x, -y or -z, got '" + t + "'");
}

static void to_mesh(const ViewFrame& f, double v[3]) {
  double w[3];
  for (int j = 0; j < 3; ++j) w[j] = v[0] * f.axes[0][j] + v[1] * f.axes[1][j] + v[2] * f.axes[2][j];
  for (int j = 0; j < 3; ++j) v[j] = w[j];
}

void view_direction(const ViewFrame& f, const ViewAngles& a, double d[3]) {
  view_direction(a, d);
  to_mesh(f, d);
}

void view_basis(const ViewFrame& f, const ViewAngles& a, double right[3], double up[3], double d[3]) {
  view_basis(a, right, up, d);
  to_mesh(f, right);
  to_mesh(f, up);
  to_mesh(f, d);
}

ViewAngles direction_angles(const ViewFrame& f, const double d[3]) {
  double local[3];
  for (int i = 0; i < 3; ++i) local[i] = f.axes[i][0] * d[0] + f.axes[i][1] * d[1] + f.axes[i][2] * d[2];
  return direction_angles(local);
}

void view_direction(const ViewAngles& a, double d[3]) {
  d[0] = std::cos(a.phi) * std::sin(a.theta);
  d[1] = std::sin(a.phi);
  d[2] = std::cos(a.phi) * std::cos(a.theta);
}

ViewAngles direction_angles(const double d[3]) {
  double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(n > 0)) return {};
  double y = d[1] / n;
  y = y > 1 ? 1 : (y < -1 ? -1 : y);
  ViewAngles a;
  a.phi = std::asin(y);
  a.theta = (d[0] == 0 && d[2] == 0) ? 0.0 : std::atan2(d[0], d[2]);
  return a;
}

void view_basis(const ViewAngles& a, double right[3], double up[3], double d[3]) {
  view_direction(a, d);
  right[0] = std::cos(a.theta);
  right[1] = 0;
  right[2] = -std::sin(a.theta);
  cross3(d, right, up);
}

ViewRows view_rows(const ViewFrame& frame, const ViewAngles& a) {
  double axes[3][3];
  view_basis(frame, a, axes[0], axes[1], axes[2]);
  ViewRows v;
  double inv_r = 1.0 / frame.radius;
  for (int r = 0; r < 3; ++r) {
    double off = 0;
    for (int k = 0; k < 3; ++k) {
      v.row[r][k] = float(axes[r][k] * inv_r);
      off += axes[r][k] * frame.centre[k];
    }
    v.row[r][3] = float(-off * inv_r);
  }
  return v;
}

}  // namespace meshsal
