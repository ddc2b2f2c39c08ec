// meshsal: a per-vertex prediction scored against ground truth (SPEC section 7): CC, AUC at
// 20% and 5%, NSS, KLD, SIM (evaluate_scores), and the two files of `meshsal eval` and
// Python's evaluate() read, joined or carried to the same vertices (evaluate_files).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <string>
#include <vector>

#include "core/mesh_points.h"
#include "core/model_frame.h"
#include "core/number_text.h"
#include "core/surface_distance.h"
#include "meshsal/meshsal.h"
#include "saliency/gaussian_filter.h"

namespace meshsal {
namespace {

// AUC-q of p against the top q of g (EvalScores): positives from the (1 - q) quantile of g,
// the Mann-Whitney statistic from the average ranks of p. `rank` holds p's average ranks
// (1-based).
void auc_at(const std::vector<double>& g, const std::vector<double>& sorted_g, const std::vector<double>& rank,
            double q, std::optional<double>& auc, size_t& positives, double& threshold) {
  const size_t n = g.size();
  size_t top = size_t(std::ceil(q * double(n) - 1e-9));
  top = std::min(n, std::max<size_t>(1, top));
  threshold = sorted_g[n - top];
  double rank_sum = 0;
  positives = 0;
  for (size_t i = 0; i < n; ++i)
    if (g[i] >= threshold) ++positives, rank_sum += rank[i];
  const size_t negatives = n - positives;
  if (negatives == 0) return;  // every vertex ties at the top: undefined
  const double P = double(positives), N = double(negatives);
  auc = (rank_sum - P * (P + 1) / 2) / (P * N);
}

// The values made a distribution: shifted by the minimum when it is negative, scaled to
// sum 1; empty when they sum to 0.
std::vector<double> distribution(const std::vector<double>& x) {
  const double lo = *std::min_element(x.begin(), x.end());
  const double shift = lo < 0 ? lo : 0;
  double sum = 0;
  for (double v : x) sum += v - shift;
  if (!(sum > 0)) return {};
  std::vector<double> out(x.size());
  for (size_t i = 0; i < x.size(); ++i) out[i] = (x[i] - shift) / sum;
  return out;
}

}  // namespace

EvalScores evaluate_scores(const std::vector<double>& p, const std::vector<double>& g) {
  if (p.size() != g.size())
    throw Error("the prediction has " + std::to_string(p.size()) + " values and the ground truth " +
                std::to_string(g.size()) + ": they must be of the same vertices");
  const size_t n = p.size();
  if (n < 2) throw Error("scoring needs at least 2 vertices with ground truth, got " + std::to_string(n));
  for (size_t i = 0; i < n; ++i) {
    if (!std::isfinite(p[i])) throw Error("prediction value " + std::to_string(i) + " is " + number_text(p[i], 9));
    if (!std::isfinite(g[i])) throw Error("ground-truth value " + std::to_string(i) + " is " + number_text(g[i], 9));
  }
  EvalScores s;
  s.vertices = n;
  // Means and population standard deviations in double, two passes.
  double mp = 0, mg = 0;
  for (size_t i = 0; i < n; ++i) mp += p[i], mg += g[i];
  mp /= double(n), mg /= double(n);
  double spp = 0, sgg = 0, spg = 0;
  for (size_t i = 0; i < n; ++i) {
    const double a = p[i] - mp, b = g[i] - mg;
    spp += a * a, sgg += b * b, spg += a * b;
  }
  const bool p_constant = !(spp > 0), g_constant = !(sgg > 0);
  if (!p_constant && !g_constant) s.cc = std::max(-1.0, std::min(1.0, spg / std::sqrt(spp * sgg)));
  else s.notes.push_back(std::string("CC undefined: ") + (p_constant ? "the prediction" : "the ground truth") +
                         " is constant (standard deviation 0)");

  // AUC: average ranks of p (ties share the mean of their ranks).
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), size_t(0));
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return p[a] < p[b]; });
  std::vector<double> rank(n);
  for (size_t i = 0; i < n;) {
    size_t j = i;
    while (j < n && p[order[j]] == p[order[i]]) ++j;
    const double r = (double(i + 1) + double(j)) / 2;  // mean of ranks i+1..j
    for (size_t k = i; k < j; ++k) rank[order[k]] = r;
    i = j;
  }
  std::vector<double> sorted_g = g;
  std::sort(sorted_g.begin(), sorted_g.end());
  auc_at(g, sorted_g, rank, 0.20, s.auc_20, s.positives_20, s.threshold_20);
  auc_at(g, sorted_g, rank, 0.05, s.auc_5, s.positives_5, s.threshold_5);
  if (!s.auc_20 || !s.auc_5)
    s.notes.push_back(std::string("AUC") + (!s.auc_20 ? "-20%" : "-5%") + (!s.auc_20 && !s.auc_5 ? " and AUC-5%" : "") +
                      " undefined: every vertex ties at or above the ground truth's quantile (no negatives)");

  // NSS over the vertices with g > 0.
  double nss_sum = 0;
  for (size_t i = 0; i < n; ++i)
    if (g[i] > 0) ++s.nss_vertices, nss_sum += p[i] - mp;
  if (p_constant) s.notes.push_back("NSS undefined: the prediction is constant (standard deviation 0)");
  else if (s.nss_vertices == 0) s.notes.push_back("NSS undefined: no vertex has ground truth above 0");
  else s.nss = nss_sum / double(s.nss_vertices) / std::sqrt(spp / double(n));

  // KLD and SIM of the two as distributions.
  const std::vector<double> P = distribution(p), G = distribution(g);
  if (P.empty() || G.empty()) {
    s.notes.push_back(std::string("KLD and SIM undefined: ") + (P.empty() ? "the prediction" : "the ground truth") +
                      " sums to 0 (after shifting a negative minimum to 0)");
  } else {
    double kld = 0, sim = 0;
    for (size_t i = 0; i < n; ++i) {
      if (G[i] > 0) kld += G[i] * std::log(kEvalEps + G[i] / (kEvalEps + P[i]));
      sim += std::min(P[i], G[i]);
    }
    s.kld = kld;
    s.sim = sim;
  }
  return s;
}

