// meshsal: the uniform grid of the GPU sweep, built on the device: cell keys and counts,
// cell starts by a prefix sum, and the points in cell order by a stable LSD radix sort of
// (cell key, vertex) pairs, so that inside a cell points stay in vertex order exactly as
// in build_spatial_grid() (spatial_grid.cpp), at a cost linear in the points however many
// share a cell. The GPU twin of build_spatial_grid().
#pragma once
#include <cstdint>
#include <vector>

#include "meshsal/meshsal.h"
#include "gpu/gpu_radix_sort.h"
#include "gpu/gpu_scan.h"
#include "gpu/vk_buffer.h"
#include "gpu/vk_compute.h"
#include "gpu/vk_context.h"

namespace meshsal {

// Cells of min_cell, grown by 1.25 while there are more than max(2^20, 4 points) cells
// (or more than `limit`); coordinates relative to the bbox minimum.
struct GridPlan {
  uint32_t nx = 1, ny = 1, nz = 1;
  double h = 1;
  uint64_t cells() const { return uint64_t(nx) * ny * nz; }
};
GridPlan plan_grid(const double extent[3], double min_cell, uint64_t points, uint64_t limit);

// The device arrays of a grid build: pos (dvec4 per vertex: xyz - bbox min, value) and
// flags (mesh point or not) in; starts (cells + 1), sorted_pos and sorted_vertex (one per
// mesh point) made here.
struct GridArrays {
  const vk::Buffer* pos = nullptr;
  const vk::Buffer* flags = nullptr;
  vk::Buffer* starts = nullptr;
  vk::Buffer* sorted_pos = nullptr;
  vk::Buffer* sorted_vertex = nullptr;
};

// The build's scratch and pipelines, made once for builds over n items (those flagged are the
// points) on grids of at most max_cells cells; it makes a.starts (max_cells + 1). The fast
// filter builds a grid per sigma with one.
class GridBuilder {
 public:
  GridBuilder(vk::Context& ctx, vk::DescriptorPool& pool, const GridArrays& a, uint32_t n, uint64_t max_cells);
  // Its descriptor sets name its own buffers: neither copied nor moved.
  GridBuilder(const GridBuilder&) = delete;
  GridBuilder& operator=(const GridBuilder&) = delete;
  // Records the build of plan g (g.cells() <= max_cells) into cmd: a.starts over its cells,
  // the first `gather` sorted items (the points, or a bound of them) into a.sorted_pos and
  // a.sorted_vertex. Ends with a barrier.
  void record(vk::Context& ctx, VkCommandBuffer cmd, const GridPlan& g, uint32_t gather);
  static constexpr uint32_t kSets = gpu::RadixSort::kSets + gpu::Scan::kSets + 2;
  static constexpr uint32_t kBuffers = gpu::RadixSort::kBuffers + gpu::Scan::kBuffers + 8;

 private:
  uint32_t n_;
  vk::Buffer cell_count_;
  gpu::RadixSort sort_;
  gpu::Scan scan_;
  const vk::Kernel *k_key_, *k_gather_;
  VkDescriptorSet s_key_, s_gather_;
};

// Builds the grid of cells >= `cell` over nv vertices of which np are mesh points, and
// downloads the cell starts (the sweep plans its slices with them).
GridPlan build_gpu_grid(vk::Context& ctx, const GridArrays& a, uint32_t nv, uint32_t np,
                        const double extent[3], double cell, std::vector<uint32_t>* starts_out);

// Device bytes the build needs besides its outputs (keys, values, digit counts).
uint64_t gpu_grid_scratch_bytes(uint64_t nv, uint64_t cells);

// For tests: the grid of the mesh points on the device, as build_spatial_grid() would
// order them (order[j] = vertex of sorted point j; starts per cell).
void gpu_grid_order(vk::Context& ctx, const Mesh& mesh, const std::vector<uint8_t>& is_point,
                    double cell, std::vector<uint32_t>* order, std::vector<uint32_t>* starts);

}  // namespace meshsal
