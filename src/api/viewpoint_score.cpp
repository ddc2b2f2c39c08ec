#include "api/viewpoint_score.h"

#include <cmath>

#include "core/adjacency.h"
#include "saliency/curvature.h"
#include "meshsal/meshsal.h"
#include "simplify/saliency_weights.h"

namespace meshsal {

ViewScore parse_view_score(const std::string& text) {
  if (text == "saliency") return ViewScore::Saliency;
  if (text == "curvature") return ViewScore::Curvature;
  throw Error("score must be saliency or curvature, got '" + text + "'");
}

std::vector<double> vertex_score(const Mesh& mesh, ViewScore kind, const std::string& saliency_from,
                                 const SaliencyOptions& options, std::string* source) {
  if (kind == ViewScore::Curvature) {
    Adjacency adj = build_adjacency(mesh);
    std::vector<double> normals = vertex_normals(mesh);
    std::vector<double> h = mean_curvature(mesh, adj, normals, options.threads);
    for (double& v : h) v = std::fabs(v);
    if (source) *source = "|mean curvature|";
    return h;
  }
  if (!saliency_from.empty()) {
    std::vector<double> s = load_saliency_ply(saliency_from, mesh);
    if (source) *source = saliency_from;
    return s;
  }
  SaliencyOptions so = options;
  so.raw_maps = false;  // only S is scored
  SaliencyResult r = compute_saliency(mesh, so);
  if (source) *source = "computed (" + r.backend_name + ")";
  return r.saliency;
}

}  // namespace meshsal
