// meshsal Python module: simplify() and its result object.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "bindings.h"
#include "meshsal/meshsal.h"
#include "numpy_in.h"
#include "numpy_out.h"
#include "saliency_args.h"
#include "interrupt.h"

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
  py::object vertices, faces, vertex_origin, notices;
  size_t input_faces = 0, target_faces = 0, output_faces = 0, collapses = 0;
  bool reached = false, unchanged = false;
  std::string note, weights;
  std::string device = "cpu";  // what computed S; the CLI's JSON `device`
  double alpha = 0, seconds = 0, error = 0;
};

SimplifyOut simplify(const py::object& vertices, const py::object& faces, const py::object& target_faces,
                     const py::object& ratio, const py::object& weights, const py::object& saliency,
                     double lambda, double alpha_percentile, double weight_floor, const py::object& scales,
                     double eps_frac, const std::string& method, const std::string& backend,
                     const std::string& precision, int device, unsigned threads) {
  meshsal::Mesh mesh = mesh_from_arrays(vertices, faces);
  const size_t n = mesh.vertex_count();
  if (target_faces.is_none() == ratio.is_none())
    throw py::value_error("give exactly one of target_faces and ratio");
  meshsal::SimplifyOptions options;
  options.threads = threads;
  if (!target_faces.is_none()) {
    // Any integer (numpy's too), as Python's operator.index takes it.
    PyObject* index = PyNumber_Index(target_faces.ptr());
    if (!index) {
      PyErr_Clear();
      throw py::type_error("target_faces must be an integer, got " +
                           std::string(py::str(target_faces.get_type().attr("__name__"))));
    }
    int overflow = 0;
    const long long t = PyLong_AsLongLongAndOverflow(index, &overflow);  // 2**70 is no C++ integer
    const std::string given = py::str(py::reinterpret_steal<py::object>(index));
    if (overflow || t < 1 || t > 4000000000LL)
      throw py::value_error("target_faces must be in [1, 4000000000], got " + given);
    options.target_faces = size_t(t);
  } else {
    if (!py::isinstance<py::float_>(ratio) && !py::isinstance<py::int_>(ratio) &&
        !PyNumber_Check(ratio.ptr()))
      throw py::type_error("ratio must be a number");
    const double r = py::float_(ratio).cast<double>();
    if (!(r > 0 && r <= 1)) throw py::value_error("ratio must be in (0, 1], got " + std::string(py::str(ratio)));
    options.ratio = r;
  }
  // What the CLI checks: W's parameters, and weights given one way only.
  if (!(lambda >= 0 && lambda <= 1e6)) throw py::value_error("lambda_ must be in [0, 1e6]");
  if (!(alpha_percentile >= 0 && alpha_percentile <= 100)) throw py::value_error("alpha_percentile must be in [0, 100]");
  if (!(weight_floor >= 0 && weight_floor <= 100)) throw py::value_error("weight_floor must be in [0, 100]");
  std::string mode = "array";
  if (py::isinstance<py::str>(weights)) {
    mode = weights.cast<std::string>();
    if (mode != "saliency" && mode != "none")
      throw py::value_error("weights must be 'saliency', 'none' or an array of one weight per vertex, got '" + mode + "'");
  }
  if (mode != "saliency" && !saliency.is_none())
    throw py::value_error("saliency (S per vertex) needs weights='saliency'");

  std::vector<double> w, s;
  if (mode == "array") w = vertex_values(weights, n, "weights");
  if (!saliency.is_none()) s = vertex_values(saliency, n, "saliency");
  std::vector<std::string> notices;
  meshsal::SaliencyOptions so =
      saliency_options({scales, eps_frac, method, backend, precision, device, threads}, &notices);

  SimplifyOut out;
  const double diagonal = mesh_diagonal(mesh);  // for the error in model units, as the CLI's JSON
  meshsal::Mesh result;
  meshsal::SimplifyReport report;
  {
    const InterruptibleCall call;  // Ctrl-C stops it (interrupt.h)
    options.cancel = so.cancel = call.flag();
    // A target at or above the face count keeps the mesh as it is (the library's rule),
    // with no saliency computed for it.
    if (mode == "saliency" && !meshsal::simplify_keeps_mesh(options, mesh.triangle_count())) {
      meshsal::SaliencyWeightOptions wo;
      wo.lambda = lambda;
      wo.alpha_percentile = alpha_percentile;
      wo.floor = weight_floor;
      w = meshsal::simplification_weights(mesh, wo, so, s.empty() ? nullptr : &s, &out.alpha, nullptr,
                                          &out.device);
    }
    result = meshsal::simplify_mesh(mesh, options, w.empty() ? nullptr : &w, &report);
  }
  const py::ssize_t nv = py::ssize_t(result.vertex_count()), nf = py::ssize_t(result.triangle_count());
  out.vertices = model_vertices(result);
  out.faces = to_numpy(std::move(result.triangles), {nf, 3});
  out.vertex_origin = to_numpy(std::move(report.vertex_origin));
  if (!report.warning.empty()) notices.push_back("warning: " + report.warning);
  out.notices = py::cast(notices);
  out.input_faces = report.input_faces;
  out.target_faces = report.target_faces;
  out.output_faces = report.output_faces;
  out.collapses = report.collapses;
  out.reached = report.reached;
  out.unchanged = report.unchanged;
  out.note = report.note;
  out.weights = out.unchanged ? "none" : mode;
  out.seconds = report.seconds;
  out.error = report.error * diagonal;
  return out;
}

}  // namespace

