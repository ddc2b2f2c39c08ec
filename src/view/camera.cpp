#include "view/camera.h"

#include <cmath>

#include "core/mesh_points.h"

namespace meshsal {

ViewFrame frame_mesh(const Mesh& mesh) {
  BoundingBox box = mesh_points_bbox(mesh, referenced_vertices(mesh));
  ViewFrame f;
  for (int k = 0; k < 3; ++k) f.centre[k] = 0.5 * (box.min[k] + box.max[k]);
  f.radius = 0.5 * box.diagonal();
  if (!(f.radius > 0)) f.radius = 1;  // a degenerate box still gets a usable camera
  return f;
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
  up[0] = d[1] * right[2] - d[2] * right[1];
  up[1] = d[2] * right[0] - d[0] * right[2];
  up[2] = d[0] * right[1] - d[1] * right[0];
}

ViewRows view_rows(const ViewFrame& frame, const ViewAngles& a) {
  double axes[3][3];
  view_basis(a, axes[0], axes[1], axes[2]);
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
