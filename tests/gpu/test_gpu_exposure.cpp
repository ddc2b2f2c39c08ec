// Exposure on Vulkan (lavapipe here): GpuExposure (gpu/gpu_exposure.h) against its CPU
// twin exposure_cpu over exposure_views(), for the three weightings. Both sides apply one
// visibility rule to the same float projections, so the vertices with exposure > 0 are the
// same set, and the values differ by the rounding of exp and of the float sums over a batch
// (1e-5 of the largest).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "api/gpu_backend.h"
#include "cli/synthetic.h"
#include "gpu/gpu_exposure.h"
#include "gpu/gpu_visibility.h"
#include "gpu/vk_context.h"
#include "meshsal/meshsal.h"
#include "view/camera.h"
#include "view/exposure.h"
#include "test_util.h"

using namespace meshsal;

namespace {

const ExposureWeighting kWeightings[] = {{true, true}, {true, false}, {false, true}};

std::string name_of(ExposureWeighting w) {
  return w.facing && w.centre ? "facing and centre" : w.facing ? "facing only" : "centre only";
}

// Ties: vertices whose visibility differs in some view between the twins. None on CPU
// devices (lavapipe): the raster and the tests are `precise` (no fused multiply-adds), so
// their z-buffers and projections are depth_buffer_cpu's bits. (Without it lavapipe's fused
// z-buffers differed by up to 593 ulp and one (vertex, view) pair in about 2 million on the
// bumpy sphere below fell on the other side of z + tolerance.) A hardware GPU's division
// 1 / area need not be correctly rounded: there, rare ties, at most one vertex in 10^4.
double ties_allowed(bool cpu_device) { return cpu_device ? 0 : 1e-4; }

// max |gpu - cpu| <= 1e-5 max(cpu) but at rare ties (each off by at most a view's score,
// 1 / views), and exposure > 0 on the same vertices.
void check_close(const std::vector<double>& cpu, const std::vector<double>& gpu, size_t views, bool cpu_device) {
  REQUIRE(gpu.size() == cpu.size());
  const double top = *std::max_element(cpu.begin(), cpu.end());
  REQUIRE(top > 0);
  double worst = 0, worst_tie = 0;
  size_t seen = 0, differ = 0, ties = 0;
  for (size_t i = 0; i < cpu.size(); ++i) {
    const double d = std::fabs(gpu[i] - cpu[i]);
    if (d > 1e-5 * top) {
      ++ties;
      worst_tie = std::max(worst_tie, d);
    } else {
      worst = std::max(worst, d);
    }
    seen += cpu[i] > 0;
    differ += (cpu[i] > 0) != (gpu[i] > 0);
  }
  INFO("max |gpu - cpu| " << worst << " (" << ties << " vertices at ties, off by up to " << worst_tie
                          << "), max cpu " << top << ", " << seen << " of " << cpu.size() << " vertices exposed, "
                          << differ << " exposed on one side only");
  CHECK(worst <= 1e-5 * top);
  CHECK(double(ties) <= ties_allowed(cpu_device) * double(cpu.size()));
  CHECK(worst_tie <= 1.0 / double(views) + 1e-5 * top);
  CHECK(differ == 0);
}

// The GPU exposure of `mesh` (built once, run for every weighting) against exposure_cpu.
// Returns the submissions it made.
uint64_t compare(const Mesh& mesh, const VisibilityOptions& options, int max_batch = 0) {
  vk::Context ctx(-1, true);
  const uint64_t messages = vk::validation_message_count();
  const std::vector<float> normals = exposure_normals(mesh);
  const ViewFrame frame = frame_mesh(mesh);
  const std::vector<ViewAngles> views = exposure_views();
  GpuExposure gpu(ctx, mesh, normals, frame, options, max_batch);
  for (ExposureWeighting w : kWeightings) {
    INFO(name_of(w));
    check_close(exposure_cpu(mesh, normals, frame, views, w, options), gpu.exposure(views, w), views.size(),
                ctx.info.vk_type == VK_PHYSICAL_DEVICE_TYPE_CPU);
  }
  CHECK(gpu.submissions() == 3 * uint64_t((views.size() + gpu.batch() - 1) / gpu.batch()));
  CHECK(vk::validation_message_count() == messages);
  return gpu.submissions();
}

VisibilityOptions at(int resolution) {
  VisibilityOptions o;
  o.resolution = resolution;
  return o;
}

// `part` appended to `mesh`, its coordinates scaled and then moved.
void append(Mesh& mesh, const Mesh& part, const float scale[3], const float move[3]) {
  const uint32_t offset = uint32_t(mesh.vertex_count());
  for (size_t i = 0; i < part.positions.size(); ++i)
    mesh.positions.push_back(part.positions[i] * scale[i % 3] + move[i % 3]);
  for (uint32_t t : part.triangles) mesh.triangles.push_back(t + offset);
}

// A box open at the top (its top face's inner vertices left unreferenced) with a block
// standing inside: from the views' 10..30 degree elevations the near wall hides the floor,
// the lower part of the far wall and most of the block.
Mesh box_with_cavity() {
  const Mesh cube = make_cube(8);
  Mesh box;
  box.positions = cube.positions;
  for (size_t t = 0; t < cube.triangle_count(); ++t) {
    bool top = true;
    for (int k = 0; k < 3; ++k) top = top && cube.positions[3 * cube.triangles[3 * t + k] + 1] > 0.999f;
    if (!top) box.triangles.insert(box.triangles.end(), &cube.triangles[3 * t], &cube.triangles[3 * t + 3]);
  }
  const float scale[3] = {0.4f, 0.55f, 0.4f}, move[3] = {0.1f, -0.35f, 0.0f};
  append(box, make_cube(4), scale, move);
  return box;
}

}  // namespace

