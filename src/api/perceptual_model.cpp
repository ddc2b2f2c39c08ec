// The perceptual model (docs/method.md, "The perceptual model"): where people look at a
// rendered object, from cues computed alone and combined with weights fixed in advance:
//   P = smooth( X * (1 + h + r + c) ), scaled to a maximum of 1,
// X the exposure seen through the centre bias (view/exposure.h), h the height along up,
// r the global rarity and c the paper's saliency an octave coarser (each scaled to a
// maximum of 1), smoothed with the fixation-sized Gaussian (kFixationSigmaFrac).
#include "api/perceptual_model.h"

#include <algorithm>
#include <string>
#include <vector>

#include "api/gpu_backend.h"
#include "core/number_text.h"
#include "core/mesh_points.h"
#include "core/parallel.h"
#include "core/timer.h"
#include "saliency/curvature.h"
#include "saliency/gaussian_filter.h"
#include "saliency/gaussian_filter_fast.h"
#include "saliency/perceptual_cues.h"
#include "view/camera.h"
#include "view/exposure.h"

namespace meshsal {
namespace {

void tell(const SaliencyOptions& options, const std::string& line) {
  if (options.notice) options.notice(line);
}

void progress(const SaliencyOptions& options, const char* stage, double fraction) {
  if (options.progress) options.progress(stage, fraction);
}

// The z-buffers of the exposure: the viewpoint search's rule at a coarser side (the cue is
// a mean over 48 views, not one view's exact edge).
VisibilityOptions exposure_visibility(const SaliencyOptions& options) {
  VisibilityOptions v;
  v.resolution = kExposureResolution;
  v.depth_tol_px = 2.0;
  v.threads = options.threads;
  return v;
}

std::string cpu_name(const SaliencyOptions& options) {
  return "cpu (" + std::to_string(resolve_threads(options.threads)) + " threads)";
}

// Exposure on the backend the options name, as compute_saliency picks one: Cpu; Gpu (an
// error when it fails); Auto (a hardware GPU or the session given, else the CPU; a
// failure falls back to the CPU with a notice).
ExposureRun exposure_on_backend(const Mesh& mesh, const std::vector<float>& normals, const ViewFrame& frame,
                                ExposureWeighting weighting, const SaliencyOptions& options) {
  const std::vector<ViewAngles> views = exposure_views();
  const VisibilityOptions vis = exposure_visibility(options);
  auto on_cpu = [&] { return ExposureRun{exposure_cpu(mesh, normals, frame, views, weighting, vis), cpu_name(options)}; };
  if (options.backend == Backend::Cpu) return on_cpu();
  const GpuBackend* gpu = linked_gpu_backend();
  auto fallback = [&](const std::string& why) {
    if (options.backend == Backend::Gpu) throw Error("exposure on the GPU: " + why);
    tell(options, "auto: the GPU exposure failed (" + why + "), using the CPU");
    return on_cpu();
  };
  if (!gpu || !gpu->exposure) {
    if (options.backend == Backend::Gpu && !gpu) gpu_backend();  // throws the no-Vulkan message
    return options.backend == Backend::Gpu ? fallback("this build has no GPU exposure") : on_cpu();
  }
  try {
    if (options.session) return gpu->exposure_on(session_handle(*options.session), mesh, normals, frame, views, weighting, vis);
    int device = options.device;
    if (device < 0 && options.backend == Backend::Auto) {
      device = pick_hardware_gpu(list_devices());
      if (device < 0) return on_cpu();  // only lavapipe: the CPU is the plain choice
    }
    return gpu->exposure(mesh, normals, frame, views, weighting, vis, device);
  } catch (const Cancelled&) {
    throw;
  } catch (const Error& e) {
    return fallback(e.what());
  }
}

// The Gaussian average of `values` at sigma (model units) by `method` (Exact or Fast); its
// pairs added to *pairs.
std::vector<std::vector<double>> average(const Mesh& mesh, const std::vector<uint8_t>& is_point,
                                         const std::vector<double>& values, const std::vector<double>& sigmas,
                                         Method method, unsigned threads, uint64_t* pairs) {
  FilterStats stats;
  std::vector<std::vector<double>> out =
      method == Method::Fast ? gaussian_filter_fast(mesh, is_point, values, sigmas, threads, &stats)
                             : gaussian_filter(mesh, is_point, values, sigmas, threads, &stats);
  *pairs += stats.pairs;
  return out;
}

// Method::Auto decided as compute_saliency decides it, over the model's widest exact sweep:
// the coarse saliency's (4 x its largest scale x eps) or, for Perceptual, the smoothing's
// (2 x kFixationSigmaFrac x the diagonal), whichever reaches further.
Method decide_method(const Mesh& mesh, const std::vector<uint8_t>& is_point, const BoundingBox& box,
                     const SaliencyOptions& options, const SaliencyOptions& coarse) {
  if (options.method != Method::Auto) return options.method;
  const double eps = options.eps_frac * box.diagonal();
  double radius = 4 * *std::max_element(coarse.scales.begin(), coarse.scales.end()) * eps;
  if (options.model == Model::Perceptual) radius = std::max(radius, 2 * kFixationSigmaFrac * box.diagonal());
  const double pairs = estimate_sweep_pairs(mesh, is_point, radius);
  if (pairs <= kAutoPairBudget) return Method::Exact;
  tell(options, "method auto: the exact sweeps would visit ~" + number_text(pairs) + " neighbour pairs (budget " +
                    number_text(kAutoPairBudget) + "), using the fast method");
  return Method::Fast;
}

}  // namespace

SaliencyResult compute_model_saliency(const Mesh& mesh, const SaliencyOptions& options) {
  validate_mesh(mesh);
  const Model model = options.model;
  const bool all = model == Model::Perceptual;
  SaliencyResult r;
  r.model = model;
  r.is_point = referenced_vertices(mesh);
  const std::vector<uint8_t>& is_point = r.is_point;
  const BoundingBox box = mesh_points_bbox(mesh, is_point);
  r.eps = options.eps_frac * box.diagonal();
  r.backend_name = cpu_name(options);
  const size_t n = mesh.vertex_count();
  Timer clock;
  auto stage_done = [&](const char* name) {
    r.stages.push_back({name, clock.seconds()});
    clock.restart();
  };

  // The method of the averages: the coarse saliency's (Auto decided with its scales).
  SaliencyOptions coarse_options = options;
  coarse_options.model = Model::Lee2005;
  for (double& k : coarse_options.scales) k *= 2;
  coarse_options.raw_maps = false;
  coarse_options.smoothed = false;
  const Method method = decide_method(mesh, is_point, box, options, coarse_options);
  coarse_options.method = method;
  r.method = method;

  // Coarse: the paper's saliency an octave coarser; its curvature serves the rarity too.
  std::vector<double> coarse, curvature;
  if (all || model == Model::Coarse) {
    SaliencyResult c = compute_saliency(mesh, coarse_options);
    for (const StageTime& s : c.stages) r.stages.push_back({"coarse " + s.name, s.seconds, s.peak_bytes});
    coarse = std::move(c.saliency);
    curvature = std::move(c.curvature);
    r.pairs += c.pairs;
    r.backend_name = c.backend_name;
    scale_to_max(coarse, is_point);
    clock.restart();
  }

  // Rarity of the multi-scale curvature descriptor.
  std::vector<double> rarity;
  if (all || model == Model::Rarity) {
    progress(options, "rarity", 0);
    if (curvature.empty()) curvature = mean_curvature_morton(mesh, box, options.threads);
    std::vector<double> sigmas;
    for (double k : rarity_descriptor_scales()) sigmas.push_back(k * r.eps);
    rarity = global_rarity(average(mesh, is_point, curvature, sigmas, method, options.threads, &r.pairs), is_point);
    scale_to_max(rarity, is_point);
    progress(options, "rarity", 1);
    stage_done("rarity");
  }
  // H for every model (--score curvature colours and searches by it).
  r.curvature = curvature.empty() ? mean_curvature_morton(mesh, box, options.threads) : curvature;

  // Height along up.
  ViewFrame frame = frame_mesh(mesh, options.up);
  std::vector<double> height;
  if (all || model == Model::Height) height = height_cue(mesh, is_point, frame.axes[1]);

  // Exposure over the band's views (the centre bias inside each view for Perceptual).
  std::vector<double> exposure;
  if (all || model == Model::Exposure || model == Model::Centre) {
    progress(options, "exposure", 0);
    ExposureWeighting w;
    w.facing = model != Model::Centre;
    w.centre = model != Model::Exposure;
    ExposureRun run = exposure_on_backend(mesh, exposure_normals(mesh, options.threads), frame, w, options);
    exposure = std::move(run.exposure);
    scale_to_max(exposure, is_point);
    if (!all || coarse.empty() || run.backend_name.rfind("vulkan", 0) == 0) r.backend_name = run.backend_name;
    progress(options, "exposure", 1);
    stage_done("exposure");
  }

  if (!all) {
    std::vector<double>& cue = model == Model::Coarse ? coarse : model == Model::Rarity ? rarity
                               : model == Model::Height ? height : exposure;
    r.saliency = cue;
    scale_to_max(r.saliency, is_point);
    r.cues.push_back({model_name(model), std::move(cue)});
  } else {
    std::vector<double> p(n, 0.0);
    for (size_t i = 0; i < n; ++i)
      if (is_point[i]) p[i] = exposure[i] * (1 + height[i] + rarity[i] + coarse[i]);
    progress(options, "smoothing", 0);
    r.saliency =
        average(mesh, is_point, p, {kFixationSigmaFrac * box.diagonal()}, method, options.threads, &r.pairs)[0];
    scale_to_max(r.saliency, is_point);
    progress(options, "smoothing", 1);
    stage_done("smoothing");
    r.cues.push_back({"exposure_centre", std::move(exposure)});
    r.cues.push_back({"height", std::move(height)});
    r.cues.push_back({"rarity", std::move(rarity)});
    r.cues.push_back({"coarse", std::move(coarse)});
  }
  if (options.smoothed) {
    SaliencyOptions so = options;
    so.method = method;
    r.smoothed = smooth_saliency(mesh, r.saliency, so);
  }
  return r;
}

}  // namespace meshsal