NearestValues transfer_nearest(const std::vector<double>& source_xyz, const std::vector<double>& source_values,
                               const Mesh& target) {
  const size_t m = source_values.size();
  if (source_xyz.size() != 3 * m)
    throw Error("transfer_nearest: " + std::to_string(source_xyz.size()) + " coordinates for " + std::to_string(m) +
                " values (3 per point)");
  if (m == 0) throw Error("transfer_nearest: no source points");
  // The points as degenerate triangles in the target's frame, so the BVH of surface
  // distances finds the nearest one (its index = the triangle's).
  Mesh points;
  points.positions.resize(3 * m);
  points.triangles.resize(3 * m);
  for (size_t i = 0; i < m; ++i) {
    for (int k = 0; k < 3; ++k) points.positions[3 * i + k] = float(source_xyz[3 * i + k] - target.origin[k]);
    points.triangles[3 * i] = points.triangles[3 * i + 1] = points.triangles[3 * i + 2] = uint32_t(i);
  }
  const TriangleBvh bvh = build_triangle_bvh(points);
  NearestValues out;
  const size_t n = target.vertex_count();
  out.values.resize(n);
  double sum = 0;
  for (size_t v = 0; v < n; ++v) {
    const double x[3] = {target.positions[3 * v], target.positions[3 * v + 1], target.positions[3 * v + 2]};
    const ClosestTriangle c = closest_triangle(bvh, x);
    out.values[v] = source_values[c.triangle];
    out.max_distance = std::max(out.max_distance, c.distance);
    sum += c.distance;
  }
  out.mean_distance = n ? sum / double(n) : 0;
  return out;
}

std::vector<double> smooth_vertex_values(const Mesh& mesh, const std::vector<double>& values, double sigma_frac,
                                         unsigned threads) {
  if (!(sigma_frac > 0 && sigma_frac <= 0.5))
    throw Error("the smoothing sigma must be in (0, 0.5] of the bounding-box diagonal, got " + number_text(sigma_frac, 9));
  if (values.size() != mesh.vertex_count())
    throw Error("smoothing: " + std::to_string(values.size()) + " values for a mesh of " +
                std::to_string(mesh.vertex_count()) + " vertices");
  const std::vector<uint8_t> is_point = referenced_vertices(mesh);
  const double sigma = sigma_frac * mesh_points_bbox(mesh, is_point).diagonal();
  std::vector<double> out = gaussian_filter(mesh, is_point, values, {sigma}, threads)[0];
  for (size_t v = 0; v < out.size(); ++v)
    if (!is_point[v]) out[v] = values[v];  // no surface around it: kept
  return out;
}

}  // namespace meshsal
