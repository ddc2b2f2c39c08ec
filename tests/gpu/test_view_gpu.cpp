// Viewpoint selection on Vulkan (lavapipe here): GPU visibility against the CPU twin.
#include <algorithm>
#include <cmath>

#include "view/camera.h"
#include "gpu/gpu_visibility.h"
#include "meshsal/meshsal.h"
#include "saliency/saliency.h"
#include "cli/synthetic.h"
#include "view/viewpoint.h"
#include "api/viewpoint_backend.h"
#include "view/visibility.h"
#include "gpu/vk_context.h"
#include "test_util.h"

using namespace meshsal;

namespace {
// Per view |U_gpu - U_cpu| <= rel * U_cpu (and both non-trivial).
void compare_views(const Mesh& mesh, const std::vector<double>& score, int res, int views, double rel,
                   int max_batch = 0, bool gpu_plan = false) {
  vk::Context ctx(-1, true);
  // The lane plan of a GPU (many invocations for small batches), here on any device.
  if (gpu_plan) ctx.info.vk_type = VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU;
  const bool cpu_plan = ctx.info.vk_type == VK_PHYSICAL_DEVICE_TYPE_CPU;
  uint64_t messages = vk::validation_message_count();
  std::vector<float> w = visibility_weights(mesh, score);
  ViewFrame frame = frame_mesh(mesh);
  VisibilityOptions o;
  o.resolution = res;
  std::vector<ViewAngles> dirs = fibonacci_directions(views);
  std::vector<double> cpu = visible_score_cpu(mesh, w, frame, dirs, o);
  GpuVisibility gpu(ctx, mesh, w, frame, o, max_batch);
  std::vector<double> g = gpu.score(dirs);
  REQUIRE(g.size() == cpu.size());
  double total = 0;
  for (float x : w) total += x;
  double worst = 0;
  for (size_t v = 0; v < dirs.size(); ++v) {
    REQUIRE(cpu[v] > 0.05 * total);
    worst = std::max(worst, std::fabs(g[v] - cpu[v]) / cpu[v]);
  }
  INFO("worst relative difference " << worst << " over " << views << " views at " << res << " px");
  CHECK(worst <= rel);
  CHECK(gpu.submissions() == uint64_t((views + gpu.batch() - 1) / gpu.batch()));
  // Reduced on the device: one value per view and work group of 64 invocations.
  uint64_t expected = 0;
  for (int first = 0; first < views; first += gpu.batch()) {
    uint32_t count = uint32_t(std::min(views - first, gpu.batch()));
    expected += count * (visibility_lanes(uint32_t(mesh.vertex_count()), 2048, count, cpu_plan) / 64);
  }
  CHECK(gpu.values_read() == expected);
  CHECK(vk::validation_message_count() == messages);
}
}  // namespace

TEST_CASE("gpu visibility: per-view sums match the CPU twin within 0.5% on three meshes", "[view][gpu]") {
  for (const char* name : {"bunny_3k.off", "spot_3k.obj", "max_planck_5k.obj"}) {
    MESHSAL_MESH_OR_CONTINUE(path, name);
    Mesh mesh = load_mesh(path);
    std::vector<double> sal = compute_saliency_cpu(mesh, SaliencyOptions{}).saliency;
    INFO(name);
    compare_views(mesh, sal, 128, 41, 0.005, 16);  // 3 submissions, the last with a partial view group
  }
}

TEST_CASE("gpu visibility: a GPU's lane plan for small batches matches the CPU twin", "[view][gpu]") {
  for (const char* name : {"bunny_3k.off", "spot_3k.obj"}) {
    MESHSAL_MESH_OR_CONTINUE(path, name);
    Mesh mesh = load_mesh(path);
    std::vector<double> sal = compute_saliency_cpu(mesh, SaliencyOptions{}).saliency;
    INFO(name);
    compare_views(mesh, sal, 128, 41, 0.005, 0, true);  // the optimiser's batch size
  }
}

