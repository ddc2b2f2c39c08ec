// meshsal Python module: best_view() and render().
#include <climits>
#include <cstdio>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "arg_values.h"
#include "bindings.h"
#include "meshsal/meshsal.h"
#include "numpy_in.h"
#include "numpy_out.h"
#include "saliency_args.h"
#include "interrupt.h"

namespace meshsal_py {

namespace {

const double kDeg = 180.0 / 3.14159265358979323846;

// The per-vertex score of a view: the given array, or the saliency computed as the CLI does
// (called without the GIL).
std::vector<double> score_or_saliency(const meshsal::Mesh& mesh, std::vector<double>&& given,
                                      const meshsal::SaliencyOptions& options) {
  if (!given.empty()) return std::move(given);
  return meshsal::compute_saliency(mesh, options).saliency;
}

// One view as `meshsal viewpoint` prints it: angles in the frame of `up`, degrees, the
// direction in the mesh's coordinates (unit, towards the viewer) and U (visible_score).
py::dict view_dict(const meshsal::ViewAngles& a, const double direction[3], double U) {
  py::dict v;
  v["theta"] = a.theta;
  v["phi"] = a.phi;
  v["theta_deg"] = a.theta * kDeg;
  v["phi_deg"] = a.phi * kDeg;
  v["direction"] = py::make_tuple(direction[0], direction[1], direction[2]);
  v["visible_score"] = U;
  return v;
}

// A pair of values (elevation, color_range): ValueError naming how many were given.
std::vector<py::object> pair_items(const py::object& value, const char* name, const char* expected) {
  std::vector<py::object> t = sequence_items(value, name, expected, 2);
  if (t.size() != 2)
    throw py::value_error(std::string(name) + " must be " + expected + ", got " +
                          (t.size() > 2 ? std::string("more than 2") : std::to_string(t.size())) + " values");
  return t;
}

// "10 to 30": the default elevation band, for the docs.
std::string default_band() {
  char b[64];
  std::snprintf(b, sizeof b, "%g to %g", meshsal::kDefaultElevationMin, meshsal::kDefaultElevationMax);
  return b;
}

// elevation=(min, max) in degrees, or None (the default band, kDefaultElevationMin..Max);
// the library checks the range.
meshsal::ElevationRange elevation_range(const py::object& elevation) {
  meshsal::ElevationRange r;
  if (elevation.is_none()) return r;
  if (py::isinstance<py::str>(elevation)) return meshsal::parse_elevation_range(elevation.cast<std::string>());
  const std::vector<py::object> t = pair_items(elevation, "elevation", "(min, max) in degrees, a str such as '0,60', or None");
  r.min = number_arg(t[0], "elevation");
  r.max = number_arg(t[1], "elevation");
  return r;
}

py::dict best_view(const py::object& vertices, const py::object& faces, const py::object& score,
                   const py::object& restarts_arg, const py::object& seed_arg, const py::object& views_arg,
                   const py::object& resolution_arg, const py::object& depth_tol_arg, const std::string& up,
                   const py::object& elevation, const py::object& scales, const py::object& eps_frac,
                   const std::string& method, const std::string& backend, const std::string& precision,
                   const py::object& device, const py::object& threads, const std::string& model) {
  const meshsal::Mesh mesh = mesh_from_arrays(vertices, faces);
  // The CLI's ranges (the library checks resolution and depth_tol itself).
  const int restarts = int(integer_arg(restarts_arg, "restarts", 1, meshsal::kMaxViewRestarts));
  const int views = int(integer_arg(views_arg, "views", 0, meshsal::kMaxViewMapViews));
  const int resolution = int(integer_arg(resolution_arg, "resolution", meshsal::kMinImageSize, meshsal::kMaxImageSize));
  const uint64_t seed = unsigned_arg(seed_arg, "seed", 0, std::numeric_limits<uint64_t>::max());
  const double depth_tol = number_arg(depth_tol_arg, "depth_tol");
  if (!(depth_tol >= 0 && depth_tol <= meshsal::kMaxDepthTolPx))
    throw py::value_error("depth_tol must be in [0, " + std::to_string(meshsal::kMaxDepthTolPx) + "], got " +
                          std::string(py::str(depth_tol_arg)));
  meshsal::ViewpointOptions vo;
  vo.up = meshsal::parse_up_axis(up);
  vo.elevation = elevation_range(elevation);
  std::vector<double> given;
  if (!score.is_none()) given = vertex_values(score, mesh.vertex_count(), "score");
  const bool computed = given.empty();
  std::vector<std::string> notices;
  meshsal::SaliencyOptions so =
      saliency_options({scales, eps_frac, method, backend, precision, device, threads, model, up}, &notices);
  vo.optimiser.restarts = restarts;
  vo.optimiser.seed = seed;
  vo.views = views;
  vo.visibility.resolution = resolution;
  vo.visibility.depth_tol_px = depth_tol;
  vo.visibility.threads = so.threads;
  use_saliency_device(vo, so);
  meshsal::Viewpoint b;
  meshsal::ViewCamera map_best;
  {
    const InterruptibleCall call;  // Ctrl-C stops it (interrupt.h)
    so.cancel = vo.optimiser.cancel = call.flag();
    const std::vector<double> s = score_or_saliency(mesh, std::move(given), so);
    b = meshsal::best_viewpoint(mesh, s, vo);  // the one view pipeline, as the CLI's
    if (views > 0) map_best = meshsal::view_camera(mesh, b.map.views[b.map.best], vo.up);
  }
  py::dict out = view_dict(b.view, b.camera.direction, b.U);
  out["visible_fraction"] = b.visible_fraction;
  out["score_source"] = computed ? "computed (" + b.backend_name + ")" : std::string("given");
  out["device"] = b.backend_name;
  out["resolution"] = resolution;
  out["depth_tol_px"] = depth_tol;
  out["elevation"] = py::make_tuple(vo.elevation.min, vo.elevation.max);
  out["restarts"] = restarts;
  out["seed"] = seed;
  if (views > 0) {
    py::dict ex = view_dict(b.map.views[b.map.best], map_best.direction, b.map.U[b.map.best]);
    ex["views"] = views;
    out["exhaustive"] = ex;
  } else {
    out["exhaustive"] = py::none();
  }
  out["views_evaluated"] = b.optimised.views_evaluated + uint64_t(views);
  out["note"] = b.note;  // why the front view, when no view saw anything
  out["notices"] = py::cast(notices);
  return out;
}

py::array render(const py::object& vertices, const py::object& faces, const py::object& values,
                 const py::object& theta_arg, const py::object& phi_arg, bool best, const std::string& up,
                 const py::object& elevation, const py::object& size, const py::object& color_range, bool grey,
                 bool flat, bool edges, const py::object& supersample, const py::object& scales,
                 const py::object& eps_frac, const std::string& method, const std::string& backend,
                 const std::string& precision, const py::object& device, const py::object& threads,
                 const std::string& model) {
  const meshsal::Mesh mesh = mesh_from_arrays(vertices, faces);
  const double theta = number_arg(theta_arg, "theta"), phi = number_arg(phi_arg, "phi");
  if (!(theta >= -360 && theta <= 360))
    throw py::value_error("theta must be in [-360, 360] degrees, got " + std::string(py::str(theta_arg)));
  if (!(phi >= -90 && phi <= 90)) throw py::value_error("phi must be in [-90, 90] degrees, got " + std::string(py::str(phi_arg)));
  meshsal::RenderStyle style;
  // Beyond an int: ValueError here; within, the library's own range check (meshsal.Error).
  style.size = int(integer_arg(size, "size", INT_MIN, INT_MAX));
  style.smooth = !flat;
  style.edges = edges;
  style.supersample = int(integer_arg(supersample, "supersample", INT_MIN, INT_MAX));
  style.up = meshsal::parse_up_axis(up);
  const meshsal::ElevationRange band = elevation_range(elevation);
  if (!best && !elevation.is_none()) throw py::value_error("elevation needs best=True");
  if (!color_range.is_none()) {
    std::string text;
    if (py::isinstance<py::str>(color_range)) {
      text = color_range.cast<std::string>();
    } else {
      // Each end a value or a percentile such as '5%': the library reads the text.
      for (const py::object& end : pair_items(color_range, "color_range", "'LO,HI' or a pair (lo, hi)")) {
        if (!py::isinstance<py::str>(end)) number_arg(end, "color_range");
        text += (text.empty() ? "" : ",") + std::string(py::str(end));
      }
    }
    style.range = meshsal::parse_color_range(text);
  }
  std::vector<double> given;
  if (!values.is_none()) given = vertex_values(values, mesh.vertex_count(), "values");
  meshsal::SaliencyOptions so =
      saliency_options({scales, eps_frac, method, backend, precision, device, threads, model, up}, nullptr);
  meshsal::Image image;
  {
    const InterruptibleCall call;  // Ctrl-C stops it (interrupt.h)
    so.cancel = call.flag();
    std::vector<double> score;
    if (!grey || best) score = score_or_saliency(mesh, std::move(given), so);
    if (best) {
      // The view of most visible score: the one view pipeline, as `meshsal render --best`.
      meshsal::ViewpointOptions vo;
      vo.up = style.up;
      vo.elevation = band;
      vo.visibility.threads = so.threads;
      use_saliency_device(vo, so);
      vo.optimiser.cancel = so.cancel;
      const meshsal::Viewpoint b = meshsal::best_viewpoint(mesh, score, vo);
      image = meshsal::render_camera_view(mesh, grey ? std::vector<double>{} : score, b.camera, style);
    } else {
      image = meshsal::render_view(mesh, grey ? std::vector<double>{} : score, meshsal::ViewAngles{theta / kDeg, phi / kDeg}, style);
    }
  }
  const py::ssize_t h = image.height, w = image.width;
  return to_numpy(std::move(image.rgb), {h, w, 3});
}

}  // namespace

void bind_view(py::module_& m) {
  m.def("best_view", &best_view, py::arg("vertices"), py::arg("faces"), py::arg("score") = py::none(),
        py::kw_only(), py::arg("restarts") = 8, py::arg("seed") = 1ULL, py::arg("views") = 0,
        py::arg("resolution") = meshsal::kDefaultViewResolution, py::arg("depth_tol") = 2.0, py::arg("up") = "y",
        py::arg("elevation") = py::none(),
        py::arg("scales") = py::none(), py::arg("eps_frac") = 0.003, py::arg("method") = "exact",
        py::arg("backend") = "auto", py::arg("precision") = "auto", py::arg("device") = -1,
        py::arg("threads") = 0u, py::arg("model") = "lee2005",
        (std::string(R"(best_view(vertices, faces, score=None, *, restarts=8, seed=1, views=0, resolution=512,
          depth_tol=2.0, up='y', elevation=None, scales=None, eps_frac=0.003, method='exact', backend='auto',
          precision='auto', device=-1, threads=0, model='lee2005') -> dict

The view direction that sees the most score (`meshsal viewpoint`): U = the sum of score over
the mesh points visible from it. score: one value per vertex (e.g. saliency().saliency, or
abs(curvature) for the paper's baseline); None computes the saliency first. Gradient ascent
from `restarts` seeded random directions; views > 0 also scores that many Fibonacci-sphere
directions exhaustively. elevation=(min, max): the latitudes in degrees (in the frame of
`up`) the search may look from (default: )" + default_band() + R"(, a little above the horizon; (-90, 90):
the whole sphere, the paper's search). The same search as the CLI's
(one library call): the same settings give the same view. Returns the CLI's JSON keys: theta, phi (radians), theta_deg,
phi_deg and direction (unit vector in the mesh's coordinates) in the frame of `up` ('x',
'y', 'z', '-x', '-y', '-z': the axis that points up), visible_score (U, the score summed
over the visible mesh points), visible_fraction (U over the score of all mesh points),
score_source, device, resolution, depth_tol_px, elevation, restarts, seed, exhaustive
(a dict of the same view keys plus 'views', or None), views_evaluated, notices, note ('', or why
the front view was returned: no direction saw any score).
The GIL is released while it computes.
)") + kSaliencyArgsDoc).c_str());
  m.def("render", &render, py::arg("vertices"), py::arg("faces"), py::arg("values") = py::none(),
        py::kw_only(), py::arg("theta") = 0.0, py::arg("phi") = 0.0, py::arg("best").noconvert() = false,
        py::arg("up") = "y", py::arg("elevation") = py::none(), py::arg("size") = 512, py::arg("color_range") = py::none(),
        py::arg("grey").noconvert() = false, py::arg("flat").noconvert() = false, py::arg("edges").noconvert() = false,
        py::arg("supersample") = 2, py::arg("scales") = py::none(), py::arg("eps_frac") = 0.003,
        py::arg("method") = "exact", py::arg("backend") = "auto", py::arg("precision") = "auto",
        py::arg("device") = -1, py::arg("threads") = 0u, py::arg("model") = "lee2005",
        (std::string(R"(render(vertices, faces, values=None, *, theta=0, phi=0, best=False, up='y', elevation=None, size=512,
       color_range=None, grey=False, flat=False, edges=False, supersample=2, scales=None,
       eps_frac=0.003, method='exact', backend='auto', precision='auto', device=-1,
       threads=0, model='lee2005') -> numpy.ndarray uint8 (size, size, 3)

A picture of the mesh (`meshsal render`, without its title line and colour bar): seen from
theta, phi (degrees; theta 0 looks from the front, 90 from the right, phi 90 from above, in
the frame of `up`) or from the best view (best=True, as `meshsal render --best`; elevation=(min, max) limits its
latitudes as best_view's does), orthographic
and Lambert-shaded, coloured by `values` (one per vertex; None computes the saliency;
grey=True: plain grey) on the Turbo scale between color_range's ends: 'LO,HI' or (lo, hi),
each a value or a percentile such as '5%' (default: minimum to maximum). flat: flat faces;
edges: darken triangle edges; supersample: 1..4. Rows run top to bottom, RGB.
The GIL is released while it computes.
)") + kSaliencyArgsDoc).c_str());
}

}  // namespace meshsal_py
