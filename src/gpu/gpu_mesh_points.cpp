// meshsal: the mesh points built on the device (gpu_mesh_points.h).
#include "gpu/gpu_mesh_points.h"

#include "core/parallel.h"
#include "gpu/shader_interfaces.h"

#include "point_flags_comp.h"
#include "point_positions_comp.h"

namespace meshsal::gpu {

namespace {
constexpr uint32_t kLocal = 64;  // local_size_x of both shaders
}  // namespace

void pack_local_points(const Mesh& mesh, const std::vector<double>& curvature, const BoundingBox& box,
                       size_t first, size_t count, double* out, unsigned threads) {
  parallel_for(count, threads, 1 << 16, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const size_t v = first + i;
      for (int a = 0; a < 3; ++a) out[4 * i + a] = double(mesh.positions[3 * v + a]) - box.min[a];
      out[4 * i + 3] = curvature.empty() ? 0.0 : curvature[v];
    }
  });
}

std::vector<double> local_points(const Mesh& mesh, const std::vector<double>& curvature, const BoundingBox& box,
                                 unsigned threads) {
  std::vector<double> pos4(4 * mesh.vertex_count());
  pack_local_points(mesh, curvature, box, 0, mesh.vertex_count(), pos4.data(), threads);
  return pos4;
}

DeviceMeshPoints::DeviceMeshPoints(vk::Context& ctx, const vk::Buffer& pos32, const vk::Buffer& triangles,
                                   vk::Buffer& pos, vk::Buffer& flags, uint32_t vertices, uint64_t triangle_count)
    : pool_(ctx, 2, 4),
      k_flags_(&vk::cached_kernel<shader::PointFlags>(ctx, spv_point_flags_comp, sizeof spv_point_flags_comp,
                                                      "point_flags")),
      k_positions_(&vk::cached_kernel<shader::PointPositions>(ctx, spv_point_positions_comp,
                                                              sizeof spv_point_positions_comp, "point_positions")),
      flags_(flags.handle()),
      vertices_(vertices) {
  if (triangle_count > 0xffffffffu / 3) throw Error("mesh too large for the GPU path (triangle count)");
  corners_ = uint32_t(3 * triangle_count);
  s_flags_ = pool_.bind(*k_flags_, {&triangles, &flags});
  s_positions_ = pool_.bind(*k_positions_, {&pos32, &pos});
}

void DeviceMeshPoints::record(vk::Context& ctx, VkCommandBuffer cmd, const BoundingBox& box) const {
  vkCmdFillBuffer(cmd, flags_, 0, VK_WHOLE_SIZE, 0);
  vk::barrier(cmd);
  shader::CornersPush fp{0, 0, vertices_};
  vk::dispatch(ctx, cmd, *k_flags_, s_flags_, &fp, 0, corners_, kLocal);
  shader::OriginPush pp{0, 0, 0, 0, box.min[0], box.min[1], box.min[2]};
  vk::dispatch(ctx, cmd, *k_positions_, s_positions_, &pp, 0, vertices_, kLocal);
  vk::barrier(cmd);
}

}  // namespace meshsal::gpu
