// compute_saliency(): the backend switch and the option parsing shared by every front end.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "meshsal/meshsal.h"
#include "api/gpu_backend.h"
#include "saliency/saliency.h"

namespace meshsal {

namespace {

void tell(const SaliencyOptions& options, const std::string& line) {
  if (options.notice) options.notice(line);
}

// Auto: a discrete or integrated GPU when there is one (or the --device given), else the
// CPU; no Vulkan at all, or any failure on the GPU, falls back to the CPU with a one-line
// notice.
SaliencyResult compute_auto(const Mesh& mesh, const SaliencyOptions& options) {
  // A build without Vulkan has only the CPU path: the plain choice, not a fallback.
  if (!built_with_vulkan()) return compute_saliency_cpu(mesh, options);
  SaliencyOptions gpu = options;
  if (gpu.device < 0) {
    std::vector<DeviceInfo> devices;
    try {
      devices = list_devices();
    } catch (const Error& e) {
      tell(options, std::string("auto: no Vulkan (") + e.what() + "), using the CPU path");
      return compute_saliency_cpu(mesh, options);
    }
    // Only lavapipe (or no device): the CPU path is the plain choice, not a fallback, so
    // no notice (backend_name says "cpu").
    gpu.device = pick_hardware_gpu(devices);
    if (gpu.device < 0) return compute_saliency_cpu(mesh, options);
  }
  try {
    return gpu_backend().saliency(mesh, gpu);
  } catch (const Error& e) {
    tell(options, std::string("auto: the GPU path failed (") + e.what() + "), using the CPU path");
    return compute_saliency_cpu(mesh, options);
  }
}

std::string number_text(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

}  // namespace

void check_saliency_options(const SaliencyOptions& options) {
  if (!(options.eps_frac > 0 && options.eps_frac <= kMaxEpsFrac))
    throw Error("eps-frac must be a finite number in (0, " + number_text(kMaxEpsFrac) + "], got " +
                number_text(options.eps_frac));
  if (options.scales.empty() || options.scales.size() > 16)
    throw Error("scales: give 1 to 16 scales, got " + std::to_string(options.scales.size()));
  double largest = 0;
  for (double k : options.scales) {
    if (!(k > 0 && k <= kMaxScale))
      throw Error("scales must be finite numbers in (0, " + number_text(kMaxScale) + "], got " + number_text(k));
    largest = std::max(largest, k);
  }
  // The surround Gaussian 2k eps wider than the whole mesh averages everything alike: the
  // center-surround maps would be ~0 (what `--scales 1e300` gave).
  if (2 * largest * options.eps_frac > 1)
    throw Error("scales and eps-frac: the widest surround sigma, 2 x " + number_text(largest) +
                " x " + number_text(options.eps_frac) +
                " of the bounding-box diagonal, must be at most 1 diagonal");
}

SaliencyResult compute_saliency(const Mesh& mesh, const SaliencyOptions& options) {
  check_saliency_options(options);
  switch (options.backend) {
    case Backend::Cpu:
      return compute_saliency_cpu(mesh, options);
    case Backend::Auto:
      return compute_auto(mesh, options);
    case Backend::Gpu:
      return gpu_backend().saliency(mesh, options);
  }
  throw Error("unknown backend");
}

Precision parse_precision(const std::string& name) {
  if (name == "auto") return Precision::Auto;
  if (name == "mixed") return Precision::Mixed;
  if (name == "double") return Precision::Double;
  throw Error("--precision must be auto, mixed or double, got '" + name + "'");
}

std::vector<double> parse_scales(const std::string& text) {
  std::vector<double> scales;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    double k = std::strtod(item.c_str(), &end);
    if (item.empty() || end == item.c_str() || *end != '\0' || !(k > 0 && k <= kMaxScale))
      throw Error("--scales must be a comma-separated list of numbers in (0, 100], got '" + text + "'");
    scales.push_back(k);
  }
  if (scales.empty()) throw Error("--scales must list at least one scale");
  if (scales.size() > 16) throw Error("--scales takes at most 16 scales");
  return scales;
}

}  // namespace meshsal

namespace meshsal {

SaliencyResult compute_saliency(const float* positions, size_t vertex_count,
                                const uint32_t* indices, size_t index_count,
                                const SaliencyOptions& options) {
  return compute_saliency(make_mesh(positions, vertex_count, indices, index_count), options);
}

}  // namespace meshsal
