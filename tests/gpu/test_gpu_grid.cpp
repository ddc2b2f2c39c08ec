// The GPU grid build (gpu_grid.h: keys, prefix sum, stable radix sort) against its CPU
// twin build_spatial_grid(): the same cell starts and the same point order, vertex order
// inside each cell, also when thousands of points share one cell.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "gpu/gpu_grid.h"
#include "meshsal/meshsal.h"
#include "core/mesh_points.h"
#include "saliency/spatial_grid.h"
#include "cli/synthetic.h"
#include "gpu/vk_context.h"
#include "test_util.h"

using namespace meshsal;

namespace {
void compare_grids(vk::Context& ctx, const Mesh& mesh, double cell, const std::string& what) {
  INFO(what << ", cell " << cell);
  std::vector<uint8_t> is_point = referenced_vertices(mesh);
  SpatialGrid cpu = build_spatial_grid(mesh, is_point, cell);
  std::vector<uint32_t> order, starts;
  gpu_grid_order(ctx, mesh, is_point, cell, &order, &starts);
  CHECK(starts == cpu.cell_start);
  CHECK(order == cpu.order);
}
}  // namespace

TEST_CASE("gpu grid: the same cells and point order as the cpu grid", "[gpu]") {
  const uint64_t before = vk::validation_message_count();
  vk::Context ctx(-1, true);
  Mesh sphere = make_bumpy_sphere(4);
  compare_grids(ctx, sphere, 0.05, "bumpy sphere");
  compare_grids(ctx, sphere, 0.3, "bumpy sphere, large cells");
  // Every point in one cell: 2.6k points whose order must still be the vertex order.
  compare_grids(ctx, sphere, 100.0, "bumpy sphere, one cell");
  // Loose vertices (not mesh points) between the others.
  Mesh loose = make_plane_with_bump(2.0, 50, 0.3, 0.2);
  loose.positions.insert(loose.positions.begin() + 30, {0.5f, 0.5f, 9.0f});
  for (auto& t : loose.triangles)
    if (t >= 10) ++t;
  compare_grids(ctx, loose, 0.01, "plane with a loose vertex");
  CHECK(vk::validation_message_count() == before);
}

TEST_CASE("gpu grid: real meshes, under forced staging too", "[gpu]") {
  MESHSAL_REQUIRE_MESH(path, "bunny_36k.obj");
  Mesh bunny = load_mesh(path);
  vk::Context ctx(-1, true);
  compare_grids(ctx, bunny, 0.002, "bunny_36k");
  ctx.use_staging = true;
  compare_grids(ctx, bunny, 0.01, "bunny_36k, staged");
  compare_grids(ctx, bunny, 1.0, "bunny_36k, one cell");  // 36k points in one cell
}
