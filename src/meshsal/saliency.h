// meshsal: mesh saliency (Lee, Varshney, Jacobs 2005) exactly as SPEC section 1 fixes it.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "meshsal/mesh.h"

namespace meshsal {

enum class Backend { Auto, Cpu, Gpu };

struct SaliencyOptions {
  double eps_frac = 0.003;                   // eps = eps_frac * bbox diagonal
  std::vector<double> scales{2, 3, 4, 5, 6};  // s_i = scales[i] * eps
  unsigned threads = 0;                       // CPU threads, 0 = all cores
  Backend backend = Backend::Cpu;             // used by compute_saliency()
  int device = -1;                            // Vulkan device index, -1 = choose
  bool smoothed = false;                      // also compute G(S, 3 eps) (simplification)
  // Called with a stage name and the fraction done of that stage (0..1).
  std::function<void(const char* stage, double fraction)> progress;
  // Called once with a one-line notice (e.g. "auto: no GPU, using the CPU path").
  std::function<void(const std::string&)> notice;
};

struct StageTime {
  std::string name;
  double seconds;
};

struct SaliencyResult {
  double eps = 0;
  std::vector<uint8_t> is_point;          // mesh points (referenced vertices)
  std::vector<double> curvature;          // H per vertex
  std::vector<std::vector<double>> raw;   // S_i per scale, per vertex
  std::vector<double> saliency;           // final S per vertex
  std::vector<double> smoothed;           // G(S, 3 eps) when options.smoothed, else empty
  uint64_t pairs = 0;                     // neighbour pairs visited by the sweep
  std::vector<StageTime> stages;          // wall time per stage
  std::string backend_name;               // "cpu (N threads)" or the Vulkan device name
};

// The CPU reference path.
SaliencyResult compute_saliency_cpu(const Mesh& mesh, const SaliencyOptions& options);

// Dispatches on options.backend (Auto: GPU when a discrete/integrated one exists, else CPU).
SaliencyResult compute_saliency(const Mesh& mesh, const SaliencyOptions& options);

// The distinct sigmas (in eps units) the filter needs for these scales: each k and 2k, sorted.
std::vector<double> filter_sigma_units(const std::vector<double>& scales);

// Limits of the options: eps_frac in (0, kMaxEpsFrac], each scale in (0, kMaxScale], and
// 2 x largest scale x eps_frac <= 1 (the widest Gaussian at most the bounding-box diagonal).
constexpr double kMaxEpsFrac = 0.1;
constexpr double kMaxScale = 100;

// Throws Error when options break the limits above (compute_saliency* call it).
void check_saliency_options(const SaliencyOptions& options);

// Parses "2,3,4,5,6" into scales; throws Error on anything else (empty, <= 0, > 100, junk).
std::vector<double> parse_scales(const std::string& text);

}  // namespace meshsal
