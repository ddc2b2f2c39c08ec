// meshsal Python module: simplify() and its result object.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "arg_values.h"
#include "bindings.h"
#include "meshsal/meshsal.h"
#include "numpy_in.h"
#include "numpy_out.h"
#include "request_call.h"
#include "saliency_args.h"
#include "interrupt.h"
#include "mesh_args.h"

namespace meshsal_py {

namespace {

// The bounding-box diagonal of the mesh points.
double mesh_diagonal(const meshsal::Mesh& mesh) {
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (uint32_t v : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], double(mesh.positions[3 * size_t(v) + k]));
      hi[k] = std::max(hi[k], double(mesh.positions[3 * size_t(v) + k]));
    }
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                   (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

// What simplify() returns: the mesh and the report `meshsal simplify --json` prints.
struct SimplifyOut {
  py::object vertices, faces, vertex_origin, notices, attributes, position_vertex;
  size_t input_faces = 0, target_faces = 0, output_faces = 0, collapses = 0;
  bool reached = false, unchanged = false;
  std::string note, weights;
  std::string device = "cpu";  // what computed S; the CLI's JSON `device`
  double alpha = 0, seconds = 0, error = 0, error_percent = 0, lambda = 0, alpha_percentile = 0,
         weight_floor = 0;
};

// A number argument that may be None: the value, or `fallback` for None.
double number_or(const py::object& value, double fallback, const char* name) {
  return value.is_none() ? fallback : number_arg(value, name);
}

// A SimplifyOut from one simplified mesh and its report (simplify() and each lod level).
void fill_result(SimplifyOut& out, meshsal::Mesh result, meshsal::SimplifyReport report, std::vector<std::string> notices,
                 double diagonal, const std::string& mode, const meshsal::SaliencyWeightOptions& wo, bool computed,
                 bool float32_in) {
  const py::ssize_t nf = py::ssize_t(result.triangle_count());
  out.vertices = model_vertices(result, false, !float32_in);  // float64 in, float64 out
  out.faces = to_numpy(std::move(result.triangles), {nf, 3});
  out.vertex_origin = to_numpy(std::move(report.vertex_origin));
  out.attributes = attributes_dict(std::move(result.attributes));
  out.position_vertex = position_vertex_array(std::move(result.position_vertex));
  if (!report.warning.empty()) notices.push_back("warning: " + report.warning);
  out.notices = py::cast(notices);
  out.input_faces = report.input_faces;
  out.target_faces = report.target_faces;
  out.output_faces = report.output_faces;
  out.collapses = report.collapses;
  out.reached = report.reached;
  out.unchanged = report.unchanged;
  out.note = report.note;
  out.weights = out.unchanged ? meshsal::weighting_name(meshsal::Weighting::None) : mode;
  out.seconds = report.seconds;
  out.error = report.error * diagonal;
  out.error_percent = 100 * report.error;
  if (computed && !out.unchanged) {
    out.lambda = wo.lambda;
    out.alpha_percentile = wo.alpha_percentile;
    out.weight_floor = wo.floor;
  }
}

}  // namespace

namespace {

SimplifyOut simplify(const py::object& vertices, const py::object& faces, const py::object& target_faces,
                     const py::object& ratio, const py::object& target_error, bool lock_border,
                     const py::object& weights, const py::object& saliency, const py::object& lambda_arg,
                     const py::object& alpha_arg, const py::object& floor_arg, const py::object& attributes,
                     const py::object& position_vertex, const py::object& scales, const py::object& eps_frac,
                     const std::string& method, const std::string& backend, const std::string& precision,
                     const py::object& device, const py::object& threads, const std::string& model,
                     const std::string& up, std::vector<SimplifyOut>* lod_out,
                     const std::vector<meshsal::SimplifyOptions>* lod) {
  meshsal::Mesh mesh = mesh_with_attributes(vertices, faces, attributes, position_vertex);
  const size_t n = mesh.vertex_count();
  // The CLI's rule: one of target_faces and ratio, or target_error alone.
  const double error_percent = number_or(target_error, 0, "target_error");
  if (!(error_percent >= 0 && error_percent <= 100))
    throw py::value_error("target_error must be in [0, 100] (% of the bounding-box diagonal), got " +
                          std::string(py::str(target_error)));
  meshsal::SimplifyOptions options;
  options.target_error = error_percent / 100;
  options.lock_border = lock_border;
  // Both as given: the library's rules (check_request) say which combine.
  if (!target_faces.is_none()) options.target_faces = size_t(integer_arg(target_faces, "target_faces", 1, 4000000000LL));
  if (!ratio.is_none()) {
    const double r = number_or(ratio, 0, "ratio");
    if (!(r > 0 && r <= 1)) throw py::value_error("ratio must be in (0, 1], got " + std::string(py::str(ratio)));
    options.ratio = r;
  }
  // The weighting, read once here: a name (the library's presets, as --weights), or W per
  // vertex from an array (`named` empty).
  std::optional<meshsal::Weighting> named;
  if (weights.is_none()) {
    named = meshsal::kDefaultWeighting;
  } else if (py::isinstance<py::str>(weights)) {
    const std::string name = weights.cast<std::string>();
    try {
      named = meshsal::parse_weighting(name);
    } catch (const meshsal::Error&) {
      throw py::value_error("weights must be 'saliency', 'balanced', 'none' or an array of one weight per vertex, got '" +
                            name + "'");
    }
  }
  const bool array = !named;
  const bool computed = named && *named != meshsal::Weighting::None;
  const std::string mode = named ? meshsal::weighting_name(*named) : "array";  // the result's `weights`
  // W's parameters: the preset's unless given (the CLI's --lambda, --alpha-percentile).
  meshsal::SaliencyWeightOptions wo = weight_preset(computed ? *named : meshsal::kDefaultWeighting);
  wo.lambda = number_or(lambda_arg, wo.lambda, "lambda_");
  wo.alpha_percentile = number_or(alpha_arg, wo.alpha_percentile, "alpha_percentile");
  wo.floor = number_or(floor_arg, wo.floor, "weight_floor");
  if (!(wo.lambda >= 0 && wo.lambda <= 1e6)) throw py::value_error("lambda_ must be in [0, 1e6]");
  if (!(wo.alpha_percentile >= 0 && wo.alpha_percentile <= 100)) throw py::value_error("alpha_percentile must be in [0, 100]");
  if (!(wo.floor >= 0 && wo.floor <= 100)) throw py::value_error("weight_floor must be in [0, 100]");
  if (!computed && !saliency.is_none())
    throw py::value_error("saliency (S per vertex) needs weights='saliency' or 'balanced'");
  if (lod && array) throw py::value_error("lod takes weights 'saliency', 'balanced' or 'none', not an array");

  std::vector<double> w, s;
  if (array) w = vertex_values(weights, n, "weights");
  if (!saliency.is_none()) s = vertex_values(saliency, n, "saliency");
  std::vector<std::string> notices;
  meshsal::SaliencyOptions so =
      saliency_options({scales, eps_frac, method, backend, precision, device, threads, model, up}, &notices);
  options.threads = so.threads;

  SimplifyOut out;
  const double diagonal = mesh_diagonal(mesh);  // for the error in model units, as the CLI's JSON
  // The library's one pipeline (run_request), as `meshsal simplify` runs it: the rules of
  // what combines are its (check_request), their messages in this module's spelling.
  meshsal::Request req;
  req.mesh = &mesh;
  req.attributed = &mesh;
  req.simplify_in_memory = true;
  req.simplify = options;
  if (lod) req.lod = *lod;
  req.weighting = named.value_or(meshsal::Weighting::None);
  req.weight_options = wo;
  if (array) req.vertex_weights = &w;
  if (!s.empty()) req.saliency_values = &s;
  req.saliency = so;
  meshsal::RequestResult r;
  {
    const InterruptibleCall call;  // Ctrl-C stops it (interrupt.h)
    req.simplify.cancel = req.saliency.cancel = call.flag();
    r = run_in_python_terms(req);
  }
  if (lod) {
    for (meshsal::LodLevel& level : r.lod) {
      SimplifyOut o;
      if (computed) meshsal::set_vertex_attribute(level.mesh, "quality", level.saliency);
      fill_result(o, std::move(level.mesh), std::move(level.report), notices, diagonal, mode, wo, computed,
                  float32_vertices(vertices));
      lod_out->push_back(std::move(o));
    }
    return out;
  }
  out.alpha = r.alpha;
  if (!r.weights_device.empty()) out.device = r.weights_device;
  fill_result(out, std::move(r.simplified), std::move(r.simplify), notices, diagonal, mode, wo, computed,
              float32_vertices(vertices));
  return out;
}

py::object simplify_any(const py::object& vertices, const py::object& faces, const py::object& target_faces,
                        const py::object& ratio, const py::object& target_error, bool lock_border,
                        const py::object& weights, const py::object& saliency, const py::object& lambda_arg,
                        const py::object& alpha_arg, const py::object& floor_arg, const py::object& attributes,
                        const py::object& position_vertex, const py::object& scales, const py::object& eps_frac,
                        const std::string& method, const std::string& backend, const std::string& precision,
                        const py::object& device, const py::object& threads, const py::object& lod,
                        const std::string& model, const std::string& up) {
  if (lod.is_none())
    return py::cast(simplify(vertices, faces, target_faces, ratio, target_error, lock_border, weights, saliency,
                             lambda_arg, alpha_arg, floor_arg, attributes, position_vertex, scales, eps_frac, method,
                             backend, precision, device, threads, model, up, nullptr, nullptr));
  std::vector<meshsal::SimplifyOptions> levels;
  try {
    levels = lod_levels(lod);
  } catch (const meshsal::Error& e) {
    throw py::value_error(e.what());
  }
  std::vector<SimplifyOut> out;
  simplify(vertices, faces, target_faces, ratio, target_error, lock_border, weights, saliency, lambda_arg, alpha_arg,
           floor_arg, attributes, position_vertex, scales, eps_frac, method, backend, precision, device, threads, model,
           up, &out, &levels);
  return py::cast(std::move(out));
}

}  // namespace

void bind_simplify(py::module_& m) {
  py::class_<SimplifyOut>(m, "SimplifyResult", "The result of simplify(): the mesh and its report.")
      .def_readonly("vertices", &SimplifyOut::vertices, "(k, 3): surviving vertices, in input order; float64 for float64 input (or where float32 "
                    "would move a vertex by over 1e-7 of the diagonal), else float32")
      .def_readonly("faces", &SimplifyOut::faces, "uint32 (f, 3)")
      .def_readonly("vertex_origin", &SimplifyOut::vertex_origin,
                    "uint32 (k,): the input vertex each output vertex survived as")
      .def_readonly("attributes", &SimplifyOut::attributes,
                    "dict name -> float32 (k,): the attributes given, carried along the collapses (as the "
                    "CLI carries OBJ vt/vn and PLY properties), and with computed weights 'quality' = the "
                    "saliency S, as the CLI's PLY output has it")
      .def_readonly("position_vertex", &SimplifyOut::position_vertex,
                    "uint32 (k,) or None: the seam map of the result (see position_vertex=)")
      .def_readonly("input_faces", &SimplifyOut::input_faces, "non-degenerate input triangles")
      .def_readonly("target_faces", &SimplifyOut::target_faces, "the target actually used")
      .def_readonly("output_faces", &SimplifyOut::output_faces, "faces of the result")
      .def_readonly("collapses", &SimplifyOut::collapses, "edge collapses done")
      .def_readonly("reached", &SimplifyOut::reached, "output_faces == target_faces")
      .def_readonly("unchanged", &SimplifyOut::unchanged, "the target was at or above the face count")
      .def_readonly("note", &SimplifyOut::note, "why the target was not reached ('' when it was)")
      .def_readonly("weights", &SimplifyOut::weights, "'saliency', 'balanced', 'none' or 'array'")
      .def_readonly("alpha", &SimplifyOut::alpha, "the alpha_percentile of Sm (computed weights)")
      .def_readonly("lambda_", &SimplifyOut::lambda, "the lambda used (computed weights; else 0)")
      .def_readonly("alpha_percentile", &SimplifyOut::alpha_percentile,
                    "the alpha_percentile used (computed weights; else 0)")
      .def_readonly("weight_floor", &SimplifyOut::weight_floor, "the weight floor used (computed weights; else 0)")
      .def_readonly("seconds", &SimplifyOut::seconds, "wall time of the simplification itself")
      .def_readonly("error", &SimplifyOut::error,
                    "the largest collapse's error in model units (RMS distance to its merged planes, unweighted)")
      .def_readonly("error_percent", &SimplifyOut::error_percent,
                    "the same in % of the bounding-box diagonal (the CLI's error_percent)")
      .def_readonly("device", &SimplifyOut::device,
                    "the device that computed the saliency ('cpu (N threads)' or the Vulkan device's "
                    "name); 'cpu' when no saliency was computed (weights 'none' or an array, or "
                    "saliency given)")
      .def_readonly("notices", &SimplifyOut::notices, "list of str: the library's notices")
      .def("__iter__", [](const SimplifyOut& r) { return py::iter(py::make_tuple(r.vertices, r.faces)); })
      .def("__repr__", [](const SimplifyOut& r) {
        return "<meshsal.SimplifyResult: " + std::to_string(py::len(r.vertices)) + " vertices, " +
               std::to_string(r.output_faces) + " faces (target " + std::to_string(r.target_faces) + ")>";
      });
  const std::string default_weights = meshsal::weighting_name(meshsal::kDefaultWeighting);
  m.def("simplify", &simplify_any, py::arg("vertices"), py::arg("faces"), py::arg("target_faces") = py::none(),
        py::kw_only(), py::arg("ratio") = py::none(), py::arg("target_error") = py::none(),
        py::arg("lock_border").noconvert() = false, py::arg("weights") = default_weights,
        py::arg("saliency") = py::none(), py::arg("lambda_") = py::none(), py::arg("alpha_percentile") = py::none(),
        py::arg("weight_floor") = meshsal::kDefaultWeightFloor, py::arg("attributes") = py::none(),
        py::arg("position_vertex") = py::none(), py::arg("scales") = py::none(), py::arg("eps_frac") = 0.003,
        py::arg("method") = "exact", py::arg("backend") = "auto", py::arg("precision") = "auto",
        py::arg("device") = -1, py::arg("threads") = 0u, py::arg("lod") = py::none(),
        py::arg("model") = "lee2005", py::arg("up") = "y",
        ("simplify(vertices, faces, target_faces=None, *, ratio=None, target_error=None, lock_border=False,\n"
         "         weights='" + default_weights + R"(', saliency=None, lambda_=None, alpha_percentile=None,
         weight_floor=0.001, attributes=None, position_vertex=None, scales=None, eps_frac=0.003,
         method='exact', backend='auto', precision='auto', device=-1, threads=0, lod=None,
         model='lee2005', up='y')
    -> SimplifyResult, or with lod a list of them

Garland-Heckbert edge collapses (`meshsal simplify`, the same library calls, so the same
mesh): to target_faces, or to ratio times the faces (give at most one), and/or until
every further collapse would move the surface by more than target_error.

  target_faces      faces to keep (an integer in [1, 4000000000])
  ratio             fraction of the faces to keep, in (0, 1]
  target_error      error bound in % of the bounding-box diagonal, in [0, 100] (--target-error):
                    stop where every further collapse would move the surface more than
                    that (RMS distance to its merged planes); alone, or with a target
                    (whichever comes first). .error / .error_percent give the error reached
  lock_border       keep the vertices of open borders exactly in place (--lock-border)
  weights           'saliency' (the paper's recipe), 'balanced' (its curve with alpha at the
                    50th percentile and lambda 3), 'none' (plain quadric error), or an
                    array of one weight W >= 0 per vertex. Computed weights multiply each
                    vertex quadric by W = lambda_ * Sm where the smoothed saliency Sm
                    reaches its alpha_percentile, else Sm (Lee et al. 2005, section 4)
  saliency          S per vertex (e.g. a previous saliency().saliency, or the 'quality' of
                    a saliency PLY) instead of computing it (--saliency-from)
  lambda_           amplification of the salient vertices, [0, 1e6]; None: the preset's
                    (100 for 'saliency', 3 for 'balanced')
  alpha_percentile  percentile of Sm above which vertices are amplified, [0, 100]; None:
                    the preset's (30 for 'saliency', 50 for 'balanced')
  weight_floor      raise W to at least this fraction of the mean W, so that no collapse is
                    free (0: the paper's literal rule, which erases flat regions), [0, 100]
  lod               levels of detail in one call (`meshsal simplify --lod`): a list of ratios
                    of the input's faces (floats in (0, 1)) and face counts (ints), each below
                    the one before, or a str such as '0.5,0.2,0.05'; returns one SimplifyResult
                    per level. The saliency is computed once and carried down the chain; each
                    level is simplified from the one before (meshsal.simplify_lod)

A target at or above the face count returns the mesh unchanged (.unchanged, .note). The
result unpacks as V, F = simplify(...); .vertex_origin maps output to input vertices;
.attributes carries the attributes given (interpolated along each collapsed edge; UV seams
stay closed with position_vertex) plus 'quality' = S with computed weights, so that
save(path, r.vertices, r.faces, attributes=r.attributes, position_vertex=r.position_vertex)
writes the CLI's output file. Arrays as in saliency(); the GIL is released while it
computes, and Ctrl-C stops it (KeyboardInterrupt).
)" + kAttributesDoc + "\n" + kSaliencyArgsDoc).c_str());
}

}  // namespace meshsal_py
