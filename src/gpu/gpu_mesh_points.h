// meshsal: the mesh points as the sweeps read them, built on the device from what the fast
// method uploads for its curvature anyway (the float positions, the triangles): each
// vertex's x, y, z in double less the mesh points' box minimum (point_positions.comp, the
// twin of local_points) and the mesh-point flags (point_flags.comp, the twin of
// referenced_vertices). They spare the upload 36 of its bytes a vertex (the doubles and the
// flags), about half of what --method fast sends a discrete GPU.
#pragma once
#include <cstdint>
#include <vector>

#include "core/mesh_points.h"
#include "gpu/vk_buffer.h"
#include "gpu/vk_compute.h"
#include "meshsal/meshsal.h"

namespace meshsal::gpu {

// The host's layout of the same positions: 4 doubles a vertex, x, y, z less box.min and
// w = curvature[v] (0 where `curvature` is empty); packed on `threads` threads.
std::vector<double> local_points(const Mesh& mesh, const std::vector<double>& curvature, const BoundingBox& box,
                                 unsigned threads = 0);
// Vertices [first, first + count) of that layout at `out` (the exact method's upload packs
// them straight into the staging area).
void pack_local_points(const Mesh& mesh, const std::vector<double>& curvature, const BoundingBox& box,
                       size_t first, size_t count, double* out, unsigned threads = 0);

class DeviceMeshPoints {
 public:
  // pos32: vec4 per vertex (upload_float_positions), triangles: 3 indices each; writes
  // pos (dvec4 per vertex, w = 0) and flags (a uint per vertex).
  DeviceMeshPoints(vk::Context& ctx, const vk::Buffer& pos32, const vk::Buffer& triangles, vk::Buffer& pos,
                   vk::Buffer& flags, uint32_t vertices, uint64_t triangle_count);
  // Its descriptor sets are its pool's: neither copied nor moved.
  DeviceMeshPoints(const DeviceMeshPoints&) = delete;
  DeviceMeshPoints& operator=(const DeviceMeshPoints&) = delete;
  // Records both, ending with a barrier; `box`: the mesh points' box (its minimum is taken).
  void record(vk::Context& ctx, VkCommandBuffer cmd, const BoundingBox& box) const;

 private:
  vk::DescriptorPool pool_;
  const vk::Kernel* k_flags_;
  const vk::Kernel* k_positions_;
  VkDescriptorSet s_flags_, s_positions_;
  VkBuffer flags_;
  uint32_t vertices_, corners_;
};

}  // namespace meshsal::gpu
