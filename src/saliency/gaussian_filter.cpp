#include "saliency/gaussian_filter.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include "meshsal/meshsal.h"
#include "core/parallel.h"
#include "saliency/spatial_grid.h"
#include "saliency/sweep_kernels.h"

namespace meshsal {

namespace {

using sweep::KernelPlan;
using sweep::kMaxSigmas;

KernelPlan make_plan(const std::vector<double>& sigmas) {
  if (sigmas.empty() || sigmas.size() > size_t(kMaxSigmas))
    throw Error("Gaussian filter needs 1 to 32 sigmas");
  for (double s : sigmas)
    if (!(s > 0) || !std::isfinite(s)) throw Error("Gaussian filter sigma must be positive");
  // Process sigmas from largest to smallest so a parent (2s) always precedes its child (s).
  std::vector<int> idx(sigmas.size());
  for (size_t i = 0; i < idx.size(); ++i) idx[i] = int(i);
  std::stable_sort(idx.begin(), idx.end(), [&](int a, int b) { return sigmas[a] > sigmas[b]; });
  KernelPlan plan;
  plan.count = int(idx.size());
  for (int e = 0; e < plan.count; ++e) {
    double s = sigmas[idx[e]];
    plan.slot[e] = idx[e];
    plan.coef[e] = 1.0 / (2.0 * s * s);
    plan.cutoff2[e] = 4.0 * s * s;
    plan.radius2 = std::max(plan.radius2, plan.cutoff2[e]);
    plan.parent[e] = -1;
    for (int q = 0; q < e; ++q)
      if (std::fabs(sigmas[idx[q]] - 2.0 * s) <= 1e-12 * s) {
        plan.parent[e] = q;
        break;
      }
  }
  return plan;
}

// The default scales {2,3,4,5,6} need sigmas {2,3,4,5,6,8,10,12} eps: a fixed plan with
// all weights powers of one exp (sweep_point_default() in sweep_kernels.inc).
bool is_default_plan(const KernelPlan& plan) {
  static const double units[8] = {12, 10, 8, 6, 5, 4, 3, 2};
  if (plan.count != 8) return false;
  const double eps = std::sqrt(1.0 / (2.0 * plan.coef[0])) / 12.0;
  for (int k = 0; k < 8; ++k) {
    const double s = std::sqrt(1.0 / (2.0 * plan.coef[k]));
    if (std::fabs(s - units[k] * eps) > 1e-12 * s) return false;
  }
  return true;
}

void check_inputs(const Mesh& mesh, const std::vector<uint8_t>& is_point,
                  const std::vector<double>& values) {
  if (is_point.size() != mesh.vertex_count() || values.size() != mesh.vertex_count())
    throw Error("Gaussian filter: per-vertex arrays do not match the vertex count");
}

}  // namespace

double sweep_grid_cell(const std::vector<double>& sigmas, const GridFrame& frame) {
  const KernelPlan plan = make_plan(sigmas);
  double extent[3];
  for (int a = 0; a < 3; ++a) extent[a] = frame.box.max[a] - frame.box.min[a];
  return grid_cell_size(extent, 0.25 * std::sqrt(plan.radius2), frame.points);
}

std::vector<std::vector<double>> gaussian_filter(
    const Mesh& mesh, const std::vector<uint8_t>& is_point, const std::vector<double>& values,
    const std::vector<double>& sigmas, unsigned threads, FilterStats* stats,
    const std::function<void(double)>& progress, const FilterScope* scope) {
  check_inputs(mesh, is_point, values);
  const KernelPlan plan = make_plan(sigmas);
  const double radius = std::sqrt(plan.radius2);
  // Cells of a quarter of the radius: rows clipped to the ball waste ~40% candidates
  // (1.85x pairs with half-radius cells).
  const SpatialGrid g = build_spatial_grid(mesh, is_point, 0.25 * radius, scope ? &scope->frame : nullptr);
  const size_t points = g.order.size();
  std::vector<double> sorted_values(points + 4, 0.0);
  for (size_t s = 0; s < points; ++s) sorted_values[s] = values[g.order[s]];
  // The sorted slots to sweep: all, or (a tile) those of the query vertices, as runs of
  // consecutive slots so the hot loop stays the same.
  std::vector<std::pair<size_t, size_t>> runs;
  if (scope && scope->query) {
    for (size_t s = 0; s < points; ++s) {
      if (!(*scope->query)[g.order[s]]) continue;
      if (!runs.empty() && runs.back().second == s)
        runs.back().second++;
      else
        runs.push_back({s, s + 1});
    }
  } else if (points > 0) {
    runs.push_back({0, points});
  }
  std::vector<size_t> run_first(runs.size() + 1, 0);  // queries before each run
  for (size_t r = 0; r < runs.size(); ++r)
    run_first[r + 1] = run_first[r] + (runs[r].second - runs[r].first);
  const size_t queries = run_first.back();

  std::vector<std::vector<double>> out(sigmas.size(), std::vector<double>(mesh.vertex_count(), 0.0));
  std::atomic<uint64_t> total_pairs{0};
  std::atomic<size_t> done{0};
  const std::thread::id caller = std::this_thread::get_id();
  std::vector<double*> out_slot(sigmas.size());
  for (size_t k = 0; k < sigmas.size(); ++k) out_slot[k] = out[k].data();
  const sweep::SweepArgs args{&g, sorted_values.data(), &plan, out_slot.data()};
  // The hot loop, on the instruction set cpu_path() picks (sweep_kernels.h).
  const auto sweep_range = is_default_plan(plan) ? sweep::kernels().sweep_default
                                                 : sweep::kernels().sweep_generic;
  parallel_for(queries, threads, 256, [&](size_t begin, size_t end) {
    uint64_t pairs = 0;
    // Queries [begin, end) as pieces of runs.
    size_t r = size_t(std::upper_bound(run_first.begin(), run_first.end(), begin) - run_first.begin()) - 1;
    for (size_t q = begin; q < end; ++r) {
      const size_t take = std::min(end, run_first[r + 1]) - q;
      const size_t first = runs[r].first + (q - run_first[r]);
      sweep_range(args, first, first + take, &pairs);
      q += take;
    }
    total_pairs += pairs;
    size_t finished = done += end - begin;
    if (progress && std::this_thread::get_id() == caller) progress(double(finished) / queries);
  });
  if (stats) stats->pairs = total_pairs;
  return out;
}

std::vector<std::vector<double>> gaussian_filter_bruteforce(
    const Mesh& mesh, const std::vector<uint8_t>& is_point, const std::vector<double>& values,
    const std::vector<double>& sigmas) {
  check_inputs(mesh, is_point, values);
  const size_t n = mesh.vertex_count();
  const float* p = mesh.positions.data();
  std::vector<std::vector<double>> out(sigmas.size(), std::vector<double>(n, 0.0));
  for (size_t k = 0; k < sigmas.size(); ++k) {
    const double s = sigmas[k];
    for (size_t v = 0; v < n; ++v) {
      if (!is_point[v]) continue;
      double num = 0, den = 0;
      for (size_t x = 0; x < n; ++x) {
        if (!is_point[x]) continue;
        double dx = double(p[3 * x]) - p[3 * v], dy = double(p[3 * x + 1]) - p[3 * v + 1],
               dz = double(p[3 * x + 2]) - p[3 * v + 2];
        double d2 = dx * dx + dy * dy + dz * dz;
        if (!(std::sqrt(d2) < 2 * s)) continue;
        double w = std::exp(-d2 / (2 * s * s));
        num += values[x] * w;
        den += w;
      }
      out[k][v] = num / den;
    }
  }
  return out;
}

}  // namespace meshsal
