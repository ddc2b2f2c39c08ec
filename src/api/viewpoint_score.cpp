#include "api/viewpoint_score.h"

#include <cmath>

#include "core/adjacency.h"
#include "saliency/curvature.h"
#include "meshsal/meshsal.h"

namespace meshsal {

ViewScore parse_view_score(const std::string& text) {
  if (text == "saliency") return ViewScore::Saliency;
  if (text == "curvature") return ViewScore::Curvature;
  throw Error("--score must be saliency or curvature, got '" + text + "'");
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
    VertexProperties props;
    Mesh other = load_mesh(saliency_from, &props);
    auto it = props.find("quality");
    if (it == props.end())
      throw Error(saliency_from + " has no vertex property 'quality' (write it with `meshsal saliency`)");
    if (it->second.size() != mesh.vertex_count())
      throw Error(saliency_from + " has " + std::to_string(it->second.size()) + " vertices, the mesh has " +
                  std::to_string(mesh.vertex_count()));
    std::vector<double> s(it->second.begin(), it->second.end());
    for (double v : s)
      if (!std::isfinite(v)) throw Error(saliency_from + " has a quality value that is not finite");
    if (source) *source = saliency_from;
    return s;
  }
  SaliencyResult r = compute_saliency(mesh, options);
  if (source) *source = "computed (" + r.backend_name + ")";
  return r.saliency;
}

}  // namespace meshsal
