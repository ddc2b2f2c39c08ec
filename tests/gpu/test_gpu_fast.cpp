// --method fast on the Vulkan path against its CPU twin (gaussian_filter_fast), on
// lavapipe in CI with the Khronos validation layer on: every raw map, the final saliency
// and the smoothed saliency must agree per vertex to 1e-4 of the map's maximum, the
// (query, cell) pair counts must agree, and the layer must report nothing.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include "cli/synthetic.h"
#include "core/mesh_points.h"
#include "gpu/gpu_fast.h"
#include "saliency/gaussian_filter_fast.h"
#include "gpu/vk_compute.h"
#include "gpu/gpu_fast_cells.h"
#include "gpu/gpu_saliency.h"
#include "gpu/vk_context.h"
#include "meshsal/meshsal.h"
#include "saliency/saliency.h"
#include "cli_run.h"
#include "test_util.h"

using namespace meshsal;

using meshsal_test::CliRun;
using meshsal_test::read_file;
using meshsal_test::run_cli;

using meshsal_test::check_maps_match;
using meshsal_test::rel_error;

namespace {

// One validated context for the whole file (the pipelines compile once).
vk::Context& context() {
  static std::unique_ptr<vk::Context> ctx = std::make_unique<vk::Context>(-1, true);
  return *ctx;
}

SaliencyOptions fast_options() {
  SaliencyOptions opt;
  opt.method = Method::Fast;
  opt.threads = 2;
  opt.smoothed = true;
  return opt;
}

// The GPU fast path against the CPU fast path on `ctx`; returns the GPU result. s_tol: for
// S and Sm (default 1e-4, as the raw maps).
SaliencyResult compare(vk::Context& ctx, const Mesh& mesh, const SaliencyOptions& opt,
                       const std::string& what, double s_tol = 1e-4) {
  INFO(what);
  const uint64_t before = vk::validation_message_count();
  SaliencyResult cpu = compute_saliency_cpu(mesh, opt);
  SaliencyResult gpu = compute_saliency_gpu(ctx, mesh, opt);
  CHECK(vk::validation_message_count() == before);
  CHECK(gpu.backend_name == ctx.info.name);
  CHECK(gpu.method == Method::Fast);
  CHECK(!gpu.mixed_precision);
  CHECK(gpu.eps == cpu.eps);
  check_maps_match(cpu, gpu, opt.scales, 1e-4, s_tol);
  // (query, cell) pairs: the same cells within the same strict cutoffs.
  CHECK(cpu.pairs > mesh.vertex_count());
  CHECK(gpu.pairs == cpu.pairs);
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    if (!cpu.is_point[v]) {
      CHECK(gpu.saliency[v] == 0);
      CHECK(gpu.smoothed[v] == 0);
    }
  return gpu;
}

// Symmetric meshes have exact ties between neighbours, where the strict local-maximum
// test depends on the last bits of any sum; a tiny deterministic jitter breaks them.
Mesh jitter(Mesh mesh) {
  for (size_t i = 0; i < mesh.positions.size(); ++i)
    mesh.positions[i] += 1e-4f * float(std::sin(12.9898 * double(i)));
  return mesh;
}

}  // namespace

TEST_CASE("gpu fast matches the cpu fast path on synthetic meshes", "[gpu][fast]") {
  const SaliencyOptions opt = fast_options();
  compare(context(), make_bumpy_sphere(4), opt, "bumpy sphere");
  compare(context(), jitter(make_plane_with_bump(2.0, 60, 0.3, 0.2)), opt, "jittered plane with bump");
  compare(context(), jitter(make_cube(16)), opt, "jittered cube");
  Mesh loose = make_bumpy_sphere(3);
  loose.positions.insert(loose.positions.end(), {0.1f, 0.2f, 0.3f, 5.0f, 5.0f, 5.0f});
  compare(context(), loose, opt, "bumpy sphere plus two loose vertices");
}

TEST_CASE("gpu fast: sphere raw maps stay near zero, as on the cpu", "[gpu][fast]") {
  SaliencyOptions opt = fast_options();
  const Mesh sphere = make_sphere(1.0, 4);
  SaliencyResult cpu = compute_saliency_cpu(sphere, opt);
  SaliencyResult gpu = compute_saliency_gpu(context(), sphere, opt);
  for (size_t i = 0; i < gpu.raw.size(); ++i) {
    INFO("raw map " << i);
    // |H| = 1 on the unit sphere: the raw maps are differences of averages of ~1.
    CHECK(*std::max_element(gpu.raw[i].begin(), gpu.raw[i].end()) < 0.02);
    CHECK(rel_error(cpu.raw[i], gpu.raw[i]) <= 1e-4);
  }
}

TEST_CASE("gpu fast matches the cpu with other scales and eps", "[gpu][fast]") {
  SaliencyOptions opt = fast_options();
  opt.scales = {1.5, 3, 7};
  opt.eps_frac = 0.005;
  compare(context(), make_bumpy_sphere(3), opt, "bumpy sphere, scales 1.5,3,7");
  opt.scales = {2};
  opt.eps_frac = 0.01;
  compare(context(), make_plane_with_bump(2.0, 40, 0.3, 0.2), opt, "plane, one scale");
}