TEST_CASE("gpu exposure: a sphere matches exposure_cpu for the three weightings", "[view][gpu]") {
  compare(make_sphere(1.0, 3), at(256));
}

TEST_CASE("gpu exposure: a box with a cavity and a hidden block matches exposure_cpu", "[view][gpu]") {
  const Mesh box = box_with_cavity();
  compare(box, at(256));
  // The cavity hides something in every view: the floor's inner vertices are never seen.
  vk::Context ctx(-1, true);
  const std::vector<float> normals = exposure_normals(box);
  GpuExposure gpu(ctx, box, normals, frame_mesh(box), at(256));
  const std::vector<double> e = gpu.exposure(exposure_views(), {false, false});
  size_t hidden = 0;
  for (size_t i = 0; i < box.vertex_count(); ++i) {
    const float* p = &box.positions[3 * i];
    if (p[1] < -0.999f && std::fabs(p[0]) < 0.7f && std::fabs(p[2]) < 0.7f) {
      CHECK(e[i] == 0);
      ++hidden;
    }
  }
  CHECK(hidden > 0);
}

TEST_CASE("gpu exposure: vertices no triangle uses get 0", "[view][gpu]") {
  // The sphere with one unreferenced vertex before it and one after, both where the
  // sphere's own points would be seen.
  const Mesh sphere = make_sphere(1.0, 2);
  Mesh m;
  m.positions = {0.0f, 0.0f, 1.5f};
  m.positions.insert(m.positions.end(), sphere.positions.begin(), sphere.positions.end());
  m.positions.insert(m.positions.end(), {0.0f, 1.0f, 0.0f});
  for (uint32_t t : sphere.triangles) m.triangles.push_back(t + 1);
  compare(m, at(256));
  vk::Context ctx(-1, true);
  GpuExposure gpu(ctx, m, exposure_normals(m), frame_mesh(m), at(256));
  const std::vector<double> e = gpu.exposure(exposure_views(), {false, false});
  CHECK(e.front() == 0);
  CHECK(e.back() == 0);
  CHECK(*std::max_element(e.begin(), e.end()) > 0);  // the sphere's own points are seen
}

