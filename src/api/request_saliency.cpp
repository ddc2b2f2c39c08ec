// meshsal: S in a request, had once for every output: computed, or read back (--saliency-from,
// or the input itself when it holds S); the saliency output; the score the views show.
#include <cmath>
#include <string>
#include <vector>

#include "api/request_parts.h"
#include "core/adjacency.h"
#include "core/mesh_points.h"
#include "meshsal/meshsal.h"
#include "saliency/curvature.h"

namespace meshsal {
namespace {

// The file S is read back from, if any: --saliency-from, else (with saliency_from_input)
// the input when it holds S (a PLY's quality, a glTF's _SALIENCY), which a note says.
std::string find_saliency_file(RequestRun& run) {
  const Request& r = run.request;
  if (!r.saliency_from.empty()) return r.saliency_from;
  // A model other than the paper's asked for: computed, whatever the input holds.
  if (!r.saliency_from_input || !run.input_has_saliency || r.saliency.model != Model::Lee2005) return "";
  add_note(run, r.input + ": using its own saliency (per-vertex quality, as `meshsal saliency` writes it), "
                          "not computing it again");
  return r.input;
}

std::string saliency_file_of(RequestRun& run) {
  if (!run.saliency_file_known) {
    run.saliency_file = find_saliency_file(run);
    run.saliency_file_known = true;
  }
  return run.saliency_file;
}

// S of `mesh` read back or computed: the full result (raw maps with dump_scales, Sm when
// `smoothed`; backend_name empty when read).
SaliencyResult saliency_of(RequestRun& run, const Mesh& mesh, bool smoothed) {
  const Request& r = run.request;
  const std::string from = saliency_file_of(run);
  SaliencyResult s;
  if (r.saliency_values) {
    if (r.saliency_values->size() != mesh.vertex_count())
      throw Error("saliency has " + std::to_string(r.saliency_values->size()) + " values for a mesh of " +
                  std::to_string(mesh.vertex_count()) + " vertices");
    s.saliency = *r.saliency_values;
    s.is_point = referenced_vertices(mesh);
    if (smoothed) s.smoothed = smooth_saliency(mesh, s.saliency, r.saliency);
    run.result.saliency_source = "given";
    return s;
  }
  if (!from.empty()) {
    s.saliency = load_saliency(from, mesh);
    s.is_point = referenced_vertices(mesh);
    if (smoothed) s.smoothed = smooth_saliency(mesh, s.saliency, r.saliency);
    run.result.saliency_source = from;
    return s;
  }
  SaliencyOptions so = run.saliency;
  so.smoothed = smoothed;
  so.raw_maps = r.dump_scales;  // written only then: 8 bytes per vertex per scale otherwise
  s = compute_saliency(mesh, so);
  if (run.warm_up_wait >= 0) {  // the part of the warm-up (and uploads) reading did not hide
    s.stages.insert(s.stages.begin(), {"device warm-up", run.warm_up_wait});
    run.warm_up_wait = -1;
  }
  run.result.saliency_source = "computed (" + s.backend_name + ")";
  return s;
}

bool same_vertices(const Mesh& a, const Mesh& b) {
  return a.positions == b.positions && a.triangles == b.triangles && a.position_vertex == b.position_vertex;
}

}  // namespace

void plain_saliency(RequestRun& run, bool smoothed) {
  if (run.has_plain_s && (!smoothed || !run.plain_s.smoothed.empty())) return;
  run.plain_s = saliency_of(run, *run.plain, smoothed);
  run.has_plain_s = true;
}

const std::vector<double>& attributed_saliency(RequestRun& run) {
  if (run.has_attributed_s) return run.attributed_s;
  // The plain mesh's S when the two are one mesh (nothing split or added by the attributes).
  if (run.has_plain_s && same_vertices(*run.attributed, *run.plain) && run.attributed->position_vertex.empty()) {
    run.attributed_s = run.plain_s.saliency;
    run.attributed_s_device = run.result.saliency_source;
  } else {
    SaliencyResult s = saliency_of(run, *run.attributed, false);
    run.attributed_s = std::move(s.saliency);
    run.attributed_s_device = s.backend_name;
  }
  run.has_attributed_s = true;
  return run.attributed_s;
}

void write_saliency(const std::string& path, const Mesh& mesh, const SaliencyResult& s, bool dump_scales) {
  const std::string format = mesh_output_format(path);
  if (format == ".ply") {
    // SPEC section 4: positions and faces as read, quality = S and its colours; with
    // dump_scales the curvature and raw maps after it.
    std::vector<PlyFloatProperty> props;
    std::vector<std::string> names;
    if (dump_scales) {
      props.push_back({"curvature", &s.curvature});
      for (size_t i = 0; i < s.raw.size(); ++i) names.push_back("saliency_raw_" + std::to_string(i));
      for (const auto& cue : s.cues) names.push_back("cue_" + cue.first);
      for (size_t i = 0; i < s.raw.size(); ++i) props.push_back({names[i], &s.raw[i]});
      for (size_t i = 0; i < s.cues.size(); ++i) props.push_back({names[s.raw.size() + i], &s.cues[i].second});
    }
    return write_saliency_ply(path, mesh, s.saliency, props, s.is_point);
  }
  Mesh with_maps;
  if (dump_scales) {
    with_maps = mesh;
    set_vertex_attribute(with_maps, "curvature", s.curvature);
    for (size_t i = 0; i < s.raw.size(); ++i) set_vertex_attribute(with_maps, "saliency_raw_" + std::to_string(i), s.raw[i]);
    for (const auto& cue : s.cues) set_vertex_attribute(with_maps, "cue_" + cue.first, cue.second);
  }
  const Mesh& written = dump_scales ? with_maps : mesh;
  if (format == ".glb" || format == ".gltf") {
    GltfLevel level;
    level.mesh = &written;
    level.saliency = &s.saliency;
    level.is_point = &s.is_point;
    return write_gltf(path, {level});
  }
  write_mesh(path, written, s.saliency);
}

void write_saliency_output(RequestRun& run) {
  const Request& r = run.request;
  const std::string& path = r.saliency_output;
  const std::string format = mesh_output_format(path);
  if (format == ".ply") {
    plain_saliency(run, false);
    write_saliency(path, *run.plain, run.plain_s, r.dump_scales);
    run.result.outputs.push_back(path);
    run.result.saliency = run.plain_s;
    // The saliency PLY holds the positions and faces as read and S (its colours replace
    // any the input had): what else the input holds is said once.
    std::string left;
    for (const std::string& what : run.plain_report.attributes_not_read)
      if (what != "the saliency" && what != "vertex colours") left += (left.empty() ? "" : ", ") + what;
    if (!run.plain->triangle_material.empty()) left += (left.empty() ? "" : ", ") + std::string("materials");
    if (!left.empty())
      add_note(run, path + " is the saliency PLY (positions, faces and S: SPEC section 4) and does not carry the input's " +
                        left + " (a .glb, .gltf or .obj output carries them)");
    return;
  }
  // The other formats carry the input's attributes and materials, S on that mesh.
  const Mesh& mesh = *run.attributed;
  SaliencyResult s = saliency_of(run, mesh, false);
  if (format == ".glb" || format == ".gltf") {
    write_saliency(path, mesh, s, r.dump_scales);
    run.result.outputs.push_back(path);
    add_note(run, mesh_output_note(path, mesh, true));
  } else {
    // OBJ and OFF: S as colours (the raw maps have no place there: the note says so).
    Mesh with_maps = mesh;
    if (r.dump_scales) {
      set_vertex_attribute(with_maps, "curvature", s.curvature);
      for (size_t i = 0; i < s.raw.size(); ++i) set_vertex_attribute(with_maps, "saliency_raw_" + std::to_string(i), s.raw[i]);
      for (const auto& cue : s.cues) set_vertex_attribute(with_maps, "cue_" + cue.first, cue.second);
    }
    write_request_mesh(run, path, with_maps, s.saliency);
  }
  run.attributed_s = s.saliency;
  run.attributed_s_device = s.backend_name;
  run.has_attributed_s = true;
  run.result.saliency = std::move(s);
}

void view_score(RequestRun& run) {
  const Request& r = run.request;
  if (r.score == Score::Curvature) {
    // |H|, the paper's baseline.
    const Mesh& mesh = *run.plain;
    const Adjacency adj = build_adjacency(mesh);
    const std::vector<double> normals = vertex_normals(mesh);
    std::vector<double> h = mean_curvature(mesh, adj, normals, r.saliency.threads);
    for (double& v : h) v = std::fabs(v);
    run.result.score = std::move(h);
    run.result.saliency_source = "|mean curvature|";
    return;
  }
  plain_saliency(run, false);
  run.result.score = run.plain_s.saliency;
}

}  // namespace meshsal
