// bench_views: views per second of the visibility score (GPU batch path and CPU twin).
//   bench_views [--views N] [--res 256,512] [--backend gpu|cpu|both] [--device I] [MESH ...]
// Default meshes: ../shared/data/meshes/{bunny_36k.obj,igea_134k.ply.gz}. Every vertex has
// weight 1 (the work does not depend on the values). The GPU is warmed up with one batch
// first (pipeline compile); the relative GPU-CPU difference of U is reported per mesh/res.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "meshsal/meshsal.h"
#include "gpu/gpu_visibility.h"
#include "core/parallel.h"
#include "view/viewpoint.h"
#include "view/visibility.h"
#include "gpu/vk_context.h"
#include "core/timer.h"

using namespace meshsal;

int main(int argc, char** argv) {
  int views = 256, device = -1;
  std::vector<int> resolutions{256, 512};
  std::string backend = "both";
  std::vector<std::string> meshes;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "missing value after %s\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--views") views = std::atoi(next().c_str());
    else if (a == "--device") device = std::atoi(next().c_str());
    else if (a == "--backend") backend = next();
    else if (a == "--res") {
      resolutions.clear();
      std::stringstream ss(next());
      std::string item;
      while (std::getline(ss, item, ',')) resolutions.push_back(std::atoi(item.c_str()));
    } else if (a == "-h" || a == "--help") {
      std::printf("bench_views [--views N] [--res 256,512] [--backend gpu|cpu|both] [--device I] [MESH ...]\n");
      return 0;
    } else meshes.push_back(a);
  }
  if (meshes.empty())
    meshes = {"../shared/data/meshes/bunny_36k.obj", "../shared/data/meshes/igea_134k.ply.gz"};
  if (views < 1) views = 1;
  try {
    std::unique_ptr<vk::Context> ctx;
    if (backend != "cpu") ctx = std::make_unique<vk::Context>(device);
    std::printf("%-28s %8s %8s %5s %-34s %6s %8s %10s %10s\n", "mesh", "V", "T", "res", "backend", "views",
                "seconds", "views/s", "gpu-cpu");
    for (const std::string& path : meshes) {
      Mesh mesh = load_mesh(path);
      std::vector<float> w = visibility_weights(mesh, std::vector<double>(mesh.vertex_count(), 1.0));
      ViewFrame frame = frame_mesh(mesh);
      std::vector<ViewAngles> dirs = fibonacci_directions(views);
      std::string name = path.substr(path.find_last_of('/') + 1);
      for (int res : resolutions) {
        VisibilityOptions o;
        o.resolution = res;
        std::vector<double> gpu_u, cpu_u;
        if (ctx) {
          GpuVisibility gpu(*ctx, mesh, w, frame, o);
          gpu.score(std::vector<ViewAngles>(dirs.begin(), dirs.begin() + std::min<size_t>(dirs.size(), 4)));
          const Timer t0;
          gpu_u = gpu.score(dirs);
          double dt = t0.seconds();
          char label[64];
          std::snprintf(label, sizeof label, "vulkan (batch %d)", gpu.batch());
          std::printf("%-28s %8zu %8zu %5d %-34s %6d %8.3f %10.1f %10s\n", name.c_str(), mesh.vertex_count(),
                      mesh.triangle_count(), res, (std::string(label) + " " + ctx->info.name).substr(0, 34).c_str(),
                      views, dt, views / dt, "");
        }
        if (backend != "gpu") {
          int n = backend == "both" ? std::min(views, 64) : views;
          std::vector<ViewAngles> sub(dirs.begin(), dirs.begin() + n);
          const Timer t0;
          cpu_u = visible_score_cpu(mesh, w, frame, sub, o);
          double dt = t0.seconds();
          double worst = 0;
          for (size_t v = 0; v < cpu_u.size() && v < gpu_u.size(); ++v)
            worst = std::max(worst, std::fabs(gpu_u[v] - cpu_u[v]) / std::max(1e-30, cpu_u[v]));
          char diff[32] = "";
          if (!gpu_u.empty()) std::snprintf(diff, sizeof diff, "%.2e", worst);
          std::printf("%-28s %8zu %8zu %5d %-34s %6d %8.3f %10.1f %10s\n", name.c_str(), mesh.vertex_count(),
                      mesh.triangle_count(), res,
                      ("cpu twin (" + std::to_string(resolve_threads(0)) + " threads)").c_str(), n, dt, n / dt, diff);
        }
        std::fflush(stdout);
      }
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
