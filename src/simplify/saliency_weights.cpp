// meshsal: saliency weights for simplification: the paper's threshold curve, the continuous
// and rank curves, and the named presets of --weights.
#include "core/model_frame.h"
#include "simplify/saliency_weights.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "meshsal/meshsal.h"
#include "saliency/gaussian_filter.h"
#include "core/mesh_points.h"
#include "saliency/saliency.h"

namespace meshsal {

double percentile(const std::vector<double>& values, const std::vector<uint8_t>& mask, double p) {
  if (!(p >= 0 && p <= 100))
    throw Error("percentile must be in [0, 100], got " + std::to_string(p));
  std::vector<double> v;
  v.reserve(values.size());
  for (size_t i = 0; i < values.size(); ++i)
    if (mask.empty() || (i < mask.size() && mask[i])) v.push_back(values[i]);
  if (v.empty()) throw Error("percentile of an empty set");
  const double rank = p / 100 * double(v.size() - 1);
  const size_t lo = size_t(std::floor(rank));
  const size_t hi = std::min(lo + 1, v.size() - 1);
  std::nth_element(v.begin(), v.begin() + lo, v.end());
  const double a = v[lo];
  if (hi == lo) return a;
  const double b = *std::min_element(v.begin() + lo + 1, v.end());
  return a + (rank - double(lo)) * (b - a);
}

std::vector<double> smooth_saliency(const Mesh& mesh, const std::vector<double>& saliency,
                                    double eps_frac, unsigned threads) {
  if (saliency.size() != mesh.vertex_count())
    throw Error("saliency has " + std::to_string(saliency.size()) + " values for a mesh of " +
                std::to_string(mesh.vertex_count()) + " vertices");
  if (!(eps_frac > 0 && eps_frac <= kMaxEpsFrac)) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "eps-frac must be a finite number in (0, %g], got %g", kMaxEpsFrac, eps_frac);
    throw Error(buf);
  }
  const std::vector<uint8_t> is_point = referenced_vertices(mesh);
  const double eps = scale_unit(mesh, is_point, eps_frac);
  return gaussian_filter(mesh, is_point, saliency, {3 * eps}, threads)[0];
}

std::vector<double> load_saliency_ply(const std::string& path, const Mesh& mesh) {
  VertexProperties props;
  const Mesh m = load_mesh(path, &props);
  auto it = props.find("quality");
  if (it == props.end())
    throw Error("'" + path + "' has no per-vertex `quality` property (write it with `meshsal saliency`)");
  const size_t n = mesh.vertex_count();
  if (m.vertex_count() != n || it->second.size() != n)
    throw Error("saliency file '" + path + "' has " + std::to_string(m.vertex_count()) +
                " vertices but the mesh has " + std::to_string(n));
  // Same count is not enough: the saliency of another mesh would be silently misapplied.
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (size_t i = 0; i < 3 * n; ++i) {
    lo[i % 3] = std::min(lo[i % 3], double(mesh.positions[i]));
    hi[i % 3] = std::max(hi[i % 3], double(mesh.positions[i]));
  }
  const double diag = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                (hi[2] - lo[2]) * (hi[2] - lo[2]));
  const double tol = 1e-6 * diag;
  // In the model's own coordinates: each file has its own origin.
  for (size_t v = 0; v < n; ++v) {
    double a[3], b[3];
    model_position(m, v, a);
    model_position(mesh, v, b);
    for (int k = 0; k < 3; ++k)
      if (!(std::fabs(a[k] - b[k]) <= tol)) {
        char buf[256];
        std::snprintf(buf, sizeof buf, "vertex %zu is at (%.9g, %.9g, %.9g) there but at (%.9g, %.9g, %.9g) in the mesh",
                      v, a[0], a[1], a[2], b[0], b[1], b[2]);
        throw Error("saliency file '" + path + "' belongs to another mesh: " + buf);
      }
  }
  for (size_t v = 0; v < n; ++v) {
    if (!std::isfinite(it->second[v]))
      throw Error("saliency file '" + path + "': the quality of vertex " + std::to_string(v) + " is not finite");
    if (it->second[v] < 0)  // every command reads S through here: one rule for all of them
      throw Error("saliency file '" + path + "': the quality of vertex " + std::to_string(v) + " is " +
                  std::to_string(it->second[v]) + ", but a saliency is >= 0 (not a file `meshsal saliency` wrote?)");
  }
  return std::vector<double>(it->second.begin(), it->second.end());
}

Weighting parse_weighting(const std::string& name) {
  if (name == "none") return Weighting::None;
  if (name == "saliency") return Weighting::Saliency;
  if (name == "balanced") return Weighting::Balanced;
  throw Error("weights must be 'saliency', 'balanced' or 'none', got '" + name + "'");
}

const char* weighting_name(Weighting weighting) {
  switch (weighting) {
    case Weighting::None: return "none";
    case Weighting::Balanced: return "balanced";
    default: return "saliency";
  }
}

