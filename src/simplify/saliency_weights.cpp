// meshsal: saliency weights for simplification: the paper's threshold curve, the continuous
// and rank curves, and the named presets of --weights.
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

SaliencyWeights saliency_weights(const std::vector<double>& smoothed, const std::vector<uint8_t>& is_point,
                                 const SaliencyWeightOptions& options) {
  if (smoothed.size() != is_point.size())
    throw Error("saliency weights: " + std::to_string(smoothed.size()) +
                " saliency values for " + std::to_string(is_point.size()) + " vertices");
  check_weight_options(options);
  for (size_t i = 0; i < smoothed.size(); ++i)
    if (is_point[i] && !(smoothed[i] >= 0 && std::isfinite(smoothed[i])))
      throw Error("saliency must be finite and >= 0 (vertex " + std::to_string(i) + ")");
  const double alpha = percentile(smoothed, is_point, options.alpha_percentile);
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
  return {std::move(w), alpha};
}

}  // namespace meshsal
