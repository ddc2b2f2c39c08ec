// meshsal Python module: best_view() and render().
#include <cmath>
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "bindings.h"
#include "choices.h"
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
// direction in the mesh's coordinates and U (visible_score).
py::dict view_dict(const meshsal::ViewAngles& y_up, meshsal::UpAxis up, double U) {
  double d[3];
  const meshsal::ViewAngles a = angles_for_up(y_up, up, d);
  py::dict v;
  v["theta"] = a.theta;
  v["phi"] = a.phi;
  v["theta_deg"] = a.theta * kDeg;
  v["phi_deg"] = a.phi * kDeg;
  v["direction"] = py::make_tuple(d[0], d[1], d[2]);
  v["visible_score"] = U;
  return v;
}

py::dict best_view(const py::object& vertices, const py::object& faces, const py::object& score, int restarts,
                   unsigned long long seed, int views, int resolution, double depth_tol, const std::string& up,
                   const py::object& scales, double eps_frac, const std::string& method, const std::string& backend,
                   const std::string& precision, int device, unsigned threads) {
  const meshsal::Mesh mesh = mesh_from_arrays(vertices, faces);
  const meshsal::UpAxis up_axis = parse_up(up);
  // The CLI's ranges (the library checks resolution and depth_tol itself).
  if (restarts < 1 || restarts > 1000) throw py::value_error("restarts must be in [1, 1000], got " + std::to_string(restarts));
  if (views < 0 || views > 1000000) throw py::value_error("views must be in [0, 1000000], got " + std::to_string(views));
  if (resolution < 16 || resolution > 8192)
    throw py::value_error("resolution must be in [16, 8192], got " + std::to_string(resolution));
  if (!(depth_tol >= 0 && depth_tol <= 1000)) throw py::value_error("depth_tol must be in [0, 1000]");
  std::vector<double> given;
  if (!score.is_none()) given = vertex_values(score, mesh.vertex_count(), "score");
  const bool computed = given.empty();
  std::vector<std::string> notices;
  meshsal::SaliencyOptions so =
      saliency_options({scales, eps_frac, method, backend, precision, device, threads}, &notices);
  meshsal::OptimiserOptions oo;
  oo.restarts = restarts;
  oo.seed = seed;
  meshsal::VisibilityOptions vo;
  vo.resolution = resolution;
  vo.depth_tol_px = depth_tol;
  vo.threads = threads;
  meshsal::BestView b;
  std::vector<double> s;
  {
    const InterruptibleCall call;  // Ctrl-C stops it (interrupt.h)
    so.cancel = oo.cancel = call.flag();
    s = score_or_saliency(mesh, std::move(given), so);
    b = meshsal::best_viewpoint(mesh, s, oo, views, vo, so.backend, device);
  }
  // visible_fraction: U over the score of every mesh point, in the visibility's float weights.
  std::vector<uint8_t> used(mesh.vertex_count(), 0);
  for (uint32_t v : mesh.triangles) used[v] = 1;
  double total = 0;
  for (size_t v = 0; v < s.size(); ++v)
    if (used[v]) total += double(float(s[v]));
  py::dict out = view_dict(b.optimised.best, up_axis, b.optimised.U);
  out["visible_fraction"] = total > 0 ? b.optimised.U / total : 0.0;
  out["score_source"] = computed ? "computed (" + b.backend_name + ")" : std::string("given");
  out["device"] = b.backend_name;
  out["resolution"] = resolution;
  out["depth_tol_px"] = depth_tol;
  out["restarts"] = restarts;
  out["seed"] = seed;
  if (views > 0) {
    py::dict ex = view_dict(b.map.views[b.map.best], up_axis, b.map.U[b.map.best]);
    ex["views"] = views;
    out["exhaustive"] = ex;
  } else {
    out["exhaustive"] = py::none();
  }
  out["views_evaluated"] = b.optimised.views_evaluated + uint64_t(views);
  out["note"] = b.optimised.note;  // why the front view, when no view saw anything
  out["notices"] = py::cast(notices);
  return out;
}

