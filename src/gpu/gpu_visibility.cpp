#include "gpu/gpu_visibility.h"

#include <algorithm>
#include <string>

#include "meshsal/meshsal.h"
#include "gpu/vk_buffer.h"
#include "gpu/shader_interfaces.h"
#include "gpu/vk_compute.h"
#include "gpu/vk_staging.h"
#include "visibility_raster_comp.h"
#include "visibility_test_comp.h"

namespace meshsal {

namespace {
using gpu::shader::RasterPush;  // the push blocks: gpu/shader_interfaces.h
using gpu::shader::TestPush;
}  // namespace

// Invocations per view: each loops over items with this stride. About 16 items each, at
// most `most` per view, which suits a CPU driver (lavapipe pays per invocation). On a GPU a
// small batch (the optimiser's ~40 views) would then leave most of the device idle, so
// there the views of a batch share about a million invocations (at least one item each).
uint32_t visibility_lanes(uint32_t items, uint32_t most, uint32_t views, bool cpu_device) {
  auto round64 = [](uint64_t x) { return uint32_t((x + 63) / 64 * 64); };
  uint32_t l = std::clamp<uint32_t>(round64(items / 16), 64, most);
  if (!cpu_device && views > 0) {
    const uint64_t share = round64((uint64_t(1) << 20) / views);
    l = std::max(l, uint32_t(std::min<uint64_t>(share, round64(items))));
  }
  return l;
}

int visibility_batch(const vk::Context& ctx, int resolution, int max_batch) {
  const uint64_t layer = uint64_t(resolution) * uint64_t(resolution) * 4;
  if (layer > ctx.properties.limits.maxStorageBufferRange)
    throw Error("resolution " + std::to_string(resolution) + " is too large for '" + ctx.info.name + "'");
  uint64_t cap = std::min<uint64_t>(64ull << 20, ctx.properties.limits.maxStorageBufferRange);
  int fit = int(std::max<uint64_t>(1, cap / layer));
  fit = std::min<int>(fit, 1024);
  fit = std::min<int>(fit, int(ctx.properties.limits.maxComputeWorkGroupCount[1]));
  return max_batch > 0 ? std::min(max_batch, fit) : fit;
}

vk::Kernel& visibility_raster_kernel(vk::Context& ctx) {
  // One copy of the SPIR-V in the program: the kernel cache knows a shader by its address.
  return vk::cached_kernel<gpu::shader::VisibilityRaster>(ctx, spv_visibility_raster_comp,
                                                         sizeof spv_visibility_raster_comp, "visibility_raster");
}

void record_depth_buffers(vk::Context& ctx, VkCommandBuffer cmd, const vk::Kernel& raster, VkDescriptorSet set,
                          const vk::Buffer& zbuf, uint32_t res, uint32_t triangles, uint32_t views,
                          bool cpu_device) {
  vkCmdFillBuffer(cmd, zbuf.handle(), 0, VkDeviceSize(res) * res * 4 * views, 0x7f800000u);  // +inf
  vk::barrier(cmd);
  const uint32_t lanes = visibility_lanes(triangles, kVisibilityRasterMost, views, cpu_device);
  RasterPush rp{0, lanes, res, triangles, views, cpu_device ? kCpuLoopBudget : 0};
  vk::dispatch(ctx, cmd, raster, set, &rp, 0, lanes, 64,
               (views + kVisibilityViewsPerGroup - 1) / kVisibilityViewsPerGroup);
}

void check_loop_budget(uint32_t over_budget, const vk::Context& ctx) {
  if (over_budget)
    throw Error("the visibility shaders would pass the Vulkan driver's limit of 65535 loop "
                "steps per invocation on '" + ctx.info.name + "' (lavapipe), which would "
                "silently give wrong results at this resolution; use a lower --resolution "
                "or --backend cpu");
}

struct GpuVisibility::State {
  bool cpu_device = false;
  uint64_t values_read = 0;
  vk::Context& ctx;
  ViewFrame frame;
  VisibilityOptions options;
  uint32_t vertices = 0, triangles = 0;
  int batch = 1;
  uint64_t submissions = 0;
  vk::Buffer pos, tri, weights, rows, zbuf, partial, status;
  vk::Kernel* raster = nullptr;
  vk::Kernel* test = nullptr;
  std::unique_ptr<vk::DescriptorPool> pool;
  VkDescriptorSet raster_set = VK_NULL_HANDLE, test_set = VK_NULL_HANDLE;
  explicit State(vk::Context& c) : ctx(c) {}
};

GpuVisibility::GpuVisibility(vk::Context& ctx, const Mesh& mesh, const std::vector<float>& weights,
                             const ViewFrame& frame, const VisibilityOptions& options, int max_batch)
    : s_(std::make_unique<State>(ctx)) {
  check_visibility_options(options);
  if (weights.size() != mesh.vertex_count()) throw Error("visibility weights do not match the mesh");
  if (mesh.vertex_count() == 0 || mesh.triangle_count() == 0) throw Error("empty mesh");
  if (mesh.vertex_count() > (1u << 31) / 3 || mesh.triangle_count() > (1u << 31) / 3)
    throw Error("mesh too large for the GPU visibility path; use --backend cpu");
  State& s = *s_;
  s.frame = frame;
  s.options = options;
  s.vertices = uint32_t(mesh.vertex_count());
  s.triangles = uint32_t(mesh.triangle_count());
  s.cpu_device = ctx.info.vk_type == VK_PHYSICAL_DEVICE_TYPE_CPU;

  const uint64_t layer = uint64_t(options.resolution) * uint64_t(options.resolution) * 4;
  s.batch = visibility_batch(ctx, options.resolution, max_batch);

  s.pos = vk::Buffer(ctx, mesh.positions.size() * 4, "vertex positions");
  s.pos.upload(mesh.positions.data(), mesh.positions.size() * 4);
  s.tri = vk::Buffer(ctx, mesh.triangles.size() * 4, "triangles");
  s.tri.upload(mesh.triangles.data(), mesh.triangles.size() * 4);
  s.weights = vk::Buffer(ctx, weights.size() * 4, "visibility weights");
  s.weights.upload(weights.data(), weights.size() * 4);
  s.rows = vk::Buffer(ctx, size_t(s.batch) * sizeof(ViewRows), "view matrices");
  s.zbuf = vk::Buffer(ctx, size_t(s.batch) * size_t(layer), "depth buffers");
  // One value per view and work group; a smaller batch has more groups per view.
  size_t partials = 0;
  for (uint32_t views = 1; views <= uint32_t(s.batch); ++views)
    partials = std::max<size_t>(
        partials, size_t(views) * visibility_lanes(s.vertices, kVisibilityTestMost, views, s.cpu_device) / 64);
  s.partial = vk::Buffer(ctx, partials * 4, "visibility partial sums");

  s.status = vk::Buffer(ctx, 16, "visibility status");
  s.raster = &visibility_raster_kernel(ctx);
  s.test = &vk::cached_kernel<gpu::shader::VisibilityTest>(ctx, spv_visibility_test_comp, sizeof spv_visibility_test_comp, "visibility_test");
  s.pool = std::make_unique<vk::DescriptorPool>(ctx, 2, 11);
  s.raster_set = s.pool->bind(*s.raster, {&s.pos, &s.tri, &s.rows, &s.zbuf, &s.status});
  s.test_set = s.pool->bind(*s.test, {&s.pos, &s.weights, &s.rows, &s.zbuf, &s.partial, &s.status});
}

GpuVisibility::~GpuVisibility() = default;

int GpuVisibility::batch() const { return s_->batch; }
uint64_t GpuVisibility::submissions() const { return s_->submissions; }
uint64_t GpuVisibility::values_read() const { return s_->values_read; }

std::vector<double> GpuVisibility::score(const std::vector<ViewAngles>& views) {
  State& s = *s_;
  std::vector<double> U(views.size(), 0.0);
  const uint32_t res = uint32_t(s.options.resolution);
  std::vector<ViewRows> rows;
  std::vector<float> partial;
  for (size_t first = 0; first < views.size(); first += size_t(s.batch)) {
    const uint32_t count = uint32_t(std::min(views.size() - first, size_t(s.batch)));
    rows.resize(count);
    for (uint32_t v = 0; v < count; ++v) rows[v] = view_rows(s.frame, views[first + v]);
    const size_t row_bytes = count * sizeof(ViewRows);
    const bool inline_rows = row_bytes <= 65536;  // vkCmdUpdateBuffer's limit
    if (!inline_rows) s.rows.upload(rows.data(), row_bytes);
    vk::RecordedDownload readback, read_status;
    const uint32_t budget = s.cpu_device ? kCpuLoopBudget : 0;
    const uint32_t test_lanes = visibility_lanes(s.vertices, kVisibilityTestMost, count, s.cpu_device);
    const uint32_t groups = test_lanes / 64;
    const size_t partial_bytes = size_t(count) * groups * 4;
    const size_t status_at = (partial_bytes + 255) / 256 * 256;  // after the sums
    if (!s.partial.mapped()) vk::staging_area(s.ctx, status_at + 4);
    vk::submit(s.ctx, "visibility", [&](VkCommandBuffer cmd) {
      // The view matrices go in the command buffer itself: no transfer of their own.
      if (inline_rows) vkCmdUpdateBuffer(cmd, s.rows.handle(), 0, row_bytes, rows.data());
      vkCmdFillBuffer(cmd, s.status.handle(), 0, VK_WHOLE_SIZE, 0);
      record_depth_buffers(s.ctx, cmd, *s.raster, s.raster_set, s.zbuf, res, s.triangles, count, s.cpu_device);
      vk::barrier(cmd);
      TestPush tp{0, test_lanes, res, s.vertices, float(s.options.depth_tol_px / s.options.resolution), count, budget};
      vk::dispatch(s.ctx, cmd, *s.test, s.test_set, &tp, 0, test_lanes, 64,
                   (count + kVisibilityViewsPerGroup - 1) / kVisibilityViewsPerGroup);
      // Read back in the same submission; vk::submit() ends with the barrier that makes
      // the partial sums (or their staging copy) visible to the host.
      readback.record(s.ctx, cmd, s.partial, 0, partial_bytes);
      read_status.record(s.ctx, cmd, s.status, 0, 4, status_at);
    });
    ++s.submissions;
    partial.resize(size_t(count) * groups);
    readback.finish(partial.data());
    uint32_t over_budget = 0;
    read_status.finish(&over_budget);
    check_loop_budget(over_budget, s.ctx);
    s.values_read += partial.size();
    for (uint32_t v = 0; v < count; ++v) {
      double sum = 0;
      for (uint32_t g = 0; g < groups; ++g) sum += partial[size_t(v) * groups + g];
      U[first + v] = sum;
    }
  }
  return U;
}

}  // namespace meshsal
