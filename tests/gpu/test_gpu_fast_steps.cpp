// The fast method's per-sigma steps on the device, each against its host twin: the cells and
// their pieces (fast_cell_runs), the query groups (group_cells), the candidate bound
// (most_candidates); and the filter as a whole waits on the host only for its submissions of
// queries (no round trip inside the sigma loop), giving the same maps whether its phases
// are submitted apart or together.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "cli/synthetic.h"
#include "core/mesh_points.h"
#include "gpu/gpu_fast_bound.h"
#include "gpu/gpu_fast_cells.h"
#include "gpu/gpu_fast_groups.h"
#include "gpu/gpu_grid.h"
#include "gpu/gpu_saliency.h"
#include "gpu/vk_compute.h"
#include "gpu/vk_context.h"
#include "meshsal/meshsal.h"
#include "saliency/query_groups.h"
#include "saliency/saliency.h"
#include "test_util.h"

using namespace meshsal;
using namespace meshsal::gpu;

namespace {

vk::Context& context() {
  static std::unique_ptr<vk::Context> ctx = std::make_unique<vk::Context>(-1, true);
  return *ctx;
}

template <class T>
std::vector<T> download(const vk::Buffer& b, size_t n) {
  std::vector<T> out(n);
  b.download(out.data(), n * sizeof(T));
  return out;
}

// A mesh's device inputs as the fast filter takes them.
struct Inputs {
  uint32_t nv = 0, np = 0;
  BoundingBox box;
  double extent[3];
  vk::Buffer pos, flags, pos32;
  Inputs(vk::Context& ctx, const Mesh& mesh) {
    const std::vector<uint8_t> is_point = referenced_vertices(mesh);
    box = mesh_points_bbox(mesh, is_point);
    nv = uint32_t(mesh.vertex_count());
    std::vector<double> p(4 * nv);
    std::vector<float> p32(4 * nv, 0.0f);
    std::vector<uint32_t> f(nv);
    for (uint32_t v = 0; v < nv; ++v) {
      for (int a = 0; a < 3; ++a) {
        p[4 * v + a] = double(mesh.positions[3 * v + a]) - box.min[a];
        p32[4 * v + a] = mesh.positions[3 * v + a];
      }
      p[4 * v + 3] = std::sin(0.37 * v);  // values to sum
      f[v] = is_point[v];
      np += is_point[v];
    }
    for (int a = 0; a < 3; ++a) extent[a] = box.max[a] - box.min[a];
    pos = vk::Buffer(ctx, p.size() * 8, "test positions");
    flags = vk::Buffer(ctx, f.size() * 4, "test flags");
    pos32 = vk::Buffer(ctx, p32.size() * 4, "test float positions");
    pos.upload(p.data(), p.size() * 8);
    flags.upload(f.data(), f.size() * 4);
    pos32.upload(p32.data(), p32.size() * 4);
  }
};

// Runs the device steps for cells of edge `cell` (pieces of `piece` points) and holds each
// to its host twin.
void check_steps(vk::Context& ctx, const Mesh& mesh, double cell, uint32_t piece, int factor,
                 const std::string& what) {
  INFO(what << ", cell " << cell << ", piece " << piece << ", factor " << factor);
  const uint64_t before = vk::validation_message_count();
  Inputs in(ctx, mesh);
  const FastGrid grid = plan_fast_grid(in.extent, cell);
  const double radius = 12 * cell;  // 2 sigma at sigma/6 cells
  const GridPlan qplan = plan_grid(in.extent, 3 * cell, in.np, ctx.properties.limits.maxStorageBufferRange / 4 - 1);
  vk::Buffer counts = vk::Buffer::host_visible(ctx, kFastCounts * 4, "test counts");
  vk::DescriptorPool pool(ctx, FastCells::kSets + FastGroups::kSets + GridBuilder::kSets + CandidateBound::kSets,
                          FastCells::kBuffers + FastGroups::kBuffers + GridBuilder::kBuffers + CandidateBound::kBuffers);
  FastCells cells(ctx, pool, {&in.pos, &in.flags, &in.pos32}, counts, in.nv, in.np, grid.cells(), piece);
  FastGroups groups(ctx, pool, cells, counts, grid.cells(), factor);
  vk::Buffer qstarts, qsorted(ctx, size_t(in.np) * 32, "test"), qcell(ctx, size_t(in.np) * 4, "test");
  GridBuilder qgrid(ctx, pool, {&cells.cell_pos, &cells.is_cell, &qstarts, &qsorted, &qcell}, in.np, qplan.cells());
  CandidateBound bound(ctx, pool, qstarts, counts, qplan.cells(), kCountMostCandidates);
  vk::submit(ctx, "test", [&](VkCommandBuffer cmd) {
    vkCmdFillBuffer(cmd, counts.handle(), 0, VK_WHOLE_SIZE, 0);
    vk::barrier(cmd);
    cells.record(ctx, cmd, grid, in.box.min);
    groups.record(ctx, cmd, grid);
    qgrid.record(ctx, cmd, qplan, in.np);
    bound.record(ctx, cmd, qplan, radius);
  });
  const std::vector<uint32_t> n = download<uint32_t>(counts, kFastCounts);

  // The cells and pieces: the host's runs of the same sorted keys.
  const std::vector<uint32_t> sorted = download<uint32_t>(cells.sorted_keys(), in.np);
  CHECK(std::is_sorted(sorted.begin(), sorted.end()));
  const FastRuns host = fast_cell_runs(sorted, in.np, grid.cells(), piece);
  const uint32_t m = uint32_t(host.cell_key.size()), pieces = uint32_t(host.piece_cell.size());
  REQUIRE(n[kCountCells] == m);
  REQUIRE(n[kCountPieces] == pieces);
  CHECK(download<uint32_t>(cells.cell_key, m) == host.cell_key);
  CHECK(download<uint32_t>(cells.cell_piece, m + 1) == host.cell_piece);
  CHECK(download<uint32_t>(cells.piece_start, pieces + 1) == host.piece_start);
  CHECK(download<uint32_t>(cells.piece_cell, pieces) == host.piece_cell);
  if (piece < 100) CHECK(pieces > m);  // some cell was cut (the cases' cells hold more)
  // Each cell's point count and value sum, from the order the sort gave.
  const std::vector<uint32_t> order = download<uint32_t>(cells.order(), in.np);
  const std::vector<double> pos = download<double>(in.pos, 4 * size_t(in.nv));
  const std::vector<double> count = download<double>(cells.cell_count, m);
  const std::vector<double> cpos = download<double>(cells.cell_pos, 4 * size_t(m));
  const std::vector<uint32_t> is_cell = download<uint32_t>(cells.is_cell, in.np);
  for (uint32_t c = 0; c < m; ++c) {
    const uint32_t b = host.piece_start[host.cell_piece[c]], e = host.piece_start[host.cell_piece[c + 1]];
    double sum = 0;
    for (uint32_t i = b; i < e; ++i) sum += pos[4 * size_t(order[i]) + 3];
    CHECK(count[c] == double(e - b));
    CHECK(std::abs(cpos[4 * size_t(c) + 3] - sum) <= 1e-12 * (e - b));
  }
  CHECK(std::count(is_cell.begin(), is_cell.end(), 1u) == m);
  CHECK(std::all_of(is_cell.begin(), is_cell.begin() + m, [](uint32_t f) { return f == 1; }));

  // The query groups: group_cells() of the same keys.
  const uint64_t dims[3] = {grid.nx, grid.ny, grid.nz};
  const sweep::QueryGroups gr = group_cells(host.cell_key, dims, factor);
  const uint32_t ng = uint32_t(gr.start.size() - 1);
  REQUIRE(n[kCountGroups] == ng);
  CHECK(download<uint32_t>(groups.group_start, ng + 1) == gr.start);
  CHECK(download<uint32_t>(groups.group_cell(), m) == gr.cell);
  std::vector<uint32_t> of_cell(m);
  for (uint32_t g = 0; g < ng; ++g)
    for (uint32_t i = gr.start[g]; i < gr.start[g + 1]; ++i) of_cell[gr.cell[i]] = g;
  CHECK(download<uint32_t>(groups.cell_group, m) == of_cell);

  // The candidate bound: most_candidates() over the query grid's starts.
  const std::vector<uint32_t> starts = download<uint32_t>(qstarts, qplan.cells() + 1);
  CHECK(starts.back() == m);
  CHECK(n[kCountMostCandidates] == most_candidates(qplan, starts, radius));
  CHECK(n[kCountMostCandidates] > 0);
  CHECK(vk::validation_message_count() == before);
}

}  // namespace

