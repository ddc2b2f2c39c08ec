// meshsal: the mean curvature on the device (gpu_curvature.h).
#include "gpu/gpu_curvature.h"

#include <string>

#include "core/morton_order.h"
#include "gpu/gpu_prestage.h"
#include "gpu/shader_interfaces.h"

#include "curvature_comp.h"
#include "curvature_face_key_comp.h"
#include "curvature_incidence_comp.h"
#include "curvature_rings_comp.h"

namespace meshsal::gpu {

namespace {
constexpr uint32_t kLocal = 64;  // local_size_x of the shaders
constexpr uint32_t kFaceKeyBits = 3 * 5;  // mean_curvature_morton's cells: 2^5 per axis

uint32_t checked_count(size_t n, const char* what) {
  if (n >= 0xffffffffu / 3) throw Error(std::string("mesh too large for the GPU curvature (") + what + ")");
  return uint32_t(n);
}
}  // namespace

uint64_t DeviceCurvature::bytes(uint64_t nv, uint64_t nt) {
  return nv * 8 + nt * 12 + RadixSort::bytes(nt) + RadixSort::bytes(3 * nt) + (nv + 1) * 8 + Scan::bytes(nv) + 16;
}

DeviceCurvature::DeviceCurvature(vk::Context& ctx, const Mesh& mesh, const vk::Buffer& pos32, vk::Buffer& pos,
                                 const BoundingBox& box, TriangleOrder order)
    : curvature(ctx, mesh.vertex_count() * 8, "the curvature"),
      triangles(mesh_triangles(ctx, mesh, ctx.host_threads)),
      start(ctx, (mesh.vertex_count() + 1) * 4, "the triangles of each vertex"),
      nv_(checked_count(mesh.vertex_count(), "vertices")), nt_(checked_count(mesh.triangle_count(), "triangles")),
      count_(ctx, size_t(nv_) * 4, "the triangles of each vertex"),
      flag_(vk::Buffer::host_visible(ctx, 16, "the curvature's overflow flag")),
      pool_(ctx, 3 + 2 * RadixSort::kSets + Scan::kSets, 16 + 2 * RadixSort::kBuffers + Scan::kBuffers),
      face_sort_(ctx, pool_, nt_, order == TriangleOrder::morton ? (1u << kFaceKeyBits) - 1 : 0,
                 "the curvature's triangle"),
      corner_sort_(ctx, pool_, 3 * nt_, nv_, "the curvature's corner"),
      scan_(ctx, pool_, count_, start, nv_) {
  // The Morton grid as morton_order() lays it over the box; in input order a scale of 0,
  // which keys every triangle 0.
  for (int a = 0; a < 3; ++a) {
    lo_[a] = box.min[a];
    scale_[a] = order == TriangleOrder::morton && box.max[a] > box.min[a]
                    ? double((1u << kMortonBits) - 1) / (box.max[a] - box.min[a])
                    : 0.0;
  }
  k_key_ = &vk::cached_kernel<shader::CurvatureFaceKey>(ctx, spv_curvature_face_key_comp, sizeof spv_curvature_face_key_comp, "curvature_face_key");
  k_incidence_ = &vk::cached_kernel<shader::CurvatureIncidence>(ctx, spv_curvature_incidence_comp, sizeof spv_curvature_incidence_comp, "curvature_incidence");
  k_curvature_ = order == TriangleOrder::morton
                     ? &vk::cached_kernel<shader::Curvature>(ctx, spv_curvature_comp, sizeof spv_curvature_comp, "curvature")
                     : &vk::cached_kernel<shader::CurvatureRings>(ctx, spv_curvature_rings_comp,
                                                             sizeof spv_curvature_rings_comp, "curvature_rings");
  s_key_ = pool_.bind(*k_key_, {&pos32, &triangles, &face_sort_.keys_in()});
  s_incidence_ = pool_.bind(*k_incidence_, {&triangles, &face_sort_.order(), &corner_sort_.keys_in(), &count_});
  s_curvature_ = pool_.bind(*k_curvature_, {&pos32, &triangles, &face_sort_.order(), &corner_sort_.order(), &start,
                                            &pos, &flag_, &curvature});
}

void DeviceCurvature::record(vk::Context& ctx, VkCommandBuffer cmd) {
  vkCmdFillBuffer(cmd, count_.handle(), 0, VK_WHOLE_SIZE, 0);
  vkCmdFillBuffer(cmd, flag_.handle(), 0, VK_WHOLE_SIZE, 0);
  vk::barrier(cmd);
  shader::MortonKeyPush kp{0, 0, 0, 0, lo_[0], lo_[1], lo_[2], scale_[0], scale_[1], scale_[2]};
  vk::dispatch(ctx, cmd, *k_key_, s_key_, &kp, 0, nt_, kLocal);
  vk::barrier(cmd);
  face_sort_.record(ctx, cmd);
  shader::RangePush ip{0, 0};
  vk::dispatch(ctx, cmd, *k_incidence_, s_incidence_, &ip, 0, nt_, kLocal);
  vk::barrier(cmd);
  scan_.record(ctx, cmd, nv_);
  corner_sort_.record(ctx, cmd);
  shader::CountedPush cp{0, 0, 0};
  vk::dispatch(ctx, cmd, *k_curvature_, s_curvature_, &cp, 0, nv_, kLocal);
  vk::barrier(cmd);
}

uint32_t DeviceCurvature::most_flagged_corners() const {
  uint32_t most = 0;
  flag_.download(&most, 4);  // host memory: no submission
  return most;
}

bool DeviceCurvature::complete() const { return most_flagged_corners() == 0; }

}  // namespace meshsal::gpu
