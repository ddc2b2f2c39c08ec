// simplify_with_saliency(): the paper's pipeline in one call (saliency, Sm = G(S, 3 eps),
// weights, weighted quadric simplification), shared by `meshsal simplify`, the demo and the
// simplification benchmark.
#include "core/mesh_points.h"
#include "meshsal/meshsal.h"

namespace meshsal {

Mesh simplify_with_saliency(const Mesh& mesh, const SimplifyOptions& options,
                            const SaliencyWeightOptions& weight_options,
                            const SaliencyOptions& saliency_options,
                            const std::vector<double>* saliency, SimplifyReport* report,
                            double* alpha_out) {
  std::vector<double> smoothed;
  if (saliency) {
    if (saliency->size() != mesh.vertex_count())
      throw Error("saliency has " + std::to_string(saliency->size()) + " values, the mesh has " +
                  std::to_string(mesh.vertex_count()) + " vertices");
    smoothed = smooth_saliency(mesh, *saliency, saliency_options.eps_frac, saliency_options.threads);
  } else {
    SaliencyOptions so = saliency_options;
    so.smoothed = true;
    smoothed = compute_saliency(mesh, so).smoothed;
  }
  const std::vector<double> weights =
      saliency_weights(smoothed, referenced_vertices(mesh), weight_options, alpha_out);
  return simplify_mesh(mesh, options, &weights, report);
}

}  // namespace meshsal