py::array render(const py::object& vertices, const py::object& faces, const py::object& values, double theta,
                 double phi, bool best, const std::string& up, int size, const py::object& color_range,
                 bool grey, bool flat, bool edges, int supersample, const py::object& scales, double eps_frac,
                 const std::string& method, const std::string& backend, const std::string& precision,
                 int device, unsigned threads) {
  const meshsal::Mesh mesh = mesh_from_arrays(vertices, faces);
  if (!(theta >= -360 && theta <= 360)) throw py::value_error("theta must be in [-360, 360] degrees");
  if (!(phi >= -90 && phi <= 90)) throw py::value_error("phi must be in [-90, 90] degrees");
  meshsal::RenderStyle style;
  style.size = size;
  style.smooth = !flat;
  style.edges = edges;
  style.supersample = supersample;
  style.up = parse_up(up);
  if (!color_range.is_none()) {
    std::string text;
    if (py::isinstance<py::str>(color_range)) {
      text = color_range.cast<std::string>();
    } else {
      py::tuple t = py::tuple(color_range);
      if (t.size() != 2) throw py::value_error("color_range must be 'LO,HI' or a pair (lo, hi)");
      text = std::string(py::str(t[0])) + "," + std::string(py::str(t[1]));
    }
    style.range = meshsal::parse_color_range(text);
  }
  std::vector<double> given;
  if (!values.is_none()) given = vertex_values(values, mesh.vertex_count(), "values");
  meshsal::SaliencyOptions so =
      saliency_options({scales, eps_frac, method, backend, precision, device, threads}, nullptr);
  meshsal::Image image;
  {
    const InterruptibleCall call;  // Ctrl-C stops it (interrupt.h)
    so.cancel = call.flag();
    std::vector<double> score;
    if (!grey || best) score = score_or_saliency(mesh, std::move(given), so);
    meshsal::ViewAngles view{theta / kDeg, phi / kDeg};
    if (best) {
      // The view of most visible score, found as `meshsal render --best` finds it.
      meshsal::VisibilityOptions vo;
      vo.threads = threads;
      meshsal::OptimiserOptions oo;
      oo.cancel = so.cancel;
      const meshsal::BestView b = meshsal::best_viewpoint(mesh, score, oo, 0, vo, so.backend, device);
      double d[3];
      view = angles_for_up(b.optimised.best, style.up, d);
    }
    image = meshsal::render_view(mesh, grey ? nullptr : &score, view, style);
  }
  const py::ssize_t h = image.height, w = image.width;
  return to_numpy(std::move(image.rgb), {h, w, 3});
}

}  // namespace

void bind_view(py::module_& m) {
  m.def("best_view", &best_view, py::arg("vertices"), py::arg("faces"), py::arg("score") = py::none(),
        py::kw_only(), py::arg("restarts") = 8, py::arg("seed") = 1ULL, py::arg("views") = 0,
        py::arg("resolution") = 512, py::arg("depth_tol") = 2.0, py::arg("up") = "y",
        py::arg("scales") = py::none(), py::arg("eps_frac") = 0.003, py::arg("method") = "exact",
        py::arg("backend") = "auto", py::arg("precision") = "auto", py::arg("device") = -1,
        py::arg("threads") = 0u,
        (std::string(R"(best_view(vertices, faces, score=None, *, restarts=8, seed=1, views=0, resolution=512,
          depth_tol=2.0, up='y', scales=None, eps_frac=0.003, method='exact', backend='auto',
          precision='auto', device=-1, threads=0) -> dict

The view direction that sees the most score (`meshsal viewpoint`): U = the sum of score over
the mesh points visible from it. score: one value per vertex (e.g. saliency().saliency, or
abs(curvature) for the paper's baseline); None computes the saliency first. Gradient ascent
from `restarts` seeded random directions; views > 0 also scores that many Fibonacci-sphere
directions exhaustively. Returns the CLI's JSON keys: theta, phi (radians), theta_deg,
phi_deg and direction (unit vector in the mesh's coordinates) in the frame of `up` ('x',
'y', 'z', '-x', '-y', '-z': the axis that points up), visible_score (U, the score summed
over the visible mesh points), visible_fraction (U over the score of all mesh points),
score_source, device, resolution, depth_tol_px, restarts, seed, exhaustive
(a dict of the same view keys plus 'views', or None), views_evaluated, notices, note ('', or why
the front view was returned: no direction saw any score).
The GIL is released while it computes.
)") + kSaliencyArgsDoc).c_str());
  m.def("render", &render, py::arg("vertices"), py::arg("faces"), py::arg("values") = py::none(),
        py::kw_only(), py::arg("theta") = 0.0, py::arg("phi") = 0.0, py::arg("best") = false,
        py::arg("up") = "y", py::arg("size") = 512, py::arg("color_range") = py::none(),
        py::arg("grey") = false, py::arg("flat") = false, py::arg("edges") = false,
        py::arg("supersample") = 2, py::arg("scales") = py::none(), py::arg("eps_frac") = 0.003,
        py::arg("method") = "exact", py::arg("backend") = "auto", py::arg("precision") = "auto",
        py::arg("device") = -1, py::arg("threads") = 0u,
        (std::string(R"(render(vertices, faces, values=None, *, theta=0, phi=0, best=False, up='y', size=512,
       color_range=None, grey=False, flat=False, edges=False, supersample=2, scales=None,
       eps_frac=0.003, method='exact', backend='auto', precision='auto', device=-1,
       threads=0) -> numpy.ndarray uint8 (size, size, 3)

A picture of the mesh (`meshsal render`, without its title line and colour bar): seen from
theta, phi (degrees; theta 0 looks from the front, 90 from the right, phi 90 from above, in
the frame of `up`) or from the best view (best=True, as `meshsal render --best`), orthographic
and Lambert-shaded, coloured by `values` (one per vertex; None computes the saliency;
grey=True: plain grey) on the Turbo scale between color_range's ends: 'LO,HI' or (lo, hi),
each a value or a percentile such as '5%' (default: minimum to maximum). flat: flat faces;
edges: darken triangle edges; supersample: 1..4. Rows run top to bottom, RGB.
The GIL is released while it computes.
)") + kSaliencyArgsDoc).c_str());
}

}  // namespace meshsal_py
