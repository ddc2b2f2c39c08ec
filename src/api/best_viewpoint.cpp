// best_viewpoint(): the one view pipeline every front end calls (`meshsal viewpoint`,
// `render --best`, `batch --view`, Python): the up frame, the scorer for the chosen backend,
// the gradient ascent and the optional exhaustive map within the elevation range, U over the
// total, and the camera the pictures use.
#include "api/viewpoint_backend.h"
#include "core/cancel.h"
#include "meshsal/meshsal.h"
#include "view/camera.h"
#include "view/render.h"
#include "view/viewpoint.h"
#include "view/visibility.h"

namespace meshsal {

namespace {

// The mesh in the frame of `up`: vertex p becomes (axes[0].p, axes[1].p, axes[2].p), the
// frame's own coordinates, in which the search runs with y up. The axes are signed unit
// vectors, so each coordinate is one of p's, perhaps negated: exact, and a mesh turned so
// that z is up gives back the y-up mesh's very coordinates.
Mesh in_frame(const Mesh& mesh, UpAxis up) {
  ViewFrame f;
  set_up_axis(f, up);
  int from[3];
  float sign[3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (f.axes[i][j] != 0) {
        from[i] = j;
        sign[i] = f.axes[i][j] > 0 ? 1.0f : -1.0f;
      }
  Mesh m;
  m.triangles = mesh.triangles;
  m.positions.resize(mesh.positions.size());
  for (size_t v = 0; v + 2 < mesh.positions.size(); v += 3)
    for (int i = 0; i < 3; ++i) m.positions[v + size_t(i)] = sign[i] * mesh.positions[v + size_t(from[i])];
  return m;
}

// A direction of the search through its unit vector and back: the angles every front end
// printed before this function existed (they turned the search's angles into the frame of
// --up that way), so that `meshsal viewpoint` prints what it printed, to the last digit.
// The same for every up axis (the search's frame is already the up frame).
ViewAngles normalised(const ViewAngles& a) {
  double d[3];
  view_direction(a, d);
  return direction_angles(ViewFrame{}, d);
}

// The search, its angles as optimise_viewpoint and exhaustive_map return them.
Viewpoint search(const Mesh& mesh, const std::vector<double>& score, const ViewpointOptions& o) {
  const CancelScope cancel(o.optimiser.cancel);
  if (o.views < 0) throw Error("views must be >= 0, got " + std::to_string(o.views));
  const LatitudeBand band = latitude_band(o.elevation);

  Viewpoint out;
  out.up = o.up;
  const auto notice = [&out, &o](const std::string& line) {
    out.notices.push_back(line);
    if (o.notice) o.notice(line);
  };
  Mesh turned;
  if (o.up != UpAxis::Y) turned = in_frame(mesh, o.up);
  const Mesh& searched = o.up != UpAxis::Y ? turned : mesh;
  const ViewScorerSetup setup = make_view_scorer(searched, score, o.visibility, o.backend, o.device, notice, o.session);
  out.backend_name = setup.backend_name;
  out.optimised = optimise_viewpoint(setup.scorer, o.optimiser, band);
  if (o.views > 0) out.map = exhaustive_map(setup.scorer, o.views, setup.batch, o.optimiser.progress, band);
  return out;  // a GPU scorer gives its device back here
}

}  // namespace

ViewCamera view_camera(const Mesh& mesh, const ViewAngles& view, UpAxis up) {
  const ViewFrame frame = frame_mesh(mesh, up);
  const PictureFit fit = fit_picture(mesh, frame, view);
  double right[3], upv[3], d[3];
  view_basis(frame, view, right, upv, d);
  ViewCamera c;
  c.view = view;
  c.up_axis = up;
  for (int k = 0; k < 3; ++k) {
    c.target[k] = frame.centre[k] + fit.cx * right[k] + fit.cy * upv[k];
    c.eye[k] = c.target[k] + frame.radius * d[k];
    c.up[k] = upv[k];
    c.direction[k] = d[k];
  }
  c.half_extent = fit.half;
  return c;
}

Viewpoint best_viewpoint(const Mesh& mesh, const std::vector<double>& score, const ViewpointOptions& o) {
  Viewpoint out = search(mesh, score, o);
  for (float w : visibility_weights(mesh, score)) out.total += w;
  out.optimised.best = normalised(out.optimised.best);
  for (ViewAngles& a : out.map.views) a = normalised(a);
  out.view = out.optimised.best;
  out.U = out.optimised.U;
  out.visible_fraction = out.total > 0 ? out.U / out.total : 0.0;
  out.note = out.optimised.note;
  out.camera = view_camera(mesh, out.view, o.up);
  return out;
}

}  // namespace meshsal
