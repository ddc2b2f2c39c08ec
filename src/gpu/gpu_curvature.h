// meshsal: Taubin mean curvature on the device, the GPU twin of either CPU curvature
// (saliency/curvature.h), the same bits:
// - TriangleOrder::morton, the fast method's mean_curvature_morton(): each triangle keyed by
//   the Morton cell of its lowest-coded corner (curvature_face_key.comp) and stably sorted
//   by it, so that each vertex visits its triangles in the order the CPU's renumbered copy
//   does; per vertex the normal and the sums over its triangles (curvature.comp);
// - TriangleOrder::input, the exact method's vertex_normals() and mean_curvature() over
//   build_adjacency()'s 1-rings: the triangles in input order (every key 0: the one-pass
//   stable sort keeps them), per vertex the normal and the sums over its distinct
//   neighbours in increasing index, each edge's area gathered from its triangles
//   (curvature_rings.comp), so no 1-rings are built on the host.
// Either way the corners of the sorted triangles are stably sorted by vertex
// (curvature_incidence.comp), and that incidence stays on the device for the local maxima
// over the triangles (local_max_faces.comp, the same test as over the 1-rings).
#pragma once
#include <cstdint>

#include "core/mesh_points.h"
#include "gpu/gpu_radix_sort.h"
#include "gpu/gpu_scan.h"
#include "gpu/vk_buffer.h"
#include "gpu/vk_compute.h"
#include "meshsal/meshsal.h"

namespace meshsal::gpu {

// Which CPU curvature the device's is the twin of (see above).
enum class TriangleOrder { morton, input };

class DeviceCurvature {
 public:
  // For `mesh` (its triangles uploaded here, or taken where gpu_prestage.h holds them), its float coordinates in pos32 (vec4 per
  // vertex) and `box` (the mesh points' box: the Morton grid's, as the CPU's fast method
  // takes it; unused in input order). H goes to pos[v].w (dvec4 per vertex) and to
  // curvature (a double per vertex, for the host to read).
  DeviceCurvature(vk::Context& ctx, const Mesh& mesh, const vk::Buffer& pos32, vk::Buffer& pos,
                  const BoundingBox& box, TriangleOrder order = TriangleOrder::morton);
  // Its descriptor sets name its own buffers: neither copied nor moved.
  DeviceCurvature(const DeviceCurvature&) = delete;
  DeviceCurvature& operator=(const DeviceCurvature&) = delete;
  // Records the whole computation into cmd, ending with a barrier.
  void record(vk::Context& ctx, VkCommandBuffer cmd);
  // After the submission: false when some vertex has more triangles than one invocation may
  // visit on every device (16,384 corners in Morton order, 64 in input order, where each
  // neighbour takes a pass over them; its H is then 0 here: the caller computes H on the
  // host).
  bool complete() const;
  // The most corners of a vertex left to the host (0 when complete()).
  uint32_t most_flagged_corners() const;
  // The most corners of a vertex whose H input order computes (curvature_rings.comp), and
  // the most Morton order does, which is also the most the local maxima over the triangles
  // may visit (local_max_faces.comp).
  static constexpr uint32_t kInputOrderCorners = 64, kMortonCorners = 16384;
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
