// compute_saliency(): the backend switch and the option parsing shared by every front end.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "meshsal/meshsal.h"
#include "core/number_text.h"
#include "core/parallel.h"
#include "core/welded_view.h"
#include "api/gpu_backend.h"
#include "api/perceptual_model.h"
#include "api/resolve_method.h"
#include "core/mesh_points.h"
#include "saliency/gaussian_filter_fast.h"
#include "saliency/saliency.h"
#include "tiles/saliency_tiles.h"
#include "core/cancel.h"

namespace meshsal {

namespace {

void tell(const SaliencyOptions& options, const std::string& line) {
  if (options.notice) options.notice(line);
}

void tell_long_exact_sweep(const Mesh& mesh, const SaliencyOptions& options) {
  if (!options.notice) return;
  if (const std::string note = long_sweep_note(mesh, options); !note.empty()) tell(options, note);
}

SaliencyResult saliency_on_cpu(const Mesh& mesh, const SaliencyOptions& options) {
  tell_long_exact_sweep(mesh, options);
  return compute_saliency_cpu(mesh, options);
}

// Auto: a discrete or integrated GPU when there is one (or the --device given), else the
// CPU; no Vulkan at all, or any failure on the GPU, falls back to the CPU with a one-line
// notice.
SaliencyResult compute_auto(const Mesh& mesh, const SaliencyOptions& options) {
  // A device the caller opened: that one (whatever its type), the CPU only on failure.
  if (options.session) {
    const std::shared_ptr<void> device = session_handle(*options.session);  // closed: an Error, no fallback
    try {
      return gpu_backend().saliency_on(device, mesh, options);
    } catch (const Cancelled&) {
      throw;
    } catch (const Error& e) {
      tell(options, std::string("auto: the GPU path failed (") + e.what() + "), using the CPU path");
      return saliency_on_cpu(mesh, options);
    }
  }
  // A build without Vulkan has only the CPU path: the plain choice, not a fallback.
  if (!built_with_vulkan()) return saliency_on_cpu(mesh, options);
  SaliencyOptions gpu = options;
  if (gpu.device < 0) {
    std::vector<DeviceInfo> devices;
    try {
      devices = list_devices();
    } catch (const Cancelled&) {
      throw;
    } catch (const Error& e) {
      tell(options, std::string("auto: no Vulkan (") + e.what() + "), using the CPU path");
      return saliency_on_cpu(mesh, options);
    }
    // Only lavapipe (or no device): the CPU path is the plain choice, not a fallback, so
    // no notice (backend_name says "cpu").
    gpu.device = pick_hardware_gpu(devices);
    if (gpu.device < 0) return saliency_on_cpu(mesh, options);
  }
  try {
    return gpu_backend().saliency(mesh, gpu);
  } catch (const Cancelled&) {
    throw;  // stopped on purpose: no fallback
  } catch (const Error& e) {
    tell(options, std::string("auto: the GPU path failed (") + e.what() + "), using the CPU path");
    return saliency_on_cpu(mesh, options);
  }
}


// The path options.backend (method resolved) and options.tiles choose.
SaliencyResult run_backend(const Mesh& mesh, const SaliencyOptions& options) {
  if (options.tiles > 1 || options.exchange) {
    // Tiles run on the CPU: the GPU path takes the whole mesh.
    if (options.backend == Backend::Gpu)
      throw Error("tiles run on the CPU: use backend cpu or auto with tiles");
    if (options.session) throw Error("a Vulkan device session was given with tiles, which run on the CPU");
    tell_long_exact_sweep(mesh, options);
    return compute_saliency_tiled(mesh, options);
  }
  // Exact and fast alike: the same device rule (compute_auto) and the same fallback.
  switch (options.backend) {
    case Backend::Cpu:
      if (options.session)
        throw Error("a Vulkan device session was given with the cpu backend: use backend gpu or auto, or no session");
      return saliency_on_cpu(mesh, options);
    case Backend::Auto:
      return compute_auto(mesh, options);
    case Backend::Gpu:
      if (options.session) return gpu_backend().saliency_on(session_handle(*options.session), mesh, options);
      return gpu_backend().saliency(mesh, options);
  }
  throw Error("unknown backend");
}

}  // namespace

SaliencyOptions warm_up_saliency(const SaliencyOptions& options) {
  if (options.backend == Backend::Cpu || options.tiles > 0 || options.session || !linked_gpu_backend())
    return options;
  try {
    SaliencyOptions o = options;
    if (o.backend == Backend::Auto && o.device < 0) {
      o.device = pick_hardware_gpu(list_devices());  // as compute_auto picks
      if (o.device < 0) {                            // the CPU path, as compute_auto takes it
        o.backend = Backend::Cpu;
        return o;
      }
    }
    linked_gpu_backend()->warm_up(o);
    return o;
  } catch (...) {
    // The run itself reports (or falls back): a warm-up only saves time.
    return options;
  }
}

// The exact CPU sweep's rate per thread, measured on a 2-core VM (igea_loop1_537k: 3.5e8
// pairs/s on 2 threads, docs/benchmarks.md): what the long-run note estimates with.
constexpr double kCpuPairsPerThreadSecond = 1.7e8;
// An exact CPU sweep estimated longer than this is said at the start, with the way out.
constexpr double kLongSweepSeconds = 60;

std::string long_sweep_note(const Mesh& mesh, const SaliencyOptions& options) {
  if (options.method != Method::Exact) return "";
  const std::vector<uint8_t> is_point = referenced_vertices(mesh);
  const double eps = scale_unit(mesh, is_point, options.eps_frac);
  const double largest = *std::max_element(options.scales.begin(), options.scales.end());
  const double pairs = estimate_sweep_pairs(mesh, is_point, 4 * largest * eps);
  const unsigned threads = resolve_threads(options.threads);
  const double minutes = pairs / (kCpuPairsPerThreadSecond * threads) / 60;
  if (minutes * 60 < kLongSweepSeconds) return "";
  const bool hours = minutes >= 120;
  const double count = std::round(hours ? minutes / 60 : minutes);
  char cost[64];
  std::snprintf(cost, sizeof cost, "%.0f %s%s", count, hours ? "hour" : "minute", count == 1 ? "" : "s");
  return "note: the exact method will visit ~" + number_text(pairs) + " neighbour pairs here: about " + cost +
         " on " + std::to_string(threads) + " CPU thread" + (threads == 1 ? "" : "s") +
         "; --method fast (or auto) takes time linear in the vertices (its error against exact: docs/method.md)";
}

// Method::Auto: fast when the exact sweep would take more pairs than kAutoPairBudget.
Method resolve_method(const Mesh& mesh, const SaliencyOptions& options) {
  if (options.method != Method::Auto) return options.method;
  validate_mesh(mesh);
  const std::vector<uint8_t> is_point = referenced_vertices(mesh);
  const double eps = scale_unit(mesh, is_point, options.eps_frac);
  const double largest = *std::max_element(options.scales.begin(), options.scales.end());
  const double pairs = estimate_sweep_pairs(mesh, is_point, 4 * largest * eps);
  if (pairs <= kAutoPairBudget) return Method::Exact;
  tell(options, "method auto: the exact sweep would visit ~" + number_text(pairs) +
                    " neighbour pairs (budget " + number_text(kAutoPairBudget) +
                    "), using the fast method");
  return Method::Fast;
}

SaliencyResult compute_saliency(const Mesh& mesh, const SaliencyOptions& options_in) {
  const CancelScope cancel(options_in.cancel);
  // Vertices split at attribute seams: the surface is the position-welded mesh.
  if (!mesh.position_vertex.empty()) {
    check_position_vertex(mesh);
    SaliencyResult r = compute_saliency(position_welded(mesh), options_in);
    copy_to_twins(mesh, r.is_point);
    copy_to_twins(mesh, r.curvature);
    for (std::vector<double>& raw : r.raw) copy_to_twins(mesh, raw);
    copy_to_twins(mesh, r.saliency);
    copy_to_twins(mesh, r.smoothed);
    for (auto& cue : r.cues) copy_to_twins(mesh, cue.second);
    return r;
  }
  check_saliency_options(options_in);
  if (options_in.notice)
    if (const std::string w = precision_warning(mesh); !w.empty()) options_in.notice("warning: " + w);
  // The models other than the paper's (the perceptual model, its cues alone).
  if (options_in.model != Model::Lee2005) return compute_model_saliency(mesh, options_in);
  SaliencyOptions options = options_in;
  options.method = resolve_method(mesh, options_in);
  SaliencyResult r = run_backend(mesh, options);
  // The paths that need the raw maps for S make them; the fast CPU path keeps none.
  if (!options.raw_maps) std::vector<std::vector<double>>().swap(r.raw);
  return r;
}

Method parse_method(const std::string& name) {
  if (name == "exact") return Method::Exact;
  if (name == "fast") return Method::Fast;
  if (name == "auto") return Method::Auto;
  throw Error("method must be exact, fast or auto, got '" + name + "'");
}

Backend parse_backend(const std::string& name) {
  if (name == "auto") return Backend::Auto;
  if (name == "cpu") return Backend::Cpu;
  if (name == "gpu") return Backend::Gpu;
  throw Error("backend must be auto, cpu or gpu, got '" + name + "'");
}

Precision parse_precision(const std::string& name) {
  if (name == "auto") return Precision::Auto;
  if (name == "mixed") return Precision::Mixed;
  if (name == "double") return Precision::Double;
  throw Error("precision must be auto, mixed or double, got '" + name + "'");
}

const char* method_name(Method method) {
  return method == Method::Exact ? "exact" : method == Method::Fast ? "fast" : "auto";
}

const char* backend_name(Backend backend) {
  return backend == Backend::Auto ? "auto" : backend == Backend::Cpu ? "cpu" : "gpu";
}

const char* precision_name(Precision precision) {
  return precision == Precision::Auto ? "auto" : precision == Precision::Mixed ? "mixed" : "double";
}

std::vector<double> parse_scales(const std::string& text) {
  std::vector<double> scales;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    double k = std::strtod(item.c_str(), &end);
    if (item.empty() || end == item.c_str() || *end != '\0' || !(k > 0 && k <= kMaxScale))
      throw Error("scales must be a comma-separated list of numbers in (0, " + number_text(kMaxScale) + "], got '" +
                  text + "'");
    scales.push_back(k);
  }
  if (scales.empty()) throw Error("scales must list at least one scale");
  if (scales.size() > kMaxScaleCount) throw Error("scales: at most " + std::to_string(kMaxScaleCount) + " scales");
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
