#include "meshsal/viewpoint_backend.h"

#include "meshsal/error.h"
#include "meshsal/gpu_visibility.h"
#include "meshsal/parallel.h"
#include "meshsal/vk_context.h"

namespace meshsal {

static ViewScorerSetup cpu_scorer(const Mesh& mesh, const std::vector<double>& score,
                                  const VisibilityOptions& options) {
  auto weights = std::make_shared<std::vector<float>>(visibility_weights(mesh, score));
  ViewFrame frame = frame_mesh(mesh);
  ViewScorerSetup s;
  s.keep_alive = weights;
  const Mesh* m = &mesh;
  s.scorer = [m, weights, frame, options](const std::vector<ViewAngles>& views) {
    return visible_score_cpu(*m, *weights, frame, views, options);
  };
  s.backend_name = "cpu (" + std::to_string(resolve_threads(options.threads)) + " threads)";
  s.batch = 64;
  return s;
}

static ViewScorerSetup gpu_scorer(const Mesh& mesh, const std::vector<double>& score,
                                  const VisibilityOptions& options, int device) {
  struct Gpu {
    std::unique_ptr<vk::Context> ctx;
    std::unique_ptr<GpuVisibility> vis;
  };
  auto g = std::make_shared<Gpu>();
  g->ctx = std::make_unique<vk::Context>(device, vk::validation_requested_by_env());
  g->vis = std::make_unique<GpuVisibility>(*g->ctx, mesh, visibility_weights(mesh, score), frame_mesh(mesh),
                                           options);
  ViewScorerSetup s;
  GpuVisibility* vis = g->vis.get();
  s.scorer = [vis](const std::vector<ViewAngles>& views) { return vis->score(views); };
  s.backend_name = "vulkan: " + g->ctx->info.name;
  s.batch = vis->batch();
  s.keep_alive = g;
  return s;
}

ViewScorerSetup make_view_scorer(const Mesh& mesh, const std::vector<double>& score,
                                 const VisibilityOptions& options, Backend backend, int device,
                                 const std::function<void(const std::string&)>& notice) {
  check_visibility_options(options);
  if (backend == Backend::Gpu) return gpu_scorer(mesh, score, options, device);
  if (backend == Backend::Auto) {
    int hw = -1;
    try {
      hw = vk::pick_hardware_gpu(vk::list_devices());
    } catch (const Error&) {
      hw = -1;  // no Vulkan driver at all
    }
    if (hw >= 0) return gpu_scorer(mesh, score, options, device >= 0 ? device : hw);
    if (notice) notice("auto: no hardware GPU, visibility on the CPU twin (--backend gpu uses any Vulkan device)");
  }
  return cpu_scorer(mesh, score, options);
}

}  // namespace meshsal
