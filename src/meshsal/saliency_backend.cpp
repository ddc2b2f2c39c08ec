// compute_saliency(): the backend switch and the option parsing shared by every front end.
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "meshsal/error.h"
#include "meshsal/saliency.h"

namespace meshsal {

SaliencyResult compute_saliency(const Mesh& mesh, const SaliencyOptions& options) {
  switch (options.backend) {
    case Backend::Cpu:
    case Backend::Auto:
      return compute_saliency_cpu(mesh, options);
    case Backend::Gpu:
      throw Error("the GPU backend is not available in this build");
  }
  throw Error("unknown backend");
}

std::vector<double> parse_scales(const std::string& text) {
  std::vector<double> scales;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    double k = std::strtod(item.c_str(), &end);
    if (item.empty() || end == item.c_str() || *end != '\0' || !(k > 0) || !std::isfinite(k))
      throw Error("--scales must be a comma-separated list of positive numbers, got '" + text + "'");
    scales.push_back(k);
  }
  if (scales.empty()) throw Error("--scales must list at least one scale");
  if (scales.size() > 16) throw Error("--scales takes at most 16 scales");
  return scales;
}

}  // namespace meshsal
