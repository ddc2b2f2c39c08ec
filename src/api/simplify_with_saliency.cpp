// The paper's simplification pipeline (saliency, Sm = G(S, 3 eps), weights, weighted
// quadric simplification): simplification_weights() for the first three steps, which
// `meshsal simplify` and the simplification benchmark share, and simplify_with_saliency()
// for all four in one call.
#include "core/cancel.h"
#include "core/mesh_points.h"
#include "core/welded_view.h"
#include "api/resolve_method.h"
#include "meshsal/meshsal.h"
#include "saliency/gaussian_filter_fast.h"
#include "saliency/saliency.h"

namespace meshsal {

SimplificationWeights simplification_weights(const Mesh& mesh, const SaliencyWeightOptions& weight_options,
                                             const SaliencyOptions& saliency_options,
                                             const std::vector<double>& saliency) {
  const CancelScope cancel(saliency_options.cancel);
  // Vertices split at attribute seams: weigh the position-welded surface, then copy.
  if (!mesh.position_vertex.empty()) {
    check_position_vertex(mesh);
    SimplificationWeights w = simplification_weights(position_welded(mesh), weight_options, saliency_options, saliency);
    copy_to_twins(mesh, w.weights);
    copy_to_twins(mesh, w.saliency);
    return w;
  }
  SimplificationWeights out;
  std::vector<double> smoothed;
  if (!saliency.empty()) {
    if (saliency.size() != mesh.vertex_count())
      throw Error("saliency has " + std::to_string(saliency.size()) + " values, the mesh has " +
                  std::to_string(mesh.vertex_count()) + " vertices");
    smoothed = smooth_saliency(mesh, saliency, saliency_options);
    out.saliency = saliency;
  } else {
    SaliencyOptions so = saliency_options;
    so.smoothed = true;
    so.raw_maps = false;  // only S and Sm are used
    SaliencyResult r = compute_saliency(mesh, so);
    smoothed = std::move(r.smoothed);
    out.device = r.backend_name;
    out.saliency = std::move(r.saliency);
  }
  SaliencyWeights w = saliency_weights(smoothed, referenced_vertices(mesh), weight_options);
  out.weights = std::move(w.weights);
  out.alpha = w.alpha;
  return out;
}

std::vector<double> smooth_saliency(const Mesh& mesh, const std::vector<double>& saliency,
                                    const SaliencyOptions& options) {
  const CancelScope cancel(options.cancel);
  check_saliency_options(options);
  if (resolve_method(mesh, options) != Method::Fast)
    return smooth_saliency(mesh, saliency, options.eps_frac, options.threads);
  if (saliency.size() != mesh.vertex_count())
    throw Error("saliency has " + std::to_string(saliency.size()) + " values for a mesh of " +
                std::to_string(mesh.vertex_count()) + " vertices");
  const std::vector<uint8_t> is_point = referenced_vertices(mesh);
  const double eps = scale_unit(mesh, is_point, options.eps_frac);
  return gaussian_filter_fast(mesh, is_point, saliency, {3 * eps}, options.threads)[0];
}

Simplified simplify_with_saliency(const Mesh& mesh, const SimplifyOptions& options,
                                  const SaliencyWeightOptions& weight_options,
                                  const SaliencyOptions& saliency_options, const std::vector<double>& saliency) {
  // The whole mesh asked for: no saliency to compute.
  if (simplify_keeps_mesh(options, mesh.triangle_count())) return simplify_mesh(mesh, options);
  const CancelScope cancel(options.cancel ? options.cancel : saliency_options.cancel);
  const SimplificationWeights w = simplification_weights(mesh, weight_options, saliency_options, saliency);
  Simplified r = simplify_mesh(mesh, options, w.weights);
  r.alpha = w.alpha;
  return r;
}

}  // namespace meshsal
