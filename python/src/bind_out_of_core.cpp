// meshsal Python module: saliency_file() and simplify_file(), file to file as `meshsal
// saliency` and `meshsal simplify` (the library's one pipeline, run_request), in memory or
// under a memory limit.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "arg_values.h"
#include "bindings.h"
#include "interrupt.h"
#include "meshsal/meshsal.h"
#include "paths.h"
#include "request_call.h"
#include "saliency_args.h"

namespace meshsal_py {

namespace {

meshsal::OutOfCoreOptions out_of_core(const py::object& memory_limit, const py::object& temp_dir) {
  meshsal::OutOfCoreOptions o;
  if (!memory_limit.is_none()) {
    if (py::isinstance<py::str>(memory_limit)) o.memory_limit = meshsal::parse_memory_size(memory_limit.cast<std::string>());
    else if (is_integer(memory_limit))
      o.memory_limit = unsigned_arg(memory_limit, "memory_limit", 1, std::numeric_limits<uint64_t>::max());
    else
      throw py::type_error("memory_limit must be a size such as '700M' or a number of bytes, got " + type_name(memory_limit));
  }
  if (!temp_dir.is_none()) o.temp_dir = path_bytes(temp_dir);
  return o;
}

// The library's error as load() and save() raise theirs: meshsal.FileNotFoundError or
// meshsal.PermissionError (filename: the output when the message starts with its name,
// else the input), else meshsal.Error.
[[noreturn]] void raise_error_of(const meshsal::Error& e, const py::object& input, const py::object& output,
                                 const std::string& out) {
  const std::string message = e.what();
  raise_file_error(e, message.compare(0, out.size() + 1, out + ":") == 0 ? output : input);
}

py::dict stages_dict(const std::vector<meshsal::StageTime>& stages) {
  py::dict d;
  for (const meshsal::StageTime& s : stages) d[py::str(s.name)] = s.seconds;
  return d;
}

// The library's one pipeline for a file-to-file call (run_request), interruptible by
// Ctrl-C: its errors as the module raises a file's (raise_error_of, with the GIL back), its
// refusals of combinations in Python's names.
meshsal::RequestResult run_files(meshsal::Request& r, const py::object& input, const py::object& output) {
  const std::string out = !r.saliency_output.empty()     ? r.saliency_output
                          : !r.simplified_output.empty() ? r.simplified_output
                                                         : r.lod_output;
  try {
    const InterruptibleCall call;
    r.simplify.cancel = r.saliency.cancel = call.flag();
    return run_in_python_terms(r);
  } catch (const meshsal::Cancelled&) {
    throw;
  } catch (const meshsal::Error& e) {
    raise_error_of(e, input, output, out);
  }
}

py::dict saliency_file(const py::object& input, const py::object& output, const py::object& memory_limit,
                       const py::object& temp_dir, const py::object& tiles, bool dump_scales, const py::object& scales,
                       const py::object& eps_frac, const std::string& method, const std::string& backend,
                       const std::string& precision, const py::object& device, const py::object& threads,
                       const std::string& model, const std::string& up) {
  std::vector<std::string> notices;
  meshsal::Request r;
  r.output_option = "the output";
  r.saliency = saliency_options({scales, eps_frac, method, backend, precision, device, threads, model, up}, &notices);
  r.saliency.tiles = count_arg(tiles, "tiles");
  r.out_of_core = out_of_core(memory_limit, temp_dir);
  r.input = path_bytes(input);
  r.saliency_output = path_bytes(output);
  r.dump_scales = dump_scales;
  const meshsal::RequestResult res = run_files(r, input, output);
  py::dict d;
  if (r.out_of_core.memory_limit) {
    const meshsal::OutOfCoreReport& o = res.out_of_core;
    d["vertices"] = o.vertices;
    d["points"] = o.points;
    d["faces"] = o.triangles;
    d["tiles"] = o.tiles;
    d["tile_estimate"] = o.tile_estimate;
    d["eps"] = o.eps;
    d["pairs"] = o.pairs;
    d["saliency_min"] = o.saliency_min;
    d["saliency_mean"] = o.saliency_mean;
    d["saliency_max"] = o.saliency_max;
    d["stages"] = stages_dict(o.stages);
  } else {
    const meshsal::SaliencyResult& s = res.saliency;
    const meshsal::SaliencyStats st = meshsal::saliency_stats(s);
    d["vertices"] = res.mesh.vertex_count();
    d["points"] = st.points;
    d["faces"] = res.mesh.triangle_count();
    d["tiles"] = s.tiles;
    d["eps"] = s.eps;
    d["pairs"] = s.pairs;
    d["saliency_min"] = st.min;
    d["saliency_mean"] = st.mean;
    d["saliency_max"] = st.max;
    d["device"] = s.backend_name;
    d["stages"] = stages_dict(s.stages);
  }
  d["outputs"] = py::cast(res.outputs);
  for (const std::string& n : res.notes) notices.push_back("note: " + n);
  d["notices"] = py::cast(notices);
  return d;
}

py::dict simplify_file(const py::object& input, const py::object& output, const py::object& target_faces,
                       const py::object& ratio, const py::object& target_error, const py::object& lod,
                       const py::object& memory_limit, const py::object& temp_dir, const py::object& tiles,
                       bool lock_border, const std::string& weights, const py::object& saliency_from,
                       const py::object& eps_frac, const std::string& method, const std::string& backend,
                       const std::string& precision, const py::object& device, const py::object& threads,
                       const std::string& model, const std::string& up) {
  std::vector<std::string> notices;
  meshsal::Request r;
  r.output_option = "the output";
  r.saliency = saliency_options({py::none(), eps_frac, method, backend, precision, device, threads, model, up}, &notices);
  // Both targets as given: the library's rules (check_request) say which combine.
  if (!target_faces.is_none()) r.simplify.target_faces = size_t(integer_arg(target_faces, "target_faces", 1, 4000000000LL));
  if (!ratio.is_none()) {
    const double x = number_arg(ratio, "ratio");
    if (!(x > 0 && x <= 1)) throw py::value_error("ratio must be in (0, 1], got " + std::string(py::str(ratio)));
    r.simplify.ratio = x;
  }
  if (!target_error.is_none()) {
    const double e = number_arg(target_error, "target_error");
    if (!(e > 0 && e <= 100)) throw py::value_error("target_error must be in (0, 100], got " + std::string(py::str(target_error)));
    r.simplify.target_error = e / 100;
  }
  r.simplify.lock_border = lock_border;
  r.simplify.threads = r.saliency.threads;
  // The library's names and presets, as --weights (meshsal.Error for another name).
  r.weighting = meshsal::parse_weighting(weights);
  r.weight_options = meshsal::weight_preset(r.weighting);
  r.simplify.tiles = count_arg(tiles, "tiles");
  r.out_of_core = out_of_core(memory_limit, temp_dir);
  r.input = path_bytes(input);
  if (!saliency_from.is_none()) r.saliency_from = path_bytes(saliency_from);
  if (lod.is_none()) {
    r.simplified_output = path_bytes(output);
  } else {
    r.lod = lod_levels(lod);
    r.lod_output = path_bytes(output);
  }
  const meshsal::RequestResult res = run_files(r, input, output);
  py::dict d;
  const meshsal::SimplifyReport& rep = res.simplify;
  if (lod.is_none()) {
    d["input_faces"] = rep.input_faces;
    d["output_faces"] = rep.output_faces;
    d["output_vertices"] = rep.output_vertices;
    d["target_faces"] = rep.target_faces;
    d["reached"] = rep.reached;
    d["unchanged"] = rep.unchanged;
    d["collapses"] = rep.collapses;
    d["error_percent"] = 100 * rep.error;
    d["note"] = rep.note;
    d["alpha"] = res.alpha;
  } else {
    py::list levels;
    for (const meshsal::LodLevel& level : res.lod) {
      py::dict l;
      l["target_faces"] = level.report.target_faces;
      l["output_faces"] = level.report.output_faces;
      l["output_vertices"] = level.report.output_vertices;
      l["reached"] = level.report.reached;
      l["unchanged"] = level.report.unchanged;
      l["error_percent"] = 100 * level.report.error;
      levels.append(l);
    }
    d["levels"] = levels;
  }
  if (r.out_of_core.memory_limit) {
    const meshsal::OutOfCoreSimplifyReport& o = res.simplify_out_of_core;
    d["tiles"] = o.tiles;
    d["saliency_tiles"] = o.saliency.tiles;
    d["tile_estimate"] = o.tile_estimate;
    d["groups_at_once"] = o.groups_at_once;
    d["stages"] = stages_dict(o.stages);
  } else {
    d["tiles"] = std::max(1u, r.simplify.tiles);
  }
  d["outputs"] = py::cast(res.outputs);
  for (const std::string& n : res.notes) notices.push_back("note: " + n);
  d["notices"] = py::cast(notices);
  return d;
}

}  // namespace

void bind_out_of_core(py::module_& m) {
  m.def("saliency_file", &saliency_file, py::arg("input"), py::arg("output"), py::kw_only(),
        py::arg("memory_limit") = py::none(), py::arg("temp_dir") = py::none(), py::arg("tiles") = 0u,
        py::arg("dump_scales").noconvert() = false, py::arg("scales") = py::none(), py::arg("eps_frac") = 0.003,
        py::arg("method") = "exact", py::arg("backend") = "auto", py::arg("precision") = "auto", py::arg("device") = -1,
        py::arg("threads") = 0u, py::arg("model") = "lee2005", py::arg("up") = "y",
        R"(saliency_file(input, output, *, memory_limit=None, temp_dir=None, tiles=0, dump_scales=False,
              scales=None, eps_frac=0.003, method='exact', backend='auto', precision='auto',
              device=-1, threads=0, model='lee2005', up='y') -> dict

`meshsal saliency IN -o OUT` (the library's one pipeline, the same bytes): the saliency of
the mesh file `input` written with the mesh to `output` in the format its name gives (.ply,
.glb, .gltf keep S; .obj and .off its colours; .stl is refused), the input's attributes and
materials carried where the format keeps them (see "notices"). dump_scales: also the
curvature and raw maps. With memory_limit (a size such as '700M', or bytes) the mesh is
never held whole (`--memory-limit`): streamed into tiles in a temporary folder under
temp_dir (default $TMPDIR or /tmp, removed at the end), computed a tile at a time on the CPU,
output a binary PLY; too small a limit raises meshsal.Error naming the smallest workable
one. tiles: cubic tiles along the longest axis (exact: the same bits). method: 'exact' (the
default of every front end), 'fast' or 'auto' (out of core: taken as 'fast'). Returns the
report (counts, eps, pairs, saliency range, stages, tiles; out of core tile_estimate),
"outputs" (every file written) and "notices".

input and output are str, bytes or os.PathLike. Before any work the library checks the
output as the CLI's: a mesh format's name (out of core: .ply), never the input file itself,
not through a symbolic or hard link either (meshsal.Error; the input is left as it was), in
a folder that exists (meshsal.FileNotFoundError) and may be written
(meshsal.PermissionError). memory_limit, tiles and threads out of range raise ValueError
naming the value.)");
  m.def("simplify_file", &simplify_file, py::arg("input"), py::arg("output"), py::kw_only(),
        py::arg("target_faces") = py::none(), py::arg("ratio") = py::none(), py::arg("target_error") = py::none(),
        py::arg("lod") = py::none(), py::arg("memory_limit") = py::none(), py::arg("temp_dir") = py::none(),
        py::arg("tiles") = 0u, py::arg("lock_border").noconvert() = false,
        py::arg("weights") = meshsal::weighting_name(meshsal::kDefaultWeighting), py::arg("saliency_from") = py::none(),
        py::arg("eps_frac") = 0.003, py::arg("method") = "exact", py::arg("backend") = "auto",
        py::arg("precision") = "auto", py::arg("device") = -1, py::arg("threads") = 0u,
        py::arg("model") = "lee2005", py::arg("up") = "y",
        R"(simplify_file(input, output, *, target_faces=None, ratio=None, target_error=None, lod=None,
              memory_limit=None, temp_dir=None, tiles=0, lock_border=False, weights='balanced',
              saliency_from=None, eps_frac=0.003, method='exact', backend='auto',
              precision='auto', device=-1, threads=0, model='lee2005', up='y') -> dict

`meshsal simplify IN -o OUT` (the library's one pipeline, the same bytes): the mesh file
`input` simplified toward target_faces, ratio (give one) and/or target_error (% of the
bounding-box diagonal), or with lod a chain of levels (as simplify(lod=...): one glTF, or a
file per level), written in the format the output's name gives with the input's
attributes and materials (an OBJ gets its .mtl beside it) and S where the format keeps it.
weights: 'saliency', 'balanced' or 'none'; saliency_from: read S from that PLY or glTF
instead of computing it. tiles > 1: the tiled simplifier. With memory_limit the tiled
simplifier runs on disk, a tile at a time (`--memory-limit`; at least `tiles` tiles, a binary
PLY with positions and S; its groups side by side, "groups_at_once" of them). Returns the
report (faces, collapses, error_percent, alpha, tiles; with lod "levels"), "outputs" and
"notices". The output is checked before any work as
saliency_file() checks it.)");
}

}  // namespace meshsal_py
