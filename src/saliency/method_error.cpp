#include "saliency/method_error.h"

#include <algorithm>
#include <cmath>

namespace meshsal {

std::vector<size_t> top_share(const std::vector<double>& values, const std::vector<uint8_t>& is_point,
                              double share) {
  std::vector<size_t> idx;
  for (size_t v = 0; v < values.size(); ++v)
    if (is_point[v]) idx.push_back(v);
  const size_t k = size_t(std::ceil(share * double(idx.size())));
  std::partial_sort(idx.begin(), idx.begin() + std::min(k, idx.size()), idx.end(), [&](size_t a, size_t b) {
    return values[a] != values[b] ? values[a] > values[b] : a < b;
  });
  idx.resize(std::min(k, idx.size()));
  return idx;
}

MethodError method_error(const SaliencyResult& exact, const SaliencyResult& approx) {
  const size_t n = exact.saliency.size();
  if (approx.saliency.size() != n || approx.raw.size() != exact.raw.size() || exact.is_point != approx.is_point)
    throw Error("method error: the two results are not of the same mesh and scales");
  MethodError e;
  // Pearson correlation over the mesh points.
  double se = 0, sa = 0, m = 0;
  for (size_t v = 0; v < n; ++v)
    if (exact.is_point[v]) se += exact.saliency[v], sa += approx.saliency[v], m += 1;
  const double me = se / m, ma = sa / m;
  double cov = 0, ve = 0, va = 0;
  for (size_t v = 0; v < n; ++v) {
    if (!exact.is_point[v]) continue;
    const double de = exact.saliency[v] - me, da = approx.saliency[v] - ma;
    cov += de * da, ve += de * de, va += da * da;
  }
  e.correlation = (ve > 0 && va > 0) ? cov / std::sqrt(ve * va) : (ve == va ? 1.0 : 0.0);

  std::vector<size_t> te = top_share(exact.saliency, exact.is_point, 0.3);
  std::vector<size_t> ta = top_share(approx.saliency, approx.is_point, 0.3);
  std::vector<uint8_t> in_approx(n, 0);
  for (size_t v : ta) in_approx[v] = 1;
  size_t common = 0;
  for (size_t v : te) common += in_approx[v];
  e.top30_overlap = te.empty() ? 1.0 : double(common) / double(te.size());

  for (size_t i = 0; i < exact.raw.size(); ++i) {
    double top = 0, sum = 0, worst = 0;
    for (size_t v = 0; v < n; ++v)
      if (exact.is_point[v]) top = std::max(top, exact.raw[i][v]);
    for (size_t v = 0; v < n; ++v) {
      if (!exact.is_point[v]) continue;
      const double d = std::fabs(approx.raw[i][v] - exact.raw[i][v]) / (top > 0 ? top : 1.0);
      sum += d, worst = std::max(worst, d);
    }
    e.raw_mean.push_back(sum / m);
    e.raw_max.push_back(worst);
  }
  return e;
}

}  // namespace meshsal