TEST_CASE("gpu visibility: lanes per view, and enough parallelism for small batches", "[view][gpu]") {
  // CPU devices: ~16 items per invocation, capped, whatever the batch.
  CHECK(visibility_lanes(36000, 2048, 40, true) == 2048);
  CHECK(visibility_lanes(3000, 2048, 40, true) == 192);
  CHECK(visibility_lanes(100, 2048, 1, true) == 64);
  // GPUs: a batch of 40 views gets about a million invocations (the bunny: 26240 a view)...
  CHECK(visibility_lanes(36000, 2048, 40, false) * 40 >= (1u << 20));
  CHECK(visibility_lanes(36000, 2048, 40, false) % 64 == 0);
  // ...but never more than one per item, and a big batch keeps the CPU plan's lanes.
  CHECK(visibility_lanes(3000, 2048, 40, false) == 3008);
  CHECK(visibility_lanes(36000, 2048, 1024, false) == 2048);
}

TEST_CASE("gpu visibility: synthetic meshes, big triangles and every vertex weighted", "[view][gpu]") {
  Mesh cube = make_cube(3);  // few, large triangles: long raster loops per invocation
  compare_views(cube, std::vector<double>(cube.vertex_count(), 1.0), 200, 20, 0.005);
  Mesh sphere = make_sphere(1.0, 4);
  std::vector<double> x(sphere.vertex_count());
  for (size_t i = 0; i < x.size(); ++i) x[i] = 1.0 + sphere.positions[3 * i];
  compare_views(sphere, x, 96, 30, 0.005);
}

TEST_CASE("gpu visibility: the viewpoint scorer on the GPU finds the CPU twin's optimum", "[view][gpu]") {
  Mesh s = make_bumpy_sphere(3);
  std::vector<double> score(s.vertex_count());
  for (size_t i = 0; i < score.size(); ++i) score[i] = std::max(0.0, double(s.positions[3 * i + 1]));  // top
  VisibilityOptions o;
  o.resolution = 64;
  ViewScorerSetup gpu = make_view_scorer(s, score, o, Backend::Gpu);
  ViewScorerSetup cpu = make_view_scorer(s, score, o, Backend::Cpu);
  CHECK(gpu.backend_name.find("vulkan") != std::string::npos);
  OptimiserOptions opt;
  opt.restarts = 3;
  OptimiserResult a = optimise_viewpoint(gpu.scorer, opt);
  OptimiserResult b = optimise_viewpoint(cpu.scorer, opt);
  double da[3], db[3];
  view_direction(a.best, da);
  view_direction(b.best, db);
  CHECK(da[1] > 0.9);  // looks from above
  CHECK(db[1] > 0.9);
  CHECK(a.U == Approx(b.U).epsilon(0.005));
}

TEST_CASE("gpu visibility: lavapipe's loop limit is an error, never silently wrong depths", "[view][gpu]") {
  // Lavapipe ends all loops of an invocation once they have taken 65535 steps in all; a
  // cube's 12 triangles at 512 px need far more per invocation (before this check it
  // returned views with hidden corners counted as visible: 8 instead of 6).
  vk::Context ctx(-1, true);
  if (ctx.info.vk_type != VK_PHYSICAL_DEVICE_TYPE_CPU) {
    meshsal_test::skip_case("not a CPU Vulkan device (no loop limit)");
    return;
  }
  Mesh cube = make_cube(1);
  std::vector<float> w(cube.vertex_count(), 1.0f);
  VisibilityOptions o;
  o.resolution = 512;
  GpuVisibility gpu(ctx, cube, w, frame_mesh(cube), o);
  CHECK_THROWS_WITH(gpu.score(fibonacci_directions(8)),
                    Catch::Contains("65535 loop steps") && Catch::Contains("--backend cpu"));
  // At 64 px the same views are within the limit, and right.
  o.resolution = 64;
  GpuVisibility small(ctx, cube, w, frame_mesh(cube), o);
  std::vector<ViewAngles> dirs = fibonacci_directions(8);
  CHECK(small.score(dirs) == visible_score_cpu(cube, w, frame_mesh(cube), dirs, o));
}