TEST_CASE("gpu fast steps: cells, pieces, groups and the candidate bound match their host twins",
          "[gpu][fast]") {
  vk::Context& ctx = context();
  const Mesh sphere = make_bumpy_sphere(4);
  check_steps(ctx, sphere, 0.02, 4096, 2, "bumpy sphere");
  check_steps(ctx, sphere, 0.2, 3, 2, "bumpy sphere, pieces of 3");
  check_steps(ctx, sphere, 0.3, 7, 1, "bumpy sphere, a group per cell");
  check_steps(ctx, sphere, 0.1, 2, 3, "bumpy sphere, groups of 3^3 cells");
  check_steps(ctx, sphere, 100.0, 1000, 2, "bumpy sphere, one cell of every point");
  Mesh loose = make_plane_with_bump(2.0, 50, 0.3, 0.2);
  loose.positions.insert(loose.positions.begin() + 30, {0.5f, 0.5f, 9.0f});  // not a mesh point
  for (auto& t : loose.triangles)
    if (t >= 10) ++t;
  check_steps(ctx, loose, 0.2, 4, 2, "plane with a loose vertex");
}

TEST_CASE("gpu fast steps: the same under forced staging", "[gpu][fast]") {
  vk::Context ctx(-1, true);
  ctx.use_staging = true;
  check_steps(ctx, make_bumpy_sphere(3), 0.5, 3, 2, "bumpy sphere, staged");
}

