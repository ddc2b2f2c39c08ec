// meshsal Python module: saliency() and its result object.
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

// What saliency() returns: numpy arrays (owned, no copy of the library's vectors) and the
// run's facts, as `meshsal saliency --json` reports them.
struct SaliencyOut {
  py::object saliency, curvature, smoothed, raw, is_point, stages, notices, cues;
  double eps = 0;
  unsigned long long pairs = 0, rechecked = 0, tiles = 0;
  std::string method, backend, precision, model;
};

SaliencyOut saliency(const py::object& vertices, const py::object& faces, bool raw_maps, bool smoothed,
                     const py::object& scales, const py::object& eps_frac, const std::string& method,
                     const std::string& backend, const std::string& precision, const py::object& device,
                     const py::object& threads, const py::object& tiles, const std::string& model,
                     const std::string& up) {
  const meshsal::Mesh mesh = mesh_from_arrays(vertices, faces);
  std::vector<std::string> notices;
  meshsal::SaliencyOptions options =
      saliency_options({scales, eps_frac, method, backend, precision, device, threads, model, up}, &notices);
  options.smoothed = smoothed;
  options.tiles = count_arg(tiles, "tiles");
  options.raw_maps = raw_maps;  // kept (8 bytes per vertex per scale) only when returned
  meshsal::SaliencyResult r;
  {
    const InterruptibleCall call;  // other Python threads run while it computes; Ctrl-C stops it
    options.cancel = call.flag();
    r = meshsal::compute_saliency(mesh, options);
  }
  SaliencyOut out;
  const size_t n = mesh.vertex_count();
  out.saliency = to_numpy(std::move(r.saliency));
  out.curvature = to_numpy(std::move(r.curvature));
  out.smoothed = smoothed ? py::object(to_numpy(std::move(r.smoothed))) : py::none();
  out.is_point = to_numpy(std::move(r.is_point)).attr("astype")("bool");
  if (raw_maps) {
    // One (scales, n) array: the maps are separate vectors, so this is the one copy.
    py::array_t<double> raw({py::ssize_t(r.raw.size()), py::ssize_t(n)});
    auto w = raw.mutable_unchecked<2>();
    for (size_t i = 0; i < r.raw.size(); ++i)
      for (size_t v = 0; v < n; ++v) w(py::ssize_t(i), py::ssize_t(v)) = r.raw[i][v];
    out.raw = raw;
  } else {
    out.raw = py::none();
  }
  py::dict stages;
  for (const meshsal::StageTime& s : r.stages) stages[py::str(s.name)] = s.seconds;
  out.stages = stages;
  out.notices = py::cast(notices);
  out.eps = r.eps;
  out.pairs = r.pairs;
  out.rechecked = r.rechecked;
  out.tiles = r.tiles;
  out.method = r.method == meshsal::Method::Fast ? "fast" : "exact";
  out.backend = r.backend_name;
  out.precision = r.mixed_precision ? "mixed" : "double";
  out.model = meshsal::model_name(r.model);
  py::dict cues;
  for (auto& cue : r.cues) cues[py::str(cue.first)] = to_numpy(std::move(cue.second));
  out.cues = cues;
  return out;
}

}  // namespace

void bind_saliency(py::module_& m) {
  py::class_<SaliencyOut>(m, "SaliencyResult",
                          "The result of saliency(): per-vertex numpy arrays and the run's facts.")
      .def_readonly("saliency", &SaliencyOut::saliency,
                    "float64 (n,): final saliency S per vertex (0 on vertices no triangle uses)")
      .def_readonly("curvature", &SaliencyOut::curvature, "float64 (n,): mean curvature H per vertex")
      .def_readonly("smoothed", &SaliencyOut::smoothed,
                    "float64 (n,): Sm = G(S, 3 eps), the map simplification uses; None unless smoothed=True")
      .def_readonly("raw", &SaliencyOut::raw,
                    "float64 (scales, n): raw center-surround maps S_i; None unless raw_maps=True")
      .def_readonly("is_point", &SaliencyOut::is_point, "bool (n,): the vertex is used by a triangle")
      .def_readonly("eps", &SaliencyOut::eps, "the scale unit eps, model units")
      .def_readonly("pairs", &SaliencyOut::pairs, "neighbour pairs the sweep visited")
      .def_readonly("rechecked", &SaliencyOut::rechecked, "points a mixed-precision sweep swept again in double")
      .def_readonly("tiles", &SaliencyOut::tiles, "tiles of the grid (tiles=N), 0 untiled")
      .def_readonly("method", &SaliencyOut::method, "'exact' or 'fast' (method='auto' resolved)")
      .def_readonly("backend", &SaliencyOut::backend, "'cpu (N threads)' or the Vulkan device's name")
      .def_readonly("precision", &SaliencyOut::precision, "the sweep's arithmetic: 'double' or 'mixed'")
      .def_readonly("stages", &SaliencyOut::stages, "dict: wall seconds per stage")
      .def_readonly("model", &SaliencyOut::model, "what S models: 'lee2005', 'perceptual' or a cue's name")
      .def_readonly("cues", &SaliencyOut::cues,
                    "dict of float64 (n,): the perceptual model's cues by name (exposure_centre, height, rarity, "
                    "coarse), the one cue of a cue model; empty for 'lee2005'")
      .def_readonly("notices", &SaliencyOut::notices, "list of str: the library's notices (e.g. a CPU fallback)")
      .def("__repr__", [](const SaliencyOut& r) {
        return "<meshsal.SaliencyResult: " + std::to_string(py::len(r.saliency)) + " vertices, backend '" +
               r.backend + "', method " + r.method + ">";
      });
  m.def("saliency", &saliency, py::arg("vertices"), py::arg("faces"), py::kw_only(),
        py::arg("raw_maps").noconvert() = false, py::arg("smoothed").noconvert() = false, py::arg("scales") = py::none(),
        py::arg("eps_frac") = 0.003, py::arg("method") = "exact", py::arg("backend") = "auto",
        py::arg("precision") = "auto", py::arg("device") = -1, py::arg("threads") = 0u, py::arg("tiles") = 0u,
        py::arg("model") = "lee2005", py::arg("up") = "y",
        (std::string(R"(saliency(vertices, faces, *, raw_maps=False, smoothed=False, scales=None, eps_frac=0.003,
         method='exact', backend='auto', precision='auto', device=-1, threads=0, tiles=0,
         model='lee2005', up='y') -> SaliencyResult

Mesh saliency of every vertex (`meshsal saliency`): the result's .saliency is the PLY's
`quality`, .curvature and .raw (raw_maps=True) what --dump-scales adds, .smoothed
(smoothed=True) the smoothed map Sm = G(S, 3 eps) that saliency-guided simplification uses.

  vertices    (n, 3) float32 or float64, any strides (trimesh's, Open3D's np.asarray(...))
  faces       (m, 3) integers (int32, int64, uint32, ...), each in [0, n)
  raw_maps    also return .curvature's companions .raw, the center-surround maps S_i
              (--dump-scales); save(path, V, F, r.saliency) writes the PLY of S
  smoothed    also return .smoothed, Sm = G(S, 3 eps) with the same method
  tiles       compute in cubic tiles, this many along the longest axis, each with a halo
              (`meshsal saliency --tiles`): exact gives the same bits, fast the same to 1e-4;
              CPU only
Wrong types raise TypeError; wrong shapes, NaN/inf, indices out of range ValueError; the
library's errors meshsal.Error (a ValueError). The GIL is released while it computes.
)") + kSaliencyArgsDoc).c_str());
}

}  // namespace meshsal_py
