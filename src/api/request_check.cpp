// meshsal: check_request, the one place that says which options of a run combine, and the
// output check of every file a run will write, before any work.
#include <string>
#include <vector>

#include "api/request_parts.h"
#include "meshsal/meshsal.h"
#include "saliency/saliency.h"
#include "view/render.h"

namespace meshsal {
namespace {

[[noreturn]] void refuse(const std::string& why) { throw RequestError(why); }

bool has_target(const SimplifyOptions& s) { return s.target_faces > 0 || s.ratio > 0 || s.target_error > 0; }

// The formats a mesh output may name, for check_outputs.
std::vector<std::string> mesh_suffixes() {
  std::vector<std::string> out;
  for (const MeshFormat& f : mesh_formats()) out.push_back(f.suffix);
  return out;
}

}  // namespace

Score parse_score(const std::string& name) {
  if (name == "saliency") return Score::Saliency;
  if (name == "curvature") return Score::Curvature;
  throw Error("score must be 'saliency' or 'curvature', got '" + name + "'");
}

void check_request(const Request& r) {
  if (r.input.empty() && !r.mesh) refuse("no input mesh given");
  const bool simplifying = !r.simplified_output.empty();
  const bool out_of_core = r.out_of_core.memory_limit > 0;
  const bool views = !r.page_output.empty() || !r.picture_output.empty() || !r.map_output.empty() || r.find_view;
  const SimplifyOptions& s = r.simplify;
  if (s.exchange) {
    // Shared simplification is the tiled simplifier's passes over the processes.
    if (!r.lod_output.empty() || !r.lod.empty()) refuse("--lod runs in one process: not under mpirun");
    if (s.tiles <= 1 && !out_of_core) refuse("shared simplification (mpirun) runs in tiles: give --tiles N (N >= 2)");
    if (s.target_error > 0) refuse("shared simplification (mpirun) takes --target-faces N or --ratio R, not --target-error");
    if (r.saliency.exchange && r.saliency.exchange != s.exchange)
      refuse("the saliency and the simplification name different TileExchanges");
  }
  if (r.simplify.tiles > 1 && s.target_error > 0) refuse("--tiles takes --target-faces N or --ratio R, not --target-error");
  const bool lod = !r.lod_output.empty() || (r.simplify_in_memory && !r.lod.empty());
  if (simplifying || (r.simplify_in_memory && !lod)) {
    if (s.target_faces > 0 && s.ratio > 0) refuse("give only one of --target-faces N and --ratio R");
    if (!has_target(s)) refuse("give --target-faces N, --ratio R or --target-error E");
  }
  if (lod) {
    if (r.lod.empty()) refuse("--lod needs at least one level");
    if (!simplifying && has_target(s))
      refuse("--lod names every level: give it without --target-faces, --ratio or --target-error");
    if (r.simplify.tiles > 1 || out_of_core) refuse("--lod runs in memory, in one piece: not with --tiles or --memory-limit");
  }
  if (!r.saliency_from.empty() && r.weighting == Weighting::None && r.saliency_output.empty() && !views)
    refuse("--saliency-from needs --weights saliency or balanced");
  if (r.saliency.model != Model::Lee2005) {
    const std::string model = std::string("--model ") + model_name(r.saliency.model);
    if (out_of_core || r.saliency.tiles > 1 || r.saliency.exchange)
      refuse(model + " computes S in memory, in one piece: not with --memory-limit, saliency's --tiles or mpirun "
                     "(which shares S in tiles)");
    // S given or read back is what it is: the model would silently not apply.
    if (!r.saliency_from.empty() || r.saliency_values)
      refuse(model + " computes S: not with --saliency-from or a given saliency, which is used as it is");
  }
  if (out_of_core) {
    if (views) refuse("--memory-limit makes no views: not with --view, --html, --best, --map or a picture");
    if (!r.saliency_output.empty() && mesh_output_format(r.saliency_output) != ".ply")
      refuse("--memory-limit writes a binary PLY: give -o OUT.ply");
    if (simplifying) {
      if (mesh_output_format(r.simplified_output) != ".ply") refuse("--memory-limit writes a binary PLY: give -o OUT.ply");
      if (s.target_error > 0) refuse("--memory-limit takes --target-faces N or --ratio R, not --target-error");
      if (!r.saliency_from.empty()) refuse("--memory-limit computes S itself: it does not take --saliency-from");
    }
    if (r.mesh) refuse("--memory-limit reads the file itself: not a mesh in memory");
  }
  if ((r.saliency_values || r.vertex_weights || r.attributed) && !r.mesh)
    refuse("S, weights or a mesh with attributes given with the request need its mesh given too");
  if (r.vertex_weights && r.mesh && r.vertex_weights->size() != r.mesh->vertex_count())
    throw Error("weights has " + std::to_string(r.vertex_weights->size()) + " values for a mesh of " +
                std::to_string(r.mesh->vertex_count()) + " vertices");
  if (!r.compare.empty() && r.compare.size() != 2) refuse("--compare takes two meshes: PLAIN SALIENT");
  if (!r.page_output.empty() && !built_with_viewer())
    throw Error("this meshsal was built without the web viewer (web/node_modules was missing at build time: "
                "run tools/setup.sh, then build again)");
  if (!r.saliency_output.empty() && mesh_output_format(r.saliency_output) == ".stl")
    throw Error(r.saliency_output + ": STL has no place for saliency (.ply, .gltf and .glb keep its values; .obj and .off its colours)");
  check_saliency_options(r.saliency);
  if (!r.picture_output.empty() || !r.map_output.empty()) check_render_style(r.style);

  // Every output: the extension its writer takes, writable, distinct, none of them an input.
  // Out of core, the file written is a binary PLY.
  const std::vector<std::string> meshes = out_of_core ? std::vector<std::string>{".ply"} : mesh_suffixes();
  const std::string& o = r.output_option;
  std::vector<OutputFile> outputs{{r.saliency_output, o, meshes}, {r.simplified_output, o, meshes},
                                  {r.page_output, o, {".html"}},  {r.picture_output, o, {".png"}},
                                  {r.map_output, "--map", {".png"}}};
  if (!r.lod_output.empty()) {
    const std::string format = mesh_output_format(r.lod_output);
    if (format == ".glb" || format == ".gltf" || format.empty())
      outputs.push_back({r.lod_output, o, meshes});
    else
      for (size_t i = 0; i < r.lod.size(); ++i) outputs.push_back({lod_level_path(r.lod_output, i + 1), o, meshes});
  }
  std::vector<std::string> inputs{r.input, r.saliency_from};
  inputs.insert(inputs.end(), r.compare.begin(), r.compare.end());
  check_outputs(outputs, inputs);
}

}  // namespace meshsal
