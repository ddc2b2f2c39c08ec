// The CPU reference path of SPEC section 1, stage by stage.
#include <cmath>
#include <set>

#include "core/adjacency.h"
#include "saliency/curvature.h"
#include "meshsal/meshsal.h"
#include "saliency/gaussian_filter.h"
#include "core/mesh_points.h"
#include "core/parallel.h"
#include "saliency/saliency.h"
#include "saliency/suppression.h"
#include "core/stage_clock.h"

namespace meshsal {


// Sigmas of the filter: every scale k and its surround 2k, deduplicated, in eps units.
std::vector<double> filter_sigma_units(const std::vector<double>& scales) {
  std::set<double> s;
  for (double k : scales) {
    s.insert(k);
    s.insert(2 * k);
  }
  return std::vector<double>(s.begin(), s.end());
}

SaliencyResult compute_saliency_cpu(const Mesh& mesh, const SaliencyOptions& opt) {
  check_saliency_options(opt);
  if (opt.method == Method::Auto) throw Error("internal: method auto not resolved");
  if (opt.method == Method::Fast) return compute_saliency_fast_cpu(mesh, opt);
  SaliencyResult r;
  r.method = opt.method;
  r.backend_name = "cpu (" + std::to_string(resolve_threads(opt.threads)) + " threads)";
  // The exact averages (SPEC 1).
  auto filter = [&](const std::vector<double>& values, const std::vector<double>& sigmas,
                    FilterStats* stats, const std::function<void(double)>& progress) {
    return gaussian_filter(mesh, r.is_point, values, sigmas, opt.threads, stats, progress);
  };
  auto report = [&](const char* stage, double f) {
    if (opt.progress) opt.progress(stage, f);
  };
  StageClock clock(r.stages);

  r.is_point = referenced_vertices(mesh);
  r.eps = scale_unit(mesh, r.is_point, opt.eps_frac);
  Adjacency adj = build_adjacency(mesh, opt.threads);
  std::vector<double> normals = vertex_normals(mesh, opt.threads);
  r.curvature = mean_curvature(mesh, adj, normals, opt.threads);
  // Only suppression's 1-ring is needed from here on: free the rest before the averages,
  // the run's largest stage (issue 14: about 300 bytes per vertex in all).
  std::vector<double>().swap(normals);
  std::vector<double>().swap(adj.edge_area);
  clock.lap("curvature");

  // All Gaussian averages of H in one sweep.
  const std::vector<double> units = filter_sigma_units(opt.scales);
  std::vector<double> sigmas;
  for (double u : units) sigmas.push_back(u * r.eps);
  FilterStats stats;
  auto G = filter(r.curvature, sigmas, &stats, [&](double f) { report("gaussian sweep", f); });
  r.pairs = stats.pairs;
  clock.lap("gaussian sweep");

  auto index_of = [&](double unit) {
    for (size_t i = 0; i < units.size(); ++i)
      if (units[i] == unit) return i;
    throw Error("internal: sigma missing from the filter plan");
  };
  const size_t n = mesh.vertex_count();
  r.saliency.assign(n, 0.0);
  for (double k : opt.scales) {
    const std::vector<double>& fine = G[index_of(k)];
    const std::vector<double>& coarse = G[index_of(2 * k)];
    std::vector<double> raw(n, 0.0);
    for (size_t v = 0; v < n; ++v)
      if (r.is_point[v]) raw[v] = std::fabs(fine[v] - coarse[v]);
    r.raw.push_back(std::move(raw));
  }
  std::vector<std::vector<double>>().swap(G);
  clock.lap("center-surround");

  for (const auto& raw : r.raw) {
    std::vector<double> s = suppress(raw, r.is_point, adj);
    for (size_t v = 0; v < n; ++v) r.saliency[v] += s[v];
  }
  clock.lap("suppression");

  if (opt.smoothed) {
    auto Sm = filter(r.saliency, {3.0 * r.eps}, nullptr, [&](double f) { report("smoothing", f); });
    r.smoothed = std::move(Sm[0]);
    clock.lap("smoothing");
  }
  return r;
}

}  // namespace meshsal
