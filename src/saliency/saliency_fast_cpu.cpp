// The fast method's CPU pipeline (SPEC 5): the stages of compute_saliency_cpu() with the
// averages from cell aggregates, laid out for the largest scans. Beside the exact path
// (saliency_cpu.cpp), which it equals but for the averages and the last bits of H:
//   - no 1-rings: curvature and suppression take their neighbours from the triangles
//     (mean_curvature_faces, suppress_faces), which saves build_adjacency's time and its
//     ~80 bytes per vertex;
//   - one sigma at a time, each freed when its last scale is done, and each scale's raw
//     map suppressed and added to S as soon as it is known, so that without
//     SaliencyOptions::raw_maps one map is held at a time.
#include <cmath>
#include <map>

#include "core/mesh_points.h"
#include "core/parallel.h"
#include "core/stage_clock.h"
#include "core/timer.h"
#include "saliency/curvature.h"
#include "saliency/filter_scope.h"
#include "saliency/gaussian_filter_fast.h"
#include "saliency/saliency.h"
#include "saliency/suppression.h"

namespace meshsal {

std::vector<size_t> fast_scale_order(const std::vector<double>& scales) {
  std::vector<size_t> order;
  std::vector<bool> done(scales.size(), false);
  double held = -1;  // the coarse sigma of the last scale run
  while (order.size() < scales.size()) {
    size_t next = scales.size();
    for (size_t i = 0; i < scales.size() && next == scales.size(); ++i)
      if (!done[i] && scales[i] == held) next = i;
    if (next == scales.size())  // no chain to follow: the smallest scale left
      for (size_t i = 0; i < scales.size(); ++i)
        if (!done[i] && (next == scales.size() || scales[i] < scales[next])) next = i;
    done[next] = true;
    order.push_back(next);
    held = 2 * scales[next];
  }
  return order;
}

SaliencyResult compute_saliency_fast_cpu(const Mesh& mesh, const SaliencyOptions& opt) {
  check_saliency_options(opt);
  SaliencyResult r;
  r.method = Method::Fast;
  r.backend_name = "cpu (" + std::to_string(resolve_threads(opt.threads)) + " threads)";
  auto report = [&](const char* stage, double f) {
    if (opt.progress) opt.progress(stage, f);
  };
  StageClock clock(r.stages);

  r.is_point = referenced_vertices(mesh);
  r.eps = scale_unit(mesh, r.is_point, opt.eps_frac);
  const size_t n = mesh.vertex_count();
  // In Morton order, the same bits as a tile's (mean_curvature_morton).
  // The mesh points' box and count, found once: each sigma's filter call lays its cells
  // over them (a scope without a query mask: every mesh point's average).
  FilterScope whole;
  whole.frame.box = mesh_points_bbox(mesh, r.is_point);
  for (uint8_t f : r.is_point) whole.frame.points += f;
  r.curvature = mean_curvature_morton(mesh, whole.frame.box, opt.threads);
  clock.lap("curvature");

  // Each scale k needs the averages at k and 2k. A sigma is filtered when a scale first
  // needs it and dropped after its last scale. The scales run in chains (a scale whose
  // sigma is held next: 2, 4, then 3, 6, then 5 for the defaults), so that at most two
  // averages are held at a time; S is summed in that order.
  const std::vector<size_t> scale_order = fast_scale_order(opt.scales);
  std::map<double, size_t> last_use;  // sigma unit -> the step of the last scale that needs it
  for (size_t step = 0; step < scale_order.size(); ++step)
    last_use[opt.scales[scale_order[step]]] = last_use[2 * opt.scales[scale_order[step]]] = step;
  const size_t filters = last_use.size();
  std::map<double, std::vector<double>> G;
  size_t filtered = 0;
  double sweep_seconds = 0, cs_seconds = 0, suppress_seconds = 0;
  Timer part;
  auto average = [&](double unit) -> const std::vector<double>& {
    auto it = G.find(unit);
    if (it != G.end()) return it->second;
    FilterStats stats;
    part.restart();
    auto out = gaussian_filter_fast(mesh, r.is_point, r.curvature, {unit * r.eps}, opt.threads, &stats,
                                    [&](double f) { report("gaussian sweep", (double(filtered) + f) / double(filters)); },
                                    {}, &whole);
    sweep_seconds += part.seconds();
    filtered++;
    r.pairs += stats.pairs;
    return G[unit] = std::move(out[0]);
  };
  // S is allocated with the first suppressed map: the finest sigmas, the run's largest
  // cell sets, are filtered before it exists.
  if (opt.raw_maps) r.raw.resize(opt.scales.size());
  for (size_t step = 0; step < scale_order.size(); ++step) {
    const size_t i = scale_order[step];
    const double k = opt.scales[i];
    const std::vector<double>& fine = average(k);
    const std::vector<double>& coarse = average(2 * k);
    part.restart();
    std::vector<double> raw(n);
    parallel_for(n, opt.threads, 1 << 16, [&](size_t begin, size_t end) {
      for (size_t v = begin; v < end; ++v) raw[v] = r.is_point[v] ? std::fabs(fine[v] - coarse[v]) : 0.0;
    });
    for (double unit : {k, 2 * k})
      if (last_use[unit] == step) G.erase(unit);
    cs_seconds += part.seconds();
    part.restart();
    // A raw map not kept is normalised where it lies (8 bytes a vertex less at the peak).
    std::vector<double> s = opt.raw_maps ? suppress_faces(raw, r.is_point, mesh, opt.threads)
                                         : suppress_faces(std::move(raw), r.is_point, mesh, opt.threads);
    if (opt.raw_maps) r.raw[i] = std::move(raw);
    if (step == 0) {
      r.saliency = std::move(s);  // s[v] >= 0, so 0 + s[v] == s[v]: adding to zeros' bits
    } else {
      parallel_for(n, opt.threads, 1 << 16, [&](size_t begin, size_t end) {
        for (size_t v = begin; v < end; ++v) r.saliency[v] += s[v];
      });
    }
    suppress_seconds += part.seconds();
  }
  // The stages as the other paths report them, their times summed over the scales.
  clock.lap("gaussian sweep");
  r.stages.back().seconds = sweep_seconds;
  r.stages.push_back({"center-surround", cs_seconds, r.stages.back().peak_bytes});
  r.stages.push_back({"suppression", suppress_seconds, r.stages.back().peak_bytes});

  if (opt.smoothed) {
    auto Sm = gaussian_filter_fast(mesh, r.is_point, r.saliency, {3.0 * r.eps}, opt.threads, nullptr,
                                   [&](double f) { report("smoothing", f); }, {}, &whole);
    r.smoothed = std::move(Sm[0]);
    clock.lap("smoothing");
  }
  return r;
}

}  // namespace meshsal
