// compute_saliency(): the backend switch and the option parsing shared by every front end.
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "meshsal/error.h"
#include "meshsal/gpu_saliency.h"
#include "meshsal/saliency.h"
#include "meshsal/vk_context.h"

namespace meshsal {

namespace {

void tell(const SaliencyOptions& options, const std::string& line) {
  if (options.notice) options.notice(line);
}

// Auto: a discrete or integrated GPU when there is one (or the --device given), else the
// CPU; no Vulkan at all, or any failure on the GPU, falls back to the CPU with a one-line
// notice.
SaliencyResult compute_auto(const Mesh& mesh, const SaliencyOptions& options) {
  SaliencyOptions gpu = options;
  if (gpu.device < 0) {
    std::vector<vk::DeviceInfo> devices;
    try {
      devices = vk::list_devices();
    } catch (const Error& e) {
      tell(options, std::string("auto: no Vulkan (") + e.what() + "), using the CPU path");
      return compute_saliency_cpu(mesh, options);
    }
    // Only lavapipe (or no device): the CPU path is the plain choice, not a fallback, so
    // no notice (backend_name says "cpu").
    gpu.device = vk::pick_hardware_gpu(devices);
    if (gpu.device < 0) return compute_saliency_cpu(mesh, options);
  }
  try {
    return compute_saliency_gpu(mesh, gpu);
  } catch (const Error& e) {
    tell(options, std::string("auto: the GPU path failed (") + e.what() + "), using the CPU path");
    return compute_saliency_cpu(mesh, options);
  }
}

}  // namespace

SaliencyResult compute_saliency(const Mesh& mesh, const SaliencyOptions& options) {
  switch (options.backend) {
    case Backend::Cpu:
      return compute_saliency_cpu(mesh, options);
    case Backend::Auto:
      return compute_auto(mesh, options);
    case Backend::Gpu:
      return compute_saliency_gpu(mesh, options);
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
    if (item.empty() || end == item.c_str() || *end != '\0' || !(k > 0) || !std::isfinite(k))
      throw Error("--scales must be a comma-separated list of positive numbers, got '" + text + "'");
    scales.push_back(k);
  }
  if (scales.empty()) throw Error("--scales must list at least one scale");
  if (scales.size() > 16) throw Error("--scales takes at most 16 scales");
  return scales;
}

}  // namespace meshsal
