// meshsal: simplification in a request: one target (simplify_mesh or its tiled twin), a
// chain of levels of detail, or out of core; the weights from S had once for the run.
#include <algorithm>
#include <string>
#include <vector>

#include "api/request_parts.h"
#include "core/mesh_points.h"
#include "core/timer.h"
#include "meshsal/meshsal.h"
#include "simplify/simplify.h"

namespace meshsal {
namespace {

bool same_vertices(const Mesh& a, const Mesh& b) {
  return a.positions == b.positions && a.triangles == b.triangles && a.position_vertex == b.position_vertex;
}

// The simplified mesh written in the format its name gives; a glTF takes the S the
// simplifier carried (the `quality` attribute) as _SALIENCY and COLOR_0.
void write_simplified(RequestRun& run, const std::string& path, const Mesh& mesh) {
  const std::string format = mesh_output_format(path);
  if (format != ".glb" && format != ".gltf") return write_request_mesh(run, path, mesh);
  Mesh plain = mesh;
  const std::vector<double> s = take_vertex_attribute(plain, kSaliencyAttribute);
  write_request_mesh(run, path, plain, s);
}

}  // namespace

void make_simplified(RequestRun& run) {
  const Request& r = run.request;
  RequestResult& out = run.result;
  SimplifyOptions opt = r.simplify;
  if (!opt.cancel) opt.cancel = r.saliency.cancel;
  if (r.out_of_core.memory_limit > 0) {
    // The tiled simplifier on disk, its own saliency (simplify_file).
    std::optional<SaliencyWeightOptions> weights;
    if (r.weighting != Weighting::None) weights = r.weight_options;
    OutOfCoreOptions o = r.out_of_core;
    o.saliency_output = r.saliency_output;  // S from the same tiles (run_request)
    o.dump_scales = r.dump_scales;
    out.simplify_out_of_core = simplify_file(r.input, r.simplified_output, opt, weights, r.saliency, o);
    out.simplify = out.simplify_out_of_core.simplify;
    out.alpha = out.simplify_out_of_core.alpha;
    if (writes_files(r)) out.outputs.push_back(r.simplified_output);
    if (!out.simplify.reached && !out.simplify.note.empty()) add_note(run, out.simplify.note);
    return;
  }
  Mesh mesh = *run.attributed;
  // A target at or above the face count keeps the mesh as it is (the library's rule), with
  // no saliency computed for it.
  if (simplify_keeps_mesh(opt, mesh.triangle_count())) {
    Simplified kept = simplify_mesh(mesh, opt);
    out.simplified = std::move(kept.mesh);
    out.simplify = std::move(kept.report);
    const size_t target = opt.target_faces > 0 ? opt.target_faces : mesh.triangle_count();
    add_note(run, "the target (" + std::to_string(target) + " faces) is at or above the mesh's " +
                      std::to_string(mesh.triangle_count()) + " faces: " +
                      (r.simplified_output.empty() ? "the mesh is returned unchanged" : "wrote it unchanged"));
    if (!r.simplified_output.empty() && writes_files(r)) write_simplified(run, r.simplified_output, out.simplified);
    return;
  }
  // A bad target is refused before any time goes into saliency.
  resolve_target_faces(opt, mesh.triangle_count());
  const Timer weights_time;
  std::vector<double> weights;
  // S goes to the output as `quality` (a glTF's _SALIENCY) where the format keeps its value.
  const bool carry_s = r.simplified_output.empty() || mesh_format(r.simplified_output)->saliency == SaliencyKept::Value;
  if (r.vertex_weights) {
    weights = *r.vertex_weights;
  } else if (r.weighting != Weighting::None) {
    if (run.has_plain_s && !run.plain_s.smoothed.empty() && same_vertices(mesh, *run.plain) && mesh.position_vertex.empty()) {
      // S was computed with its Sm on this very mesh: the weights simplification_weights()
      // would compute from it.
      SaliencyWeights w = saliency_weights(run.plain_s.smoothed, referenced_vertices(mesh), r.weight_options);
      weights = std::move(w.weights);
      out.alpha = w.alpha;
      out.weights_device = run.plain_s.backend_name;
      if (carry_s) set_vertex_attribute(mesh, kSaliencyAttribute, run.plain_s.saliency);
    } else {
      std::vector<double> from_file;
      if (r.saliency_values) from_file = *r.saliency_values;
      else if (!r.saliency_from.empty()) from_file = load_saliency(r.saliency_from, mesh);
      SimplificationWeights w = simplification_weights(mesh, r.weight_options, r.saliency, from_file);
      weights = std::move(w.weights);
      out.alpha = w.alpha;
      out.weights_device = w.device;
      if (r.saliency_from.empty() && !r.saliency_values) out.saliency_source = "computed (" + w.device + ")";
      else if (!r.saliency_from.empty()) out.saliency_source = r.saliency_from;
      if (carry_s) set_vertex_attribute(mesh, kSaliencyAttribute, w.saliency);
    }
  }
  out.weights_seconds = weights_time.seconds();
  Simplified made = opt.tiles > 1 ? simplify_mesh_tiled(mesh, opt, weights) : simplify_mesh(mesh, opt, weights);
  out.simplified = std::move(made.mesh);
  out.simplify = std::move(made.report);
  const SimplifyReport& rep = out.simplify;
  if (!r.simplified_output.empty() && writes_files(r)) write_simplified(run, r.simplified_output, out.simplified);
  if (!rep.reached && (opt.target_faces > 0 || opt.ratio > 0)) add_note(run, rep.note);
  // The input too coarse for its floats: said once (a computed S already said it).
  const bool told = !weights.empty() && r.saliency_from.empty() && !r.saliency_values;
  if (!rep.warning.empty() && !told && rep.note.find(rep.warning) == std::string::npos && r.saliency.notice)
    r.saliency.notice("warning: " + rep.warning);
}

void make_lod(RequestRun& run) {
  const Request& r = run.request;
  RequestResult& out = run.result;
  const Mesh& mesh = *run.attributed;
  const bool weighted = r.weighting != Weighting::None;
  std::vector<double> s;
  if (weighted) s = r.saliency_values ? *r.saliency_values : attributed_saliency(run);
  std::vector<SimplifyOptions> levels = r.lod;
  for (SimplifyOptions& l : levels) {
    l.lock_border = r.simplify.lock_border;
    l.threads = r.simplify.threads;
    if (!l.cancel) l.cancel = r.saliency.cancel;
  }
  SaliencyOptions so = r.saliency;
  so.raw_maps = false;  // only S is used
  std::optional<SaliencyWeightOptions> weights;
  if (weighted) weights = r.weight_options;
  out.lod = simplify_lod(mesh, levels, weights, so, s);
  for (size_t i = 0; i < out.lod.size(); ++i)
    if (!out.lod[i].report.reached || out.lod[i].report.unchanged)
      add_note(run, "LOD" + std::to_string(i + 1) + ": " + out.lod[i].report.note);
  if (r.lod_output.empty()) return;
  // One glTF holding the input and every level, or a file per level (write_lod): each
  // file's side files checked first and named, and what a level's format cannot hold said.
  const std::string format = mesh_output_format(r.lod_output);
  std::vector<std::vector<std::string>> side;
  if (format == ".glb" || format == ".gltf") {
    out.lod_files.push_back(r.lod_output);
    add_note(run, mesh_output_note(r.lod_output, mesh, weighted));
  } else {
    for (size_t i = 0; i < out.lod.size(); ++i) {
      out.lod_files.push_back(lod_level_path(r.lod_output, i + 1));
      side.push_back(check_side_files(run, out.lod_files[i], out.lod[i].mesh));
      add_note(run, mesh_output_note(out.lod_files[i], out.lod[i].mesh, false));
    }
  }
  write_lod(r.lod_output, mesh, s, out.lod);
  for (size_t i = 0; i < out.lod_files.size(); ++i) {
    out.outputs.push_back(out.lod_files[i]);
    if (i < side.size()) out.outputs.insert(out.outputs.end(), side[i].begin(), side[i].end());
  }
}

}  // namespace meshsal
