#include "saliency/gaussian_filter.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include "meshsal/meshsal.h"
#include "core/parallel.h"
#include "core/exp_poly7.h"
#include "core/simd_exp.h"
#include "saliency/spatial_grid.h"

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

// Walks the grid rows that intersect the ball of radius sqrt(radius2) around slot i and calls
// block(j, lanes_left) for every 4-wide group of candidate slots; rows of cells outside the
// ball are culled and the x extent of each row is clipped to the ball's chord.
template <class Block>
inline void for_each_candidate_block(const SpatialGrid& g, size_t i, double radius2, Block&& block) {
  for_each_row_in_ball(g, g.x[i], g.y[i], g.z[i], radius2, [&](size_t jb, size_t je) {
    for (size_t j = jb; j < je; j += 4) block(j, double(je - j));
  });
}

// Squared distances from slot i to slots j..j+3; lanes at or past the range end are +inf.
inline v4d block_distance2(const SpatialGrid& g, size_t i, size_t j, double lanes_left) {
  const v4d lane = {0, 1, 2, 3};
  v4d ex = v4d_load(&g.x[j]) - v4d_splat(g.x[i]), ey = v4d_load(&g.y[j]) - v4d_splat(g.y[i]),
      ez = v4d_load(&g.z[j]) - v4d_splat(g.z[i]);
  v4d d2 = ex * ex + ey * ey + ez * ez;
  return (lane < v4d_splat(lanes_left)) ? d2 : v4d_splat(INFINITY);
}

inline double hsum(v4d v) { return (v[0] + v[1]) + (v[2] + v[3]); }

// Any plan: weights by exp for base sigmas and by 4th powers for sigmas with a 2x partner.
void sweep_point_generic(const SpatialGrid& g, const double* values, const KernelPlan& plan,
                         size_t i, double* num, double* den, uint64_t* pairs) {
  const int K = plan.count;
  v4d acc_num[kMaxSigmas], acc_den[kMaxSigmas], w[kMaxSigmas];
  for (int k = 0; k < K; ++k) acc_num[k] = acc_den[k] = v4d_splat(0.0);
  v4d acc_pairs = v4d_splat(0.0);
  for_each_candidate_block(g, i, plan.radius2, [&](size_t j, double left) {
    v4d d2 = block_distance2(g, i, j, left);
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
    acc_pairs += (d2 < v4d_splat(plan.radius2)) ? v4d_splat(1.0) : v4d_splat(0.0);
  });
  for (int k = 0; k < K; ++k) num[k] = hsum(acc_num[k]), den[k] = hsum(acc_den[k]);
  *pairs += uint64_t(hsum(acc_pairs));
}

// The default scales {2,3,4,5,6} need sigmas {2,3,4,5,6,8,10,12} eps. With t = d^2/(2 eps^2)
// every weight exp(-t/k^2) is a power of b = exp(-t/14400) (14400 = lcm of the k^2):
// w12 = b^100, w10 = b^144, w8 = b^225, and w(k) = w(2k)^4 for k = 6, 5, 4, 3, 2.
// Inside the sweep radius t <= 288, so b lies in [exp(-0.02), 1] and a degree-7 Taylor
// polynomial is exact to double precision; the powers lose at most ~4e-13 relative
// (b^3600 for 2 eps), far below what the 1e-9 test against the exp() oracle allows.
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

// exp(-x) for 0 <= x <= 0.02: the degree-7 Taylor polynomial of core/exp_poly7.h
// (truncation < 1e-18).
inline v4d exp_neg_small(v4d x) { return exp_neg_poly7(x); }

void sweep_point_default(const SpatialGrid& g, const double* values, const KernelPlan& plan,
                         size_t i, double* num, double* den, uint64_t* pairs) {
  v4d n[8], d[8];
  for (int k = 0; k < 8; ++k) n[k] = d[k] = v4d_splat(0.0);
  v4d acc_pairs = v4d_splat(0.0);
  const double eps = std::sqrt(1.0 / (2.0 * plan.coef[0])) / 12.0;
  const v4d cb = v4d_splat(1.0 / (2.0 * eps * eps * 14400.0));
  const v4d zero = v4d_splat(0.0), one = v4d_splat(1.0);
  double cut[8];
  for (int k = 0; k < 8; ++k) cut[k] = plan.cutoff2[k];
  auto accumulate = [&](int k, v4d d2, v4d w, v4d val) {
    v4d m = (d2 < v4d_splat(cut[k])) ? w : zero;
    n[k] += m * val;
    d[k] += m;
  };
  for_each_candidate_block(g, i, plan.radius2, [&](size_t j, double left) {
    v4d d2 = block_distance2(g, i, j, left);
    v4d val = v4d_load(&values[j]);
    // Lanes past the sweep radius (or the range end, d2 = inf) get b = 0: no overflow.
    v4d b = (d2 < v4d_splat(cut[0])) ? exp_neg_small(d2 * cb) : zero;
    acc_pairs += (d2 < v4d_splat(cut[0])) ? one : zero;
    v4d b2 = b * b, b4 = b2 * b2, b8 = b4 * b4, b16 = b8 * b8, b32 = b16 * b16,
        b64 = b32 * b32, b128 = b64 * b64;
    v4d w12 = b64 * b32 * b4, w10 = b128 * b16, w8 = b128 * b64 * b32 * b, q;
    accumulate(0, d2, w12, val);
    accumulate(1, d2, w10, val);
    accumulate(2, d2, w8, val);
    q = w12 * w12;
    v4d w6 = q * q;
    accumulate(3, d2, w6, val);
    q = w10 * w10;
    accumulate(4, d2, q * q, val);
    q = w8 * w8;
    v4d w4 = q * q;
    accumulate(5, d2, w4, val);
    q = w6 * w6;
    accumulate(6, d2, q * q, val);
    q = w4 * w4;
    accumulate(7, d2, q * q, val);
  });
  for (int k = 0; k < 8; ++k) num[k] = hsum(n[k]), den[k] = hsum(d[k]);
  *pairs += uint64_t(hsum(acc_pairs));
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
  // Cells of a quarter of the radius: rows clipped to the ball waste ~40% candidates
  // (1.85x pairs with half-radius cells).
  const SpatialGrid g = build_spatial_grid(mesh, is_point, 0.25 * radius);
  const size_t points = g.order.size();
  std::vector<double> sorted_values(points + 4, 0.0);
  for (size_t s = 0; s < points; ++s) sorted_values[s] = values[g.order[s]];

  std::vector<std::vector<double>> out(sigmas.size(), std::vector<double>(mesh.vertex_count(), 0.0));
  std::atomic<uint64_t> total_pairs{0};
  std::atomic<size_t> done{0};
  const std::thread::id caller = std::this_thread::get_id();
  const auto sweep_point = is_default_plan(plan) ? sweep_point_default : sweep_point_generic;
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
