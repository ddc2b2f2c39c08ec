// meshsal: mesh saliency (Lee, Varshney, Jacobs 2005) exactly as SPEC section 1 fixes it.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "meshsal/mesh.h"

namespace meshsal {

enum class Backend { Auto, Cpu, Gpu };

// The GPU sweep's arithmetic. Mixed: distances and weights in float, sums folded into
// doubles, cutoffs decided exactly and near ties of the local-maximum test rechecked in
// double (the default sigma set; other plans run in double). Double: all in double.
// Auto: mixed on GPUs (fp64 at 1/2..1/64 of the fp32 rate), double on CPU devices
// (lavapipe), where the double sweep measured faster. The CPU path is always double.
enum class Precision { Auto, Mixed, Double };

struct SaliencyOptions {
  double eps_frac = 0.003;                   // eps = eps_frac * bbox diagonal
  std::vector<double> scales{2, 3, 4, 5, 6};  // s_i = scales[i] * eps
  unsigned threads = 0;                       // CPU threads, 0 = all cores
  Backend backend = Backend::Cpu;             // used by compute_saliency()
  int device = -1;                            // Vulkan device index, -1 = choose
  bool smoothed = false;                      // also compute G(S, 3 eps) (simplification)
  Precision precision = Precision::Auto;      // the GPU sweep's arithmetic
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
  bool mixed_precision = false;           // the GPU sweep ran in mixed precision
  uint64_t rechecked = 0;                 // points a mixed sweep swept again in double
  std::vector<StageTime> stages;          // wall time per stage
  std::string backend_name;               // "cpu (N threads)" or the Vulkan device name
};

// The CPU reference path.
SaliencyResult compute_saliency_cpu(const Mesh& mesh, const SaliencyOptions& options);

// Dispatches on options.backend (Auto: GPU when a discrete/integrated one exists, else CPU).
SaliencyResult compute_saliency(const Mesh& mesh, const SaliencyOptions& options);

// The distinct sigmas (in eps units) the filter needs for these scales: each k and 2k, sorted.
std::vector<double> filter_sigma_units(const std::vector<double>& scales);

// "auto", "mixed" or "double"; throws Error on anything else.
Precision parse_precision(const std::string& name);

// Parses "2,3,4,5,6" into scales; throws Error on anything else (empty, <= 0, junk).
std::vector<double> parse_scales(const std::string& text);

}  // namespace meshsal
