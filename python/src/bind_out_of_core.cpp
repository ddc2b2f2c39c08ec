// meshsal Python module: saliency_file() and simplify_file(), file to file under a memory
// limit (the library's out-of-core calls; `meshsal saliency/simplify --memory-limit`).
#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "arg_values.h"
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

py::dict saliency_file(const py::object& input, const py::object& output, const py::object& memory_limit,
                       const py::object& temp_dir, const py::object& tiles, const py::object& scales,
                       const py::object& eps_frac, const std::string& method, const py::object& threads) {
  std::vector<std::string> notices;
  meshsal::SaliencyOptions so =
      saliency_options({scales, eps_frac, method, "cpu", "auto", py::int_(-1), threads}, &notices);
  so.tiles = count_arg(tiles, "tiles");
  const meshsal::OutOfCoreOptions ooc = out_of_core(memory_limit, temp_dir);
  const std::string in = path_bytes(input), out = path_bytes(output);
  meshsal::OutOfCoreReport r;
  try {
    // The library checks the output (a .ply, never the input) before any work.
    const InterruptibleCall call;
    so.cancel = call.flag();
    r = meshsal::saliency_file(in, out, so, ooc);
  } catch (const meshsal::Cancelled&) {
    throw;
  } catch (const meshsal::Error& e) {
    raise_error_of(e, input, output, out);
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
                       const py::object& tiles, bool lock_border, const std::string& weights,
                       const py::object& eps_frac, const std::string& method, const py::object& threads) {
  if (target_faces.is_none() == ratio.is_none()) throw py::value_error("give one of target_faces and ratio");
  meshsal::SimplifyOptions options;
  options.lock_border = lock_border;
  if (!target_faces.is_none()) {
    options.target_faces = size_t(integer_arg(target_faces, "target_faces", 1, 4000000000LL));
  } else {
    const double r = number_arg(ratio, "ratio");
    if (!(r > 0 && r <= 1)) throw py::value_error("ratio must be in (0, 1], got " + std::string(py::str(ratio)));
    options.ratio = r;
  }
  // The library's names and presets, as --weights (meshsal.Error for another name).
  const meshsal::Weighting weighting = meshsal::parse_weighting(weights);
  const meshsal::SaliencyWeightOptions wo = meshsal::weight_preset(weighting);
  std::vector<std::string> notices;
  meshsal::SaliencyOptions so =
      saliency_options({py::none(), eps_frac, method, "cpu", "auto", py::int_(-1), threads}, &notices);
  options.threads = so.threads;
  const unsigned simplify_tiles = std::max(1u, count_arg(tiles, "tiles"));
  const meshsal::OutOfCoreOptions ooc = out_of_core(memory_limit, temp_dir);
  const std::string in = path_bytes(input), out = path_bytes(output);
  meshsal::OutOfCoreSimplifyReport r;
  try {
    // The library checks the output (a .ply, never the input) before any work.
    const InterruptibleCall call;
    options.cancel = call.flag();
    so.cancel = call.flag();
    r = meshsal::simplify_file(in, out, options, weighting == meshsal::Weighting::None ? nullptr : &wo, so, ooc,
                               simplify_tiles);
  } catch (const meshsal::Cancelled&) {
    throw;
  } catch (const meshsal::Error& e) {
    raise_error_of(e, input, output, out);
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
        py::arg("scales") = py::none(), py::arg("eps_frac") = 0.003, py::arg("method") = "exact",
        py::arg("threads") = 0u,
        R"(saliency_file(input, output, *, memory_limit=None, temp_dir=None, tiles=0, scales=None,
              eps_frac=0.003, method='exact', threads=0) -> dict

`meshsal saliency IN -o OUT.ply --memory-limit SIZE`: the saliency of the mesh file `input`
written to `output` (a PLY as the command writes it, the same bytes) without holding the
mesh whole: streamed into tiles in a temporary folder under temp_dir (default $TMPDIR or
/tmp, removed at the end) and computed a tile at a time on the CPU. memory_limit: a size
('700M', '2G') or bytes, the peak resident memory to stay under (None: no limit, `tiles`
decides); too small a limit raises meshsal.Error naming the smallest workable one.
method: 'exact' (the default of every front end), 'fast', or 'auto' (taken as 'fast' here). Returns the report (counts, tiles, tile_estimate,
saliency range, stages).

input and output are str, bytes or os.PathLike. Before any work the library checks the
output as the CLI's: a name ending in .ply (another one, .obj or .glb, raises meshsal.Error:
the file written is a binary PLY), never the input file itself, not through a symbolic or
hard link either (meshsal.Error; the input is left as it was), in a folder that exists
(meshsal.FileNotFoundError) and may be written (meshsal.PermissionError). memory_limit,
tiles and threads out of range raise ValueError naming the value.)");
  m.def("simplify_file", &simplify_file, py::arg("input"), py::arg("output"), py::kw_only(),
        py::arg("target_faces") = py::none(), py::arg("ratio") = py::none(), py::arg("memory_limit") = py::none(),
        py::arg("temp_dir") = py::none(), py::arg("tiles") = 1u, py::arg("lock_border").noconvert() = false,
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
tiles, alpha, stages). The output is checked before any work as saliency_file() checks it
(a .ply name, never the input, through a link either).)");
}

}  // namespace meshsal_py