SaliencyWeightOptions weight_preset(Weighting weighting) {
  SaliencyWeightOptions o;  // Saliency and None: the paper's recipe (with the default floor)
  if (weighting == Weighting::Balanced) {
    // Measured (tools/sweep_weights.sh; docs/method.md, "Weightings"): the paper's curve
    // with the threshold at the 50th percentile and lambda 3 instead of 30 and 100. W stays
    // proportional to Sm, which lowered the salient-region error most per unit of RMS error
    // among the curves tried; lambda 100 is what made the paper's recipe 2-3x worse
    // everywhere else.
    o.curve = WeightCurve::Threshold;
    o.alpha_percentile = 50;
    o.lambda = 3;
  }
  return o;
}

namespace {

// Rank of each mesh point's value in [0, 1] (0 the lowest, 1 the highest; ties broken by
// index so that the result does not depend on the sort), 0 for other vertices.
std::vector<double> ranks(const std::vector<double>& values, const std::vector<uint8_t>& is_point) {
  std::vector<uint32_t> idx;
  for (size_t i = 0; i < values.size(); ++i)
    if (is_point[i]) idx.push_back(uint32_t(i));
  std::sort(idx.begin(), idx.end(), [&](uint32_t x, uint32_t y) {
    return values[x] != values[y] ? values[x] < values[y] : x < y;
  });
  std::vector<double> r(values.size(), 0.0);
  const double last = idx.size() > 1 ? double(idx.size() - 1) : 1.0;
  for (size_t k = 0; k < idx.size(); ++k) r[idx[k]] = double(k) / last;
  return r;
}

}  // namespace

void check_weight_options(const SaliencyWeightOptions& options) {
  // Bounded so that W times a quadric stays far from overflow.
  if (!(options.lambda >= 0 && options.lambda <= 1e6))
    throw Error("lambda must be a finite number in [0, 1e+06]");
  if (!(options.floor >= 0 && options.floor <= 100))
    throw Error("weight floor must be a finite number in [0, 100]");
  if (!(options.gamma >= 0 && options.gamma <= 16))
    throw Error("gamma must be a finite number in [0, 16]");
  if (!(options.cap >= 0 && options.cap <= 1e6))
    throw Error("cap must be a finite number in [0, 1e+06]");
}

double curve_weight(double smoothed, double alpha, const SaliencyWeightOptions& options) {
  if (options.curve == WeightCurve::Continuous) {
    // alpha 0 (all saliency 0 up to that percentile): every point above it counts as far
    // above, the cap (if any) bounds it.
    double x = alpha > 0 ? std::pow(smoothed / alpha, options.gamma) : (smoothed > 0 ? HUGE_VAL : 0.0);
    // Bounded like lambda, so that W times a quadric stays far from overflow.
    x = std::min(x, options.cap > 0 ? options.cap : 1e6);
    return 1 + options.lambda * x;
  }
  return smoothed >= alpha ? options.lambda * smoothed : smoothed;  // Threshold
}

double weight_floor(double sum, size_t n, const SaliencyWeightOptions& options) {
  // Sm 0 everywhere (nothing salient at any scale): the mean gives no floor, and plain
  // quadrics (W = 1) are what is left to go by.
  return sum > 0 ? options.floor * sum / double(n) : 1.0;
}

std::vector<double> saliency_weights(const std::vector<double>& smoothed,
                                     const std::vector<uint8_t>& is_point,
                                     const SaliencyWeightOptions& options, double* alpha_out) {
  if (smoothed.size() != is_point.size())
    throw Error("saliency weights: " + std::to_string(smoothed.size()) +
                " saliency values for " + std::to_string(is_point.size()) + " vertices");
  check_weight_options(options);
  for (size_t i = 0; i < smoothed.size(); ++i)
    if (is_point[i] && !(smoothed[i] >= 0 && std::isfinite(smoothed[i])))
      throw Error("saliency must be finite and >= 0 (vertex " + std::to_string(i) + ")");
  const double alpha = percentile(smoothed, is_point, options.alpha_percentile);
  if (alpha_out) *alpha_out = alpha;
  std::vector<double> w(smoothed.size(), 0.0);
  if (options.curve == WeightCurve::Rank) {
    const std::vector<double> r = ranks(smoothed, is_point);
    const double a = options.alpha_percentile / 100, lambda = options.lambda, gamma = options.gamma;
    for (size_t i = 0; i < smoothed.size(); ++i) {
      if (!is_point[i]) continue;
      if (r[i] < a) { w[i] = 1; continue; }
      const double t = a < 1 ? (r[i] - a) / (1 - a) : 1.0;
      w[i] = 1 + lambda * (gamma == 0 ? 1.0 : std::pow(t, gamma));
    }
  } else {
    for (size_t i = 0; i < smoothed.size(); ++i)
      if (is_point[i]) w[i] = curve_weight(smoothed[i], alpha, options);
  }
  double sum = 0;
  size_t n = 0;
  for (size_t i = 0; i < smoothed.size(); ++i)
    if (is_point[i]) sum += w[i], ++n;
  if (options.floor > 0 && n > 0) {
    const double lo = weight_floor(sum, n, options);
    for (size_t i = 0; i < w.size(); ++i)
      if (is_point[i]) w[i] = std::max(w[i], lo);
  }
  return w;
}

}  // namespace meshsal
