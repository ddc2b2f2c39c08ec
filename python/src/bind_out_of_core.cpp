// meshsal Python module: saliency_file() and simplify_file(), file to file under a memory
// limit (the library's out-of-core calls; `meshsal saliency/simplify --memory-limit`).
#include <string>
#include <vector>

#include "bindings.h"
#include "interrupt.h"
#include "meshsal/meshsal.h"
#include "paths.h"
#include "saliency_args.h"

namespace meshsal_py {

namespace {

meshsal::OutOfCoreOptions out_of_core(const py::object& memory_limit, const py::object& temp_dir) {
  meshsal::OutOfCoreOptions o;
  if (!memory_limit.is_none()) {
    if (py::isinstance<py::str>(memory_limit)) o.memory_limit = meshsal::parse_memory_size(memory_limit.cast<std::string>());
    else if (py::isinstance<py::int_>(memory_limit) && !py::isinstance<py::bool_>(memory_limit)) {
      const long long bytes = memory_limit.cast<long long>();
      if (bytes <= 0) throw py::value_error("memory_limit must be > 0 bytes");
      o.memory_limit = uint64_t(bytes);
    } else {
      throw py::type_error("memory_limit must be a size such as '700M' or a number of bytes");
    }
  }
  if (!temp_dir.is_none()) o.temp_dir = path_bytes(temp_dir);
  return o;
}

py::dict stages_dict(const std::vector<meshsal::StageTime>& stages) {
  py::dict d;
  for (const meshsal::StageTime& s : stages) d[py::str(s.name)] = s.seconds;
  return d;
}

py::dict saliency_file(const py::object& input, const py::object& output, const py::object& memory_limit,
                       const py::object& temp_dir, unsigned tiles, const py::object& scales, double eps_frac,
                       const std::string& method, unsigned threads) {
  std::vector<std::string> notices;
  meshsal::SaliencyOptions so =
      saliency_options({scales, eps_frac, method, "cpu", "auto", py::int_(-1), threads}, &notices);
  so.tiles = tiles;
  const meshsal::OutOfCoreOptions ooc = out_of_core(memory_limit, temp_dir);
  const std::string in = path_bytes(input), out = path_bytes(output);
  meshsal::OutOfCoreReport r;
  {
    const InterruptibleCall call;
    so.cancel = call.flag();
    r = meshsal::saliency_file(in, out, so, ooc);
  }
  py::dict d;
  d["vertices"] = r.vertices;
  d["points"] = r.points;
  d["faces"] = r.triangles;
  d["tiles"] = r.tiles;
  d["tile_estimate"] = r.tile_estimate;
  d["eps"] = r.eps;
  d["pairs"] = r.pairs;
  d["saliency_min"] = r.saliency_min;
  d["saliency_mean"] = r.saliency_mean;
  d["saliency_max"] = r.saliency_max;
  d["stages"] = stages_dict(r.stages);
  return d;
}

py::dict simplify_file(const py::object& input, const py::object& output, const py::object& target_faces,
                       const py::object& ratio, const py::object& memory_limit, const py::object& temp_dir,
                       unsigned tiles, bool lock_border, const std::string& weights, double eps_frac,
                       const std::string& method, unsigned threads) {
  if (target_faces.is_none() == ratio.is_none()) throw py::value_error("give one of target_faces and ratio");
  meshsal::SimplifyOptions options;
  options.threads = threads;
  options.lock_border = lock_border;
  if (!target_faces.is_none()) {
    const long long t = target_faces.cast<long long>();
    if (t < 1 || t > 4000000000LL) throw py::value_error("target_faces must be in [1, 4000000000]");
    options.target_faces = size_t(t);
  } else {
    const double r = ratio.cast<double>();
    if (!(r > 0 && r <= 1)) throw py::value_error("ratio must be in (0, 1]");
    options.ratio = r;
  }
  // The library's names and presets, as --weights (meshsal.Error for another name).
  const meshsal::Weighting weighting = meshsal::parse_weighting(weights);
  const meshsal::SaliencyWeightOptions wo = meshsal::weight_preset(weighting);
  std::vector<std::string> notices;
  meshsal::SaliencyOptions so =
      saliency_options({py::none(), eps_frac, method, "cpu", "auto", py::int_(-1), threads}, &notices);
  const meshsal::OutOfCoreOptions ooc = out_of_core(memory_limit, temp_dir);
  const std::string in = path_bytes(input), out = path_bytes(output);
  meshsal::OutOfCoreSimplifyReport r;
  {
    const InterruptibleCall call;
    options.cancel = call.flag();
    so.cancel = call.flag();
    r = meshsal::simplify_file(in, out, options, weighting == meshsal::Weighting::None ? nullptr : &wo, so, ooc,
                               std::max(1u, tiles));
  }
  py::dict d;
  d["input_faces"] = r.simplify.input_faces;
  d["output_faces"] = r.simplify.output_faces;
  d["output_vertices"] = r.simplify.output_vertices;
  d["target_faces"] = r.simplify.target_faces;
  d["reached"] = r.simplify.reached;
  d["unchanged"] = r.simplify.unchanged;
  d["collapses"] = r.simplify.collapses;
  d["error_percent"] = 100 * r.simplify.error;
  d["note"] = r.simplify.note;
  d["tiles"] = r.tiles;
  d["saliency_tiles"] = r.saliency.tiles;
  d["tile_estimate"] = r.tile_estimate;
  d["alpha"] = r.alpha;
  d["stages"] = stages_dict(r.stages);
  return d;
}

}  // namespace

void bind_out_of_core(py::module_& m) {
  m.def("saliency_file", &saliency_file, py::arg("input"), py::arg("output"), py::kw_only(),
        py::arg("memory_limit") = py::none(), py::arg("temp_dir") = py::none(), py::arg("tiles") = 0u,
        py::arg("scales") = py::none(), py::arg("eps_frac") = 0.003, py::arg("method") = "auto",
        py::arg("threads") = 0u,
        R"(saliency_file(input, output, *, memory_limit=None, temp_dir=None, tiles=0, scales=None,
              eps_frac=0.003, method='auto', threads=0) -> dict

`meshsal saliency IN -o OUT.ply --memory-limit SIZE`: the saliency of the mesh file `input`
written to `output` (a PLY as the command writes it, the same bytes) without holding the
mesh whole: streamed into tiles in a temporary folder under temp_dir (default $TMPDIR or
/tmp, removed at the end) and computed a tile at a time on the CPU. memory_limit: a size
('700M', '2G') or bytes, the peak resident memory to stay under (None: no limit, `tiles`
decides); too small a limit raises meshsal.Error naming the smallest workable one.
method 'auto' is taken as 'fast'. Returns the report (counts, tiles, tile_estimate,
saliency range, stages).)");
  m.def("simplify_file", &simplify_file, py::arg("input"), py::arg("output"), py::kw_only(),
        py::arg("target_faces") = py::none(), py::arg("ratio") = py::none(), py::arg("memory_limit") = py::none(),
        py::arg("temp_dir") = py::none(), py::arg("tiles") = 1u, py::arg("lock_border") = false,
        py::arg("weights") = meshsal::weighting_name(meshsal::kDefaultWeighting), py::arg("eps_frac") = 0.003,
        py::arg("method") = "exact", py::arg("threads") = 0u,
        R"(simplify_file(input, output, *, target_faces=None, ratio=None, memory_limit=None,
              temp_dir=None, tiles=1, lock_border=False, weights='balanced', eps_frac=0.003,
              method='exact', threads=0) -> dict

`meshsal simplify IN -o OUT.ply --memory-limit SIZE` (the same bytes): the tiled
simplifier run on disk, a tile at a time, toward target_faces or ratio (give one), with
saliency weights ('saliency', 'balanced' or 'none') computed out of core; lock_border keeps
the vertices of open borders in place (--lock-border). At least `tiles`
tiles along the longest axis, more where memory_limit needs them. Writes a binary PLY
(positions and S as `quality`). Returns the report (faces, collapses, error_percent,
tiles, alpha, stages).)");
}

}  // namespace meshsal_py
