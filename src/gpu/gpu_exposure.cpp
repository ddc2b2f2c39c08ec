#include "gpu/gpu_exposure.h"

#include <algorithm>
#include <array>

#include "core/mesh_points.h"
#include "gpu/gpu_visibility.h"
#include "gpu/shader_interfaces.h"
#include "gpu/vk_buffer.h"
#include "gpu/vk_compute.h"
#include "gpu/vk_staging.h"
#include "view/visibility.h"
#include "exposure_test_comp.h"

namespace meshsal {

namespace {
// Most (vertex, view) pairs one invocation tests: with up to 13 counted loop steps a pair
// (a silhouette pixel's 3x3), an invocation stays under kCpuLoopBudget on lavapipe even
// for a batch of 1024 views.
const uint64_t kPairsMost = 2048;

uint64_t round64(uint64_t x) { return (x + 63) / 64 * 64; }
}  // namespace

// The visibility test runs visibility_lanes invocations per group of 4 views; here one
// invocation takes all views of the batch, so the same pairs get that many times the groups
// (~64 pairs each on a CPU device), more when that would pass kPairsMost pairs each, and
// never more than one invocation per vertex.
uint32_t exposure_lanes(uint32_t vertices, uint32_t views, bool cpu_device) {
  const uint64_t groups = (uint64_t(views) + kVisibilityViewsPerGroup - 1) / kVisibilityViewsPerGroup;
  uint64_t l = uint64_t(visibility_lanes(vertices, kVisibilityTestMost, views, cpu_device)) * groups;
  l = std::max<uint64_t>(l, round64((uint64_t(vertices) * views + kPairsMost - 1) / kPairsMost));
  return uint32_t(std::min<uint64_t>(l, round64(vertices)));
}

struct GpuExposure::State {
  explicit State(vk::Context& c) : ctx(c) {}
  vk::Context& ctx;
  bool cpu_device = false;
  ViewFrame frame;
  VisibilityOptions options;
  uint32_t vertices = 0, triangles = 0;
  int batch = 1;
  uint64_t submissions = 0;
  vk::Buffer pos, tri, normals, is_point, rows, dirs, zbuf, out, status;
  vk::Kernel* raster = nullptr;
  vk::Kernel* test = nullptr;
  std::unique_ptr<vk::DescriptorPool> pool;
  VkDescriptorSet raster_set = VK_NULL_HANDLE, test_set = VK_NULL_HANDLE;
};

GpuExposure::GpuExposure(vk::Context& ctx, const Mesh& mesh, const std::vector<float>& normals,
                         const ViewFrame& frame, const VisibilityOptions& options, int max_batch)
    : s_(std::make_unique<State>(ctx)) {
  check_visibility_options(options);
  if (normals.size() != 3 * mesh.vertex_count()) throw Error("exposure: normals do not match the mesh");
  if (mesh.vertex_count() > (1u << 31) / 3 || mesh.triangle_count() > (1u << 31) / 3)
    throw Error("mesh too large for the GPU exposure; use --backend cpu");
  State& s = *s_;
  s.frame = frame;
  s.options = options;
  s.vertices = uint32_t(mesh.vertex_count());
  s.triangles = uint32_t(mesh.triangle_count());
  s.cpu_device = ctx.info.vk_type == VK_PHYSICAL_DEVICE_TYPE_CPU;
  s.batch = visibility_batch(ctx, options.resolution, max_batch);
  if (s.triangles == 0) return;  // no mesh points: exposure() gives zeros without the device

  // Which vertices are mesh points, as the weights the shader skips on (0: not a point).
  const std::vector<uint8_t> points = referenced_vertices(mesh);
  const std::vector<float> is_point(points.begin(), points.end());
  const size_t layer = size_t(options.resolution) * size_t(options.resolution) * 4;
  s.pos = vk::Buffer(ctx, mesh.positions.size() * 4, "vertex positions");
  s.pos.upload(mesh.positions.data(), mesh.positions.size() * 4);
  s.tri = vk::Buffer(ctx, mesh.triangles.size() * 4, "triangles");
  s.tri.upload(mesh.triangles.data(), mesh.triangles.size() * 4);
  s.normals = vk::Buffer(ctx, normals.size() * 4, "exposure normals");
  s.normals.upload(normals.data(), normals.size() * 4);
  s.is_point = vk::Buffer(ctx, is_point.size() * 4, "mesh points");
  s.is_point.upload(is_point.data(), is_point.size() * 4);
  s.rows = vk::Buffer(ctx, size_t(s.batch) * sizeof(ViewRows), "view matrices");
  s.dirs = vk::Buffer(ctx, size_t(s.batch) * 16, "view directions");
  s.zbuf = vk::Buffer(ctx, size_t(s.batch) * layer, "depth buffers");
  s.out = vk::Buffer(ctx, size_t(s.vertices) * 4, "exposure per vertex");
  s.status = vk::Buffer(ctx, 16, "exposure status");
  s.raster = &visibility_raster_kernel(ctx);
  s.test = &vk::cached_kernel<gpu::shader::ExposureTest>(ctx, spv_exposure_test_comp, sizeof spv_exposure_test_comp,
                                                         "exposure_test");
  s.pool = std::make_unique<vk::DescriptorPool>(ctx, 2, 13);
  s.raster_set = s.pool->bind(*s.raster, {&s.pos, &s.tri, &s.rows, &s.zbuf, &s.status});
  s.test_set = s.pool->bind(*s.test, {&s.pos, &s.normals, &s.is_point, &s.rows, &s.dirs, &s.zbuf, &s.out, &s.status});
}

GpuExposure::~GpuExposure() = default;

int GpuExposure::batch() const { return s_->batch; }
uint64_t GpuExposure::submissions() const { return s_->submissions; }

std::vector<double> GpuExposure::exposure(const std::vector<ViewAngles>& views, ExposureWeighting weighting) {
  State& s = *s_;
  std::vector<double> sum(s.vertices, 0.0);
  if (views.empty() || s.triangles == 0) return sum;
  const uint32_t res = uint32_t(s.options.resolution);
  const size_t out_bytes = size_t(s.vertices) * 4;
  const size_t status_at = (out_bytes + 255) / 256 * 256;  // after the sums
  // The sums come back in the batch's own submission where they fit the staging area
  // (always, where the buffers are mapped); past it, by chunked downloads after it.
  const bool recorded = s.out.mapped() || status_at + 4 <= vk::kStagingMaxBytes;
  if (!s.out.mapped() && recorded) vk::staging_area(s.ctx, status_at + 4);
  std::vector<ViewRows> rows;
  std::vector<std::array<float, 4>> dirs;
  std::vector<float> batch_sum(s.vertices);
  for (size_t first = 0; first < views.size(); first += size_t(s.batch)) {
    const uint32_t count = uint32_t(std::min(views.size() - first, size_t(s.batch)));
    rows.resize(count);
    dirs.resize(count);
    for (uint32_t v = 0; v < count; ++v) {
      const ExposureView ev = exposure_view(s.frame, views[first + v]);
      rows[v] = ev.rows;
      dirs[v] = {ev.direction[0], ev.direction[1], ev.direction[2], 0.0f};
    }
    const size_t row_bytes = count * sizeof(ViewRows), dir_bytes = count * sizeof(dirs[0]);
    const bool inline_rows = row_bytes <= 65536;  // vkCmdUpdateBuffer's limit
    if (!inline_rows) {
      s.rows.upload(rows.data(), row_bytes);
      s.dirs.upload(dirs.data(), dir_bytes);
    }
    const uint32_t lanes = exposure_lanes(s.vertices, count, s.cpu_device);
    gpu::shader::ExposurePush push{0,
                                   lanes,
                                   res,
                                   s.vertices,
                                   float(s.options.depth_tol_px / s.options.resolution),
                                   count,
                                   s.cpu_device ? kCpuLoopBudget : 0,
                                   weighting.facing ? 1u : 0u,
                                   weighting.centre ? 1u : 0u,
                                   2.0f * kCentreVarianceX,  // as exposure_weight computes them
                                   2.0f * kCentreVarianceY};
    vk::RecordedDownload readback, read_status;
    vk::submit(s.ctx, "exposure", [&](VkCommandBuffer cmd) {
      // The views go in the command buffer itself: no transfer of their own.
      if (inline_rows) {
        vkCmdUpdateBuffer(cmd, s.rows.handle(), 0, row_bytes, rows.data());
        vkCmdUpdateBuffer(cmd, s.dirs.handle(), 0, dir_bytes, dirs.data());
      }
      vkCmdFillBuffer(cmd, s.status.handle(), 0, VK_WHOLE_SIZE, 0);
      record_depth_buffers(s.ctx, cmd, *s.raster, s.raster_set, s.zbuf, res, s.triangles, count, s.cpu_device);
      vk::barrier(cmd);
      vk::dispatch(s.ctx, cmd, *s.test, s.test_set, &push, 0, lanes, 64);
      if (recorded) {
        readback.record(s.ctx, cmd, s.out, 0, out_bytes);
        read_status.record(s.ctx, cmd, s.status, 0, 4, status_at);
      }
    });
    ++s.submissions;
    uint32_t over_budget = 0;
    if (recorded) {
      readback.finish(batch_sum.data());
      read_status.finish(&over_budget);
    } else {
      s.out.download(batch_sum.data(), out_bytes);
      s.status.download(&over_budget, 4);
    }
    check_loop_budget(over_budget, s.ctx);
    for (uint32_t i = 0; i < s.vertices; ++i) sum[i] += batch_sum[i];
  }
  for (double& x : sum) x /= double(views.size());
  return sum;
}

}  // namespace meshsal