TEST_CASE("gpu exposure: more triangles and vertices than one invocation covers", "[view][gpu]") {
  // 40962 vertices and 81920 triangles: every raster invocation takes many triangles, and
  // on a CPU device every exposure invocation more than one vertex.
  const Mesh m = make_bumpy_sphere(6);
  vk::Context ctx(-1, true);
  const bool cpu_device = ctx.info.vk_type == VK_PHYSICAL_DEVICE_TYPE_CPU;
  const uint32_t views = uint32_t(exposure_views().size());
  CHECK(visibility_lanes(uint32_t(m.triangle_count()), kVisibilityRasterMost, views, cpu_device) <
        m.triangle_count());
  if (cpu_device) CHECK(exposure_lanes(uint32_t(m.vertex_count()), views, true) < m.vertex_count());
  compare(m, at(256));
}

TEST_CASE("gpu exposure: small batches give the same exposure in several submissions", "[view][gpu]") {
  // 48 views 5 at a time: 10 submissions a weighting, the last with 3 views.
  CHECK(compare(make_sphere(1.0, 3), at(256), 5) == 3 * 10);
  CHECK(compare(box_with_cavity(), at(128), 7) == 3 * 7);
}

TEST_CASE("gpu exposure: invocations per batch", "[view][gpu]") {
  // CPU devices: the visibility test's invocations for the same pairs, at most one a vertex.
  CHECK(exposure_lanes(40962, 48, true) == 12 * 2048);
  CHECK(exposure_lanes(3000, 48, true) == 12 * 192);
  CHECK(exposure_lanes(100, 1, true) == 64);
  // A big batch: at most 2048 (vertex, view) pairs an invocation (lavapipe's loop limit).
  CHECK(exposure_lanes(1u << 22, 1024, true) == (1u << 22) / 2048u * 1024u);
  // GPUs: about a million invocations for a batch, never more than the vertices.
  CHECK(exposure_lanes(1u << 22, 48, false) >= (1u << 20) / 4);
  CHECK(exposure_lanes(3000, 48, false) == 3008);
}

TEST_CASE("gpu exposure: the backend entries on the cached device and on a held one", "[view][gpu]") {
  const GpuBackend& backend = gpu_backend();
  REQUIRE(backend.exposure);
  REQUIRE(backend.exposure_on);
  const Mesh m = make_sphere(1.0, 2);
  const std::vector<float> normals = exposure_normals(m);
  const ViewFrame frame = frame_mesh(m);
  const std::vector<ViewAngles> views = exposure_views();
  const std::vector<double> cpu = exposure_cpu(m, normals, frame, views, {}, at(256));
  const ExposureRun cached = backend.exposure(m, normals, frame, views, {}, at(256), -1);
  CHECK(cached.backend_name.rfind("vulkan: ", 0) == 0);
  DeviceInfo info;
  const std::shared_ptr<void> held = backend.open_device(-1, &info);
  check_close(cpu, cached.exposure, views.size(), info.type == "cpu");
  const ExposureRun on = backend.exposure_on(held, m, normals, frame, views, {}, at(256));
  CHECK(on.backend_name == "vulkan: " + info.name);
  CHECK(on.exposure == cached.exposure);  // the same device, the same bits
  // The CPU twin's checks: normals that do not match the mesh are an error.
  CHECK_THROWS_WITH(backend.exposure(m, std::vector<float>(3), frame, views, {}, at(256), -1),
                    Catch::Contains("normals do not match"));
}

TEST_CASE("gpu exposure: lavapipe's loop limit is an error and never silently wrong", "[view][gpu]") {
  vk::Context ctx(-1, true);
  if (ctx.info.vk_type != VK_PHYSICAL_DEVICE_TYPE_CPU) {
    meshsal_test::skip_case("not a CPU Vulkan device (no loop limit)");
    return;
  }
  // A cube's 12 triangles at 512 px: far more raster steps per invocation than the limit.
  const Mesh cube = make_cube(1);
  GpuExposure gpu(ctx, cube, exposure_normals(cube), frame_mesh(cube), at(512));
  CHECK_THROWS_WITH(gpu.exposure(exposure_views(), {}), Catch::Contains("65535 loop steps"));
}