TEST_CASE("gpu fast: dense cells, queried per group of cells, match the cpu", "[gpu][fast]") {
  // eps_frac 0.01 on a fine sphere: cells of the larger sigmas hold ~10 points, so those
  // sigmas take the sums once per query group (a pair per group and cell, fewer pairs than
  // the points times the sigmas), with the cutoff's shell in the gradients.
  SaliencyOptions opt = fast_options();
  opt.eps_frac = 0.01;
  const Mesh m = jitter(make_bumpy_sphere(5));
  const SaliencyResult gpu = compare(context(), m, opt, "bumpy sphere, dense cells");
  // The same sigmas per vertex everywhere count more pairs: some sigmas were dense.
  const std::vector<uint8_t> is_point = referenced_vertices(m);
  std::vector<double> sigmas;
  for (double k : {2, 3, 4, 5, 6, 8, 10, 12}) sigmas.push_back(k * gpu.eps);
  FastFilterParams per_vertex;
  per_vertex.points_per_query_cell = INFINITY;
  FilterStats stats;
  gaussian_filter_fast(m, is_point, std::vector<double>(m.vertex_count(), 1.0), sigmas, 0, &stats, {},
                       per_vertex);
  CHECK(double(gpu.pairs) < 0.8 * double(stats.pairs));  // measured 0.63
}

TEST_CASE("gpu fast: candidates split into many windows give the same sums", "[gpu][fast]") {
  // Lavapipe ends an invocation's loops after 65,535 steps, so a query's candidates are
  // walked in windows of at most Context::fast_window_candidates, one dispatch each; a tiny
  // window splits every query of a small mesh into many (rows cut mid-way).
  const SaliencyOptions opt = fast_options();
  const Mesh mesh = make_bumpy_sphere(4);
  uint64_t submissions = vk::host_barriers_recorded;  // every submission ends with one
  SaliencyResult one = compute_saliency_gpu(context(), mesh, opt);
  const uint64_t one_submissions = vk::host_barriers_recorded - submissions;
  vk::Context small(-1, true);
  small.fast_window_candidates = 7;
  submissions = vk::host_barriers_recorded;
  SaliencyResult many = compare(small, mesh, opt, "windows of 7 candidates");
  const uint64_t many_submissions = vk::host_barriers_recorded - submissions;
  CHECK(many_submissions > one_submissions);         // the context's window was used
  CHECK(context().fast_window_candidates == 32768);  // and the shared context's left alone
  CHECK(many.pairs == one.pairs);
  for (size_t i = 0; i < one.raw.size(); ++i) CHECK(rel_error(one.raw[i], many.raw[i]) <= 1e-12);
}

TEST_CASE("gpu fast under forced staging matches the cpu and the unified path", "[gpu][fast]") {
  const SaliencyOptions opt = fast_options();
  const Mesh mesh = make_bumpy_sphere(4);
  vk::Context staged(-1, true);
  staged.use_staging = true;
  SaliencyResult b = compare(staged, mesh, opt, "forced staging");
  CHECK(staged.staged_copies >= 8);  // the sorted keys of every sigma come back through it
  SaliencyResult a = compute_saliency_gpu(context(), mesh, opt);
  CHECK(a.saliency == b.saliency);
  CHECK(a.raw == b.raw);
  CHECK(a.smoothed == b.smoothed);
}

TEST_CASE("gpu fast: each sigma's averages fit a buffer of their own", "[gpu][fast]") {
  // Lavapipe allows 128 MiB per buffer: the averages of all 8 sigmas in one buffer passed
  // it at 2 million vertices (igea_loop2). Here 128 KiB per buffer on 2.6k vertices: 166
  // KiB of averages in all, 21 KiB per sigma.
  vk::Context ctx(-1, true);
  ctx.properties.limits.maxStorageBufferRange = 128 << 10;
  const Mesh mesh = make_bumpy_sphere(4);
  REQUIRE(mesh.vertex_count() * 8 * 8 > (128u << 10));
  compare(ctx, mesh, fast_options(), "128 KiB per buffer");
}

TEST_CASE("gpu fast matches the cpu fast path on real meshes", "[gpu][fast]") {
  const SaliencyOptions opt = fast_options();
  for (const char* name : {"bunny_3k.off", "spot_3k.obj", "max_planck_5k.obj", "fandisk_6k.obj"}) {
    MESHSAL_MESH_OR_CONTINUE(path, name);
    // fandisk's flat faces give exact ties between neighbours in the raw maps; the CPU's
    // float partial sums and the GPU's double ones (the raw maps agree to 9e-8) can decide
    // one of them either way: measured 445 local maxima against 446 in the first map, mbar
    // 6e-4 apart, S and Sm 3.8e-4 and 2.6e-4.
    const bool ties = std::string(name) == "fandisk_6k.obj";
    compare(context(), load_mesh(path), opt, name, ties ? 1e-3 : 1e-4);
  }
}