void bind_simplify(py::module_& m) {
  py::class_<SimplifyOut>(m, "SimplifyResult", "The result of simplify(): the mesh and its report.")
      .def_readonly("vertices", &SimplifyOut::vertices, "(k, 3): surviving vertices, in input order; float64 for float64 input (or where float32 "
                    "would move a vertex by over 1e-7 of the diagonal), else float32")
      .def_readonly("faces", &SimplifyOut::faces, "uint32 (f, 3)")
      .def_readonly("vertex_origin", &SimplifyOut::vertex_origin,
                    "uint32 (k,): the input vertex each output vertex survived as")
      .def_readonly("input_faces", &SimplifyOut::input_faces, "non-degenerate input triangles")
      .def_readonly("target_faces", &SimplifyOut::target_faces, "the target actually used")
      .def_readonly("output_faces", &SimplifyOut::output_faces, "faces of the result")
      .def_readonly("collapses", &SimplifyOut::collapses, "edge collapses done")
      .def_readonly("reached", &SimplifyOut::reached, "output_faces == target_faces")
      .def_readonly("unchanged", &SimplifyOut::unchanged, "the target was at or above the face count")
      .def_readonly("note", &SimplifyOut::note, "why the target was not reached ('' when it was)")
      .def_readonly("weights", &SimplifyOut::weights, "'saliency', 'none' or 'array'")
      .def_readonly("alpha", &SimplifyOut::alpha, "the alpha_percentile of Sm (weights='saliency')")
      .def_readonly("seconds", &SimplifyOut::seconds, "wall time of the simplification itself")
      .def_readonly("error", &SimplifyOut::error,
                    "the largest collapse's error in model units (RMS distance to its merged planes, unweighted)")
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
  m.def("simplify", &simplify, py::arg("vertices"), py::arg("faces"), py::arg("target_faces") = py::none(),
        py::kw_only(), py::arg("ratio") = py::none(), py::arg("weights") = "saliency",
        py::arg("saliency") = py::none(), py::arg("lambda_") = 100.0, py::arg("alpha_percentile") = 30.0,
        py::arg("weight_floor") = meshsal::kDefaultWeightFloor, py::arg("scales") = py::none(), py::arg("eps_frac") = 0.003,
        py::arg("method") = "exact", py::arg("backend") = "auto", py::arg("precision") = "auto",
        py::arg("device") = -1, py::arg("threads") = 0u,
        (std::string(R"(simplify(vertices, faces, target_faces=None, *, ratio=None, weights='saliency', saliency=None,
         lambda_=100, alpha_percentile=30, weight_floor=0.001, scales=None, eps_frac=0.003,
         method='exact', backend='auto', precision='auto', device=-1, threads=0) -> SimplifyResult

Garland-Heckbert edge collapses to target_faces, or to ratio times the faces
(`meshsal simplify`; give exactly one). weights='saliency' (default) multiplies each vertex
quadric by W = lambda_ * Sm where the smoothed saliency Sm reaches its alpha_percentile,
else Sm (Lee et al. 2005, section 4), raised to at least weight_floor times the mean W so
that no collapse is free (0: the paper's literal rule, which erases flat regions); saliency=S (one value per vertex, e.g. a previous
saliency().saliency) reuses S instead of computing it, as --saliency-from does.
weights='none' is plain quadric error; an array gives W per vertex directly. A target at
or above the face count returns the mesh unchanged (.unchanged, .note).
The result unpacks as V, F = simplify(...); .vertex_origin maps output to input vertices;
.error is the largest collapse's error (unweighted quadric distance) in model units.
Arrays as in saliency(); the GIL is released while it computes, and Ctrl-C stops it
(KeyboardInterrupt).
)") + kSaliencyArgsDoc).c_str());
}

}  // namespace meshsal_py