TEST_CASE("gpu fast: the host waits only for the submissions of queries", "[gpu][fast]") {
  for (bool staging : {false, true}) {
    INFO("staging " << staging);
    vk::Context ctx(-1, true);
    ctx.use_staging = staging;
    const Mesh mesh = make_bumpy_sphere(4);
    SaliencyOptions opt;
    opt.method = Method::Fast;
    opt.threads = 2;
    opt.smoothed = false;  // one filter: the phases are the last filter's
    uint64_t slices = 0;
    opt.progress = [&](const char* stage, double) { slices += std::string(stage) == "gaussian sweep"; };
    const SaliencyResult together = compute_saliency_gpu(ctx, mesh, opt);
    uint64_t queries = 0, others = 0;
    for (const auto& p : ctx.fast_phases) (p.name == "queries" ? queries : others) += p.waits;
    // One wait per submission of queries (each reports progress once); the cells, groups,
    // grid and bound of every sigma but the first, and each sigma's finish, ride on them.
    CHECK(queries == slices);
    CHECK(slices >= opt.scales.size());
    // Outside them: the first sigma's preparation and the center-surround maps, staged or
    // not (the counts and the pair sums are in host memory: read without a copy).
    CHECK(others == 2);

    // Submitted apart (the bench's timing): the same maps, bit for bit.
    ctx.fast_phase_timing = true;
    const SaliencyResult apart = compute_saliency_gpu(ctx, mesh, opt);
    CHECK(apart.saliency == together.saliency);
    CHECK(apart.pairs == together.pairs);
    CHECK(apart.raw == together.raw);
  }
}