TEST_CASE("backend gpu takes --method fast, auto picks the device as for exact", "[gpu][fast]") {
  const uint64_t before = vk::validation_message_count();
  const Mesh m = make_bumpy_sphere(3);
  SaliencyOptions opt = fast_options();
  opt.backend = Backend::Gpu;
  opt.device = 0;
  auto devices = vk::list_devices();
  REQUIRE(!devices.empty());
  SaliencyResult r = compute_saliency(m, opt);
  CHECK(r.backend_name == devices[0].name);
  CHECK(r.method == Method::Fast);
  SaliencyResult cpu = compute_saliency_cpu(m, opt);
  CHECK(rel_error(cpu.saliency, r.saliency) <= 1e-4);
  // Auto: the device rule of the exact method (a hardware GPU, else the CPU path).
  opt.backend = Backend::Auto;
  opt.device = -1;
  int notices = 0;
  opt.notice = [&](const std::string&) { ++notices; };
  SaliencyResult a = compute_saliency(m, opt);
  const int hw = vk::pick_hardware_gpu(devices);
  if (hw < 0)
    CHECK(a.backend_name.rfind("cpu", 0) == 0);
  else
    CHECK(a.backend_name == devices[hw].name);
  CHECK(a.method == Method::Fast);
  CHECK(notices == 0);
  CHECK(vk::validation_message_count() == before);
}

TEST_CASE("gpu fast: the memory estimate counts the fast method's arrays", "[gpu][fast]") {
  // The averages of every sigma (8 doubles per vertex by default) and the aggregates.
  CHECK(gpu::fast_filter_bytes(1000000, 1000000, 8) >= 1000000ull * (16 + 64 + 100));
  vk::Context ctx(-1, true);
  ctx.info.device_local_bytes = 14 << 20;  // a device with 14 MiB
  const Mesh m = make_bumpy_sphere(5);     // 10k vertices: exact needs ~10 MiB, fast ~20 MiB
  SaliencyOptions opt = fast_options();
  CHECK_NOTHROW(compute_saliency_gpu(ctx, m, SaliencyOptions{}));
  CHECK_THROWS_WITH(compute_saliency_gpu(ctx, m, opt),
                    Catch::Contains("mesh too large") && Catch::Contains("--backend cpu"));
}

TEST_CASE("cli: bench --method fast --backend gpu times the fast method on a Vulkan device",
          "[gpu][fast][cli]") {
  MESHSAL_REQUIRE_MESH(input, "bunny_3k.off");
  CliRun r = run_cli("bench " + input + " --repeat 1 --json --method fast --backend gpu");
  INFO(r.err);
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("\"method\": \"fast\"") != std::string::npos);
  CHECK(r.out.find("\"device\": \"" + context().info.name) != std::string::npos);
  CHECK(r.out.find("\"exact_measured\": true") != std::string::npos);
  // Exact times every backend; --backend keeps the Vulkan devices' rows or the CPU's.
  auto count = [](const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
  };
  CliRun both = run_cli("bench " + input + " --repeat 1 --json");
  CliRun gpu = run_cli("bench " + input + " --repeat 1 --json --backend gpu");
  CliRun cpu = run_cli("bench " + input + " --repeat 1 --json --backend cpu");
  REQUIRE(both.rc == 0);
  REQUIRE(gpu.rc == 0);
  REQUIRE(cpu.rc == 0);
  const std::string on_device = "\"device\": \"" + context().info.name;
  CHECK(count(both.out, "\"device\": \"cpu") == 1);
  CHECK(count(both.out, on_device) == 2);  // mixed and double
  CHECK(count(gpu.out, "\"device\": \"cpu") == 0);
  CHECK(count(gpu.out, on_device) == 2);
  CHECK(count(cpu.out, "\"device\": \"cpu") == 1);
  CHECK(count(cpu.out, on_device) == 0);
  // Stage peaks where they are measured (the CPU path's), none claimed for the devices'.
  CHECK(count(cpu.out, "\"stage_peak_bytes\": {\"curvature\": ") == 1);
  CHECK(count(gpu.out, "\"stage_peak_bytes\": {}") == 2);
}

TEST_CASE("gpu fast: cells past 32-bit keys are refused naming the CPU path", "[gpu][fast]") {
  const double extent[3] = {1.0, 1.0, 0.5};
  const gpu::FastGrid g = gpu::plan_fast_grid(extent, 0.01);
  CHECK(g.nx == 101);
  CHECK(g.ny == 101);
  CHECK(g.nz == 51);
  CHECK(g.cell == 0.01);
  // 10001 x 10001 x 5001 cells: more than 32-bit keys hold.
  CHECK_THROWS_WITH(gpu::plan_fast_grid(extent, 1e-4),
                    Catch::Contains("fewer than 2^32 cells") && Catch::Contains("--backend cpu"));
}
