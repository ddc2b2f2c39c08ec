// meshsal: Taubin mean curvature on the device, the GPU twin of mean_curvature_morton()
// (saliency/curvature.h), the same bits: each triangle keyed by the Morton cell of its
// lowest-coded corner (curvature_face_key.comp) and stably sorted by it, the corners of the
// sorted triangles stably sorted by vertex (curvature_incidence.comp), so that each vertex
// visits its triangles in the order the CPU's renumbered copy does; then per vertex the
// normal and the curvature sums in double (curvature.comp). The incidence stays on the
// device for the local maxima over the triangles (the fast method's suppression).
#pragma once
#include <cstdint>

#include "core/mesh_points.h"
#include "gpu/gpu_radix_sort.h"
#include "gpu/gpu_scan.h"
#include "gpu/vk_buffer.h"
#include "gpu/vk_compute.h"
#include "meshsal/meshsal.h"

namespace meshsal::gpu {

class DeviceCurvature {
 public:
  // For `mesh` (its triangles uploaded here), its float coordinates in pos32 (vec4 per
  // vertex) and `box` (the mesh points' box: the Morton grid's, as the CPU's fast method
  // takes it). H goes to pos[v].w (dvec4 per vertex) and to curvature (a double per vertex,
  // for the host to read).
  DeviceCurvature(vk::Context& ctx, const Mesh& mesh, const vk::Buffer& pos32, vk::Buffer& pos,
                  const BoundingBox& box);
  // Its descriptor sets name its own buffers: neither copied nor moved.
  DeviceCurvature(const DeviceCurvature&) = delete;
  DeviceCurvature& operator=(const DeviceCurvature&) = delete;
  // Records the whole computation into cmd, ending with a barrier.
  void record(vk::Context& ctx, VkCommandBuffer cmd);
  // After the submission: false when some vertex has more triangles than one invocation may
  // visit on every device (its H is then 0 here: the caller computes H on the host).
  bool complete() const;
  // Device bytes it holds for nv vertices and nt triangles.
  static uint64_t bytes(uint64_t nv, uint64_t nt);

  // The incidence, by vertex: vertex v's entries are entry()[start[v] .. start[v+1]), each
  // 3 s + c: corner c of the triangle at sorted slot s, triangle_order()[s].
  vk::Buffer curvature;  // H per vertex
  vk::Buffer triangles;  // 3 per triangle, as the mesh has them
  vk::Buffer start;      // nv + 1
  vk::Buffer& triangle_order() { return face_sort_.order(); }
  vk::Buffer& entry() { return corner_sort_.order(); }

 private:
  uint32_t nv_, nt_;
  double lo_[3], scale_[3];
  vk::Buffer count_, flag_;
  vk::DescriptorPool pool_;
  RadixSort face_sort_, corner_sort_;
  Scan scan_;
  const vk::Kernel *k_key_, *k_incidence_, *k_curvature_;
  VkDescriptorSet s_key_, s_incidence_, s_curvature_;
};

}  // namespace meshsal::gpu
