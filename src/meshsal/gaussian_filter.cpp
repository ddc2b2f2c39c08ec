#include "meshsal/gaussian_filter.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include "meshsal/error.h"
#include "meshsal/parallel.h"
#include "meshsal/simd_exp.h"
#include "meshsal/spatial_grid.h"

namespace meshsal {

namespace {

constexpr int kMaxSigmas = 32;

// How each sigma's weight is obtained: a sigma that is half of another one has weight
// w(s) = w(2s)^4, so only the "base" sigmas need an exp (default scales: 12, 10, 8 eps).
struct KernelPlan {
  int count = 0;
  int parent[kMaxSigmas];  // -1: exp(-d2 * coef), else w[parent]^4; parents come first
  double coef[kMaxSigmas];  // 1 / (2 s^2)
  double cutoff2[kMaxSigmas];  // (2 s)^2: strict cutoff |x - v| < 2 s
  int slot[kMaxSigmas];  // output index of plan entry
  double radius2 = 0;  // largest cutoff
};

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

// Accumulates, for grid slot i, the weighted sums over all points within the plan's radius.
// Rows of cells outside the ball are culled; inside a row, points are tested 4 at a time
// with branch-free masks (lanes past the range are masked by index).
void sweep_point(const SpatialGrid& g, const double* values, const KernelPlan& plan, size_t i,
                 double* num, double* den, uint64_t* pairs) {
  const double xi = g.x[i], yi = g.y[i], zi = g.z[i];
  const double R2 = plan.radius2, R = std::sqrt(R2);
  const int K = plan.count;
  v4d acc_num[kMaxSigmas], acc_den[kMaxSigmas], w[kMaxSigmas];
  for (int k = 0; k < K; ++k) acc_num[k] = acc_den[k] = v4d_splat(0.0);
  v4d acc_pairs = v4d_splat(0.0);
  const v4d vx = v4d_splat(xi), vy = v4d_splat(yi), vz = v4d_splat(zi), vR2 = v4d_splat(R2);
  const v4d lane = {0, 1, 2, 3};

  const double c = g.cell;
  const int zlo = std::max(0, int(std::floor((zi - R) / c)));
  const int zhi = std::min(g.dims[2] - 1, int(std::floor((zi + R) / c)));
  const int ylo = std::max(0, int(std::floor((yi - R) / c)));
  const int yhi = std::min(g.dims[1] - 1, int(std::floor((yi + R) / c)));
  for (int cz = zlo; cz <= zhi; ++cz) {
    double dz = std::max({0.0, cz * c - zi, zi - (cz + 1) * c});
    for (int cy = ylo; cy <= yhi; ++cy) {
      double dy = std::max({0.0, cy * c - yi, yi - (cy + 1) * c});
      double rest = R2 - dz * dz - dy * dy;
      if (rest <= 0) continue;
      double hx = std::sqrt(rest);
      int xlo = std::max(0, int(std::floor((xi - hx) / c)));
      int xhi = std::min(g.dims[0] - 1, int(std::floor((xi + hx) / c)));
      size_t row = (size_t(cz) * g.dims[1] + cy) * g.dims[0];
      size_t jb = g.cell_start[row + xlo], je = g.cell_start[row + xhi + 1];
      for (size_t j = jb; j < je; j += 4) {
        v4d ex = v4d_load(&g.x[j]) - vx, ey = v4d_load(&g.y[j]) - vy,
            ez = v4d_load(&g.z[j]) - vz;
        v4d d2 = ex * ex + ey * ey + ez * ez;
        d2 = (lane < v4d_splat(double(je - j))) ? d2 : v4d_splat(INFINITY);
        v4d val = v4d_load(&values[j]);
        for (int k = 0; k < K; ++k) {
          if (plan.parent[k] < 0) {
            w[k] = exp_neg(d2 * v4d_splat(plan.coef[k]));
          } else {
            v4d w2 = w[plan.parent[k]] * w[plan.parent[k]];
            w[k] = w2 * w2;
          }
          v4d m = (d2 < v4d_splat(plan.cutoff2[k])) ? w[k] : v4d_splat(0.0);
          acc_num[k] += m * val;
          acc_den[k] += m;
        }
        acc_pairs += (d2 < vR2) ? v4d_splat(1.0) : v4d_splat(0.0);
      }
    }
  }
  for (int k = 0; k < K; ++k) {
    num[k] = (acc_num[k][0] + acc_num[k][1]) + (acc_num[k][2] + acc_num[k][3]);
    den[k] = (acc_den[k][0] + acc_den[k][1]) + (acc_den[k][2] + acc_den[k][3]);
  }
  *pairs += uint64_t(acc_pairs[0] + acc_pairs[1] + acc_pairs[2] + acc_pairs[3]);
}

void check_inputs(const Mesh& mesh, const std::vector<uint8_t>& is_point,
                  const std::vector<double>& values) {
  if (is_point.size() != mesh.vertex_count() || values.size() != mesh.vertex_count())
    throw Error("Gaussian filter: per-vertex arrays do not match the vertex count");
}

}  // namespace

std::vector<std::vector<double>> gaussian_filter(
    const Mesh& mesh, const std::vector<uint8_t>& is_point, const std::vector<double>& values,
    const std::vector<double>& sigmas, unsigned threads, FilterStats* stats,
    const std::function<void(double)>& progress) {
  check_inputs(mesh, is_point, values);
  const KernelPlan plan = make_plan(sigmas);
  const double radius = std::sqrt(plan.radius2);
  // Cells of half the radius: rows are culled tightly against the ball.
  const SpatialGrid g = build_spatial_grid(mesh, is_point, 0.5 * radius);
  const size_t points = g.order.size();
  std::vector<double> sorted_values(points + 4, 0.0);
  for (size_t s = 0; s < points; ++s) sorted_values[s] = values[g.order[s]];

  std::vector<std::vector<double>> out(sigmas.size(), std::vector<double>(mesh.vertex_count(), 0.0));
  std::atomic<uint64_t> total_pairs{0};
  std::atomic<size_t> done{0};
  const std::thread::id caller = std::this_thread::get_id();
  parallel_for(points, threads, 256, [&](size_t begin, size_t end) {
    double num[kMaxSigmas], den[kMaxSigmas];
    uint64_t pairs = 0;
    for (size_t i = begin; i < end; ++i) {
      sweep_point(g, sorted_values.data(), plan, i, num, den, &pairs);
      uint32_t v = g.order[i];
      // den >= 1 always: the point itself is inside every cutoff with weight 1.
      for (int k = 0; k < plan.count; ++k) out[plan.slot[k]][v] = num[k] / den[k];
    }
    total_pairs += pairs;
    size_t finished = done += end - begin;
    if (progress && std::this_thread::get_id() == caller) progress(double(finished) / points);
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
