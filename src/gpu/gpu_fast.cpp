// meshsal: --method fast on a Vulkan device (see gpu_fast.h).
#include "gpu/gpu_fast.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/timer.h"
#include "gpu/gpu_fast_cells.h"
#include "gpu/gpu_grid.h"
#include "gpu/gpu_slices.h"
#include "gpu/gpu_sweep.h"
#include "gpu/shader_interfaces.h"
#include "gpu/vk_compute.h"
#include "saliency/gaussian_filter_fast.h"
#include "saliency/query_groups.h"
#include "saliency/sparse_cells.h"  // usable_cell(): the CPU path's cells, the same here

#include "fast_center_surround_comp.h"
#include "fast_finish_comp.h"
#include "fast_group_centroids_comp.h"
#include "fast_query_comp.h"
#include "core/cancel.h"

namespace meshsal::gpu {

namespace {

constexpr uint32_t kLocal = 64;  // local_size_x of the shaders
using shader::CenterSurroundPush;  // the push blocks: gpu/shader_interfaces.h
using shader::FinishPush;
using shader::QueryPush;
using shader::RangePush;

// The most candidates any query can walk: the aggregates in the (2r+1)^3 cells around any
// cell of the query grid, r = ceil(radius / h) + 3 (fast_query.comp walks the rows of the
// ball's cells around a box of at most 2 cells in x and 1 in y and z: a subset). Sliding
// sums along x, y and z over the cell counts.
uint64_t most_candidates(const GridPlan& g, const std::vector<uint32_t>& starts, double radius) {
  const int64_t r = int64_t(std::ceil(radius / g.h)) + 3;
  const int64_t nx = g.nx, ny = g.ny, nz = g.nz;
  std::vector<uint32_t> a(size_t(nx * ny * nz)), b(a.size());
  auto at = [&](int64_t x, int64_t y, int64_t z) { return size_t(x + nx * (y + ny * z)); };
  for (int64_t z = 0; z < nz; ++z)
    for (int64_t y = 0; y < ny; ++y) {
      const size_t row = at(0, y, z);
      for (int64_t x = 0; x < nx; ++x)
        a[row + x] = starts[row + std::min(x + r, nx - 1) + 1] - starts[row + std::max<int64_t>(x - r, 0)];
    }
  for (int64_t z = 0; z < nz; ++z)  // along y: a window of 2r+1 rows
    for (int64_t x = 0; x < nx; ++x) {
      uint64_t run = 0;
      for (int64_t y = 0; y < std::min(r, ny); ++y) run += a[at(x, y, z)];
      for (int64_t y = 0; y < ny; ++y) {
        if (y + r < ny) run += a[at(x, y + r, z)];
        b[at(x, y, z)] = uint32_t(run);
        if (y - r >= 0) run -= a[at(x, y - r, z)];
      }
    }
  uint64_t most = 0;
  for (int64_t y = 0; y < ny; ++y)  // along z
    for (int64_t x = 0; x < nx; ++x) {
      uint64_t run = 0;
      for (int64_t z = 0; z < std::min(r, nz); ++z) run += b[at(x, y, z)];
      for (int64_t z = 0; z < nz; ++z) {
        if (z + r < nz) run += b[at(x, y, z + r)];
        most = std::max(most, run);
        if (z - r >= 0) run -= b[at(x, y, z - r)];
      }
    }
  return most;
}

// The float input coordinates per vertex (vec4), which the centroids are summed from.
vk::Buffer upload_float_positions(vk::Context& ctx, const Mesh& mesh) {
  const size_t nv = mesh.vertex_count();
  std::vector<float> p4(4 * nv, 0.0f);
  for (size_t v = 0; v < nv; ++v)
    for (int a = 0; a < 3; ++a) p4[4 * v + a] = mesh.positions[3 * v + a];
  vk::Buffer b(ctx, p4.size() * 4, "the float positions");
  b.upload(p4.data(), p4.size() * 4);
  return b;
}

// Adds a phase's seconds and host waits to ctx.fast_phases and restarts the clock.
struct PhaseClock {
  Timer t;
  uint64_t waits;
};
void phase(vk::Context& ctx, const char* name, PhaseClock& c) {
  auto& list = ctx.fast_phases;
  auto it = std::find_if(list.begin(), list.end(), [&](const auto& p) { return p.name == name; });
  if (it == list.end()) it = list.insert(list.end(), {name, 0.0, 0});
  it->seconds += c.t.seconds();
  it->waits += ctx.host_waits - c.waits;
  c.t.restart();
  c.waits = ctx.host_waits;
}

// Everything one sigma needs besides the aggregates.
struct SigmaJob {
  double sigma;
  uint32_t k, nsig, nv, np;
  const double* extent;
};

// G[k][v] for one sigma into g; returns its pairs.
uint64_t filter_one_sigma(vk::Context& ctx, const vk::Buffer& pos, const FastInputs& in,
                          const BoundingBox& box, const SigmaJob& job, vk::Buffer& g,
                          const SaliencyOptions& options, const char* stage) {
  const double s = job.sigma;
  const FastFilterParams params;
  PhaseClock clock{Timer(), ctx.host_waits};
  const FastGrid grid = plan_fast_grid(job.extent, usable_cell(box, s / params.cells_per_sigma));
  FastCells fc = aggregate_cells(ctx, in, job.nv, job.np, grid, box.min);
  phase(ctx, "cells", clock);
  const uint32_t m = fc.cells;
  const bool dense = double(job.np) >= params.points_per_query_cell * double(m);

  // Dense: the queries are the query groups' centroids (grouped on the host, as the CPU
  // groups its cells), and each cell knows its group for the extrapolation.
  uint32_t groups = 0;
  vk::Buffer group_pos, cell_group;
  if (dense) {
    const uint64_t dims[3] = {grid.nx, grid.ny, grid.nz};
    const sweep::QueryGroups gr = group_cells(fc.cell_key, dims, params.query_factor);
    groups = uint32_t(gr.start.size() - 1);
    std::vector<uint32_t> of_cell(m);
    for (uint32_t g = 0; g < groups; ++g)
      for (uint32_t i = gr.start[g]; i < gr.start[g + 1]; ++i) of_cell[gr.cell[i]] = g;
    vk::Buffer group_start(ctx, gr.start.size() * 4, "the fast method's query groups"),
        group_cell(ctx, gr.cell.size() * 4, "the fast method's query groups");
    group_start.upload(gr.start.data(), gr.start.size() * 4);
    group_cell.upload(gr.cell.data(), gr.cell.size() * 4);
    cell_group = vk::Buffer(ctx, size_t(m) * 4, "the fast method's query groups");
    cell_group.upload(of_cell.data(), of_cell.size() * 4);
    group_pos = vk::Buffer(ctx, size_t(groups) * 32, "the query groups' centroids");
    auto& k_groups = vk::cached_kernel<shader::FastGroupCentroids>(ctx, spv_fast_group_centroids_comp, sizeof spv_fast_group_centroids_comp, "fast_group_centroids");
    vk::DescriptorPool gpool(ctx, 1, 5);
    VkDescriptorSet s_groups =
        gpool.bind(k_groups, {&fc.cell_pos, &fc.cell_count, &group_start, &group_cell, &group_pos});
    vk::submit(ctx, stage, [&](VkCommandBuffer cmd) {
      RangePush rp{0, 0};
      vk::dispatch(ctx, cmd, k_groups, s_groups, &rp, 0, groups, kLocal);
    });
  }
  const uint32_t queries = dense ? groups : job.np;
  phase(ctx, "query groups", clock);

  // The aggregates on a grid of cells of a quarter of the cutoff radius (as on the CPU).
  vk::Buffer ones(ctx, size_t(m) * 4, "the fast method's cell flags");
  {
    std::vector<uint32_t> one(m, 1u);
    ones.upload(one.data(), one.size() * 4);
  }
  vk::Buffer qstarts, qsorted(ctx, size_t(m) * 32, "the sorted cell aggregates"),
      qcell(ctx, size_t(m) * 4, "the sorted cell indices");
  std::vector<uint32_t> starts;
  const GridPlan qg = build_gpu_grid(ctx, {&fc.cell_pos, &ones, &qstarts, &qsorted, &qcell}, m, m,
                                     job.extent, 0.5 * s, &starts);
  const double radius = 2 * s;
  const uint32_t fast_window_candidates = std::max<uint32_t>(1, ctx.fast_window_candidates);
  const uint64_t most = m <= fast_window_candidates ? m : most_candidates(qg, starts, radius);
  const uint32_t windows = uint32_t(std::max<uint64_t>(1, (most + fast_window_candidates - 1) / fast_window_candidates));
  phase(ctx, "query grid", clock);

  vk::Buffer sums(ctx, size_t(queries) * (dense ? 8 : 2) * 8, "the fast method's sums");
  vk::Buffer pairs(ctx, size_t(queries) * 4, "the pair counts");
  auto& k_query = vk::cached_kernel<shader::FastQuery>(ctx, spv_fast_query_comp, sizeof spv_fast_query_comp, "fast_query");
  auto& k_finish = vk::cached_kernel<shader::FastFinish>(ctx, spv_fast_finish_comp, sizeof spv_fast_finish_comp, "fast_finish");
  vk::DescriptorPool pool(ctx, 4, 16);
  VkDescriptorSet s_query =
      pool.bind(k_query, {&qsorted, &qcell, &qstarts, &fc.cell_count, dense ? &group_pos : &pos,
                          &fc.order, &sums, &pairs});
  // (sparse: the group buffers are not read; the cell's stand in for the binding)
  VkDescriptorSet s_finish =
      pool.bind(k_finish, {&sums, dense ? &group_pos : &fc.cell_pos, &fc.piece_start, &fc.piece_cell,
                           &fc.order, &pos, &g, dense ? &cell_group : &fc.piece_cell});

  // Submissions of a range of queries each: the first small and timed, the next ones
  // sized from the measured rate to about ctx.submission_target_s (gpu_slices.h).
  // The cutoff's shell, as gaussian_filter_fast() sets it (params.shell_cells cells deep).
  const double t = params.shell_cells * grid.cell;
  QueryPush qp{0, 0, qg.nx, qg.ny, qg.nz, dense ? 1u : 0u, 0, 0, qg.h, 4 * s * s, radius,
               1.0 / (2 * s * s), t > 0 ? (2 * s - t) * (2 * s - t) : INFINITY,
               t > 0 ? s * s * std::exp(-2.0) / (2 * s * t) : 0.0};
  double budget = std::max(64.0, std::min(4096.0, double(queries) / 16));
  const double total = double(queries) * windows;
  double done = 0;
  for (uint32_t w = 0; w < windows; ++w) {
    qp.ord_lo = w * fast_window_candidates;
    qp.ord_hi = qp.ord_lo + fast_window_candidates;
    for (uint32_t at = 0; at < queries;) {
      const uint32_t next = uint32_t(std::min<double>(queries, at + std::max(1.0, std::floor(budget))));
      const Timer t;
      vk::submit(ctx, stage, [&](VkCommandBuffer cmd) {
        if (w == 0 && at == 0) {
          vkCmdFillBuffer(cmd, sums.handle(), 0, VK_WHOLE_SIZE, 0);
          vkCmdFillBuffer(cmd, pairs.handle(), 0, VK_WHOLE_SIZE, 0);
          vk::barrier(cmd);
        }
        vk::dispatch(ctx, cmd, k_query, s_query, &qp, at, next, kLocal);
      });
      budget = next_budget(budget, next - at, t.seconds(), ctx.submission_target_s);
      done += next - at;
      at = next;
      if (options.progress) options.progress(stage, (job.k + done / total) / job.nsig);
      throw_if_cancelled();  // between submissions: nothing of this one is still running
    }
  }
  phase(ctx, "queries", clock);
  vk::submit(ctx, stage, [&](VkCommandBuffer cmd) {
    FinishPush fp{0, 0, dense ? 1u : 0u, 0, 1.0 / (s * s)};
    vk::dispatch(ctx, cmd, k_finish, s_finish, &fp, 0, dense ? fc.pieces : job.np, kLocal);
  });
  std::vector<uint32_t> per_query(queries);
  pairs.download(per_query.data(), per_query.size() * 4);
  phase(ctx, "finish", clock);
  // Every query counts at least its own cell (a centroid at distance 0, or the vertex's
  // own cell's centroid within sqrt(3)/6 sigma): 0 means it was never swept.
  return total_swept_pairs(per_query);
}

}  // namespace

uint64_t fast_filter_bytes(uint64_t nv, uint64_t np, uint64_t nsig) {
  const uint64_t grid_cells = std::max<uint64_t>(uint64_t(1) << 20, 4 * np) + 1;
  // per point at most: the query grid (4 + 36), the sums (64), the pair counts (4), the
  // query groups (start, cell, cell's group, centroid: 4 + 4 + 4 + 32)
  return nv * 16 + nsig * nv * 8 + fast_cells_bytes(nv, np) + np * (4 + 36 + 64 + 4 + 44) +
         grid_cells * 4 + gpu_grid_scratch_bytes(np, grid_cells);
}

uint64_t fast_filter(vk::Context& ctx, const Mesh& mesh, const vk::Buffer& pos,
                     const vk::Buffer& flags, uint32_t np, const BoundingBox& box,
                     const FastFilterPlan& plan, vk::Buffer& result,
                     const SaliencyOptions& options, const char* stage) {
  const uint32_t nv = uint32_t(mesh.vertex_count());
  const uint32_t nsig = uint32_t(plan.sigmas.size());
  const uint32_t nout = uint32_t(plan.out_a.size());
  bool bad = nsig == 0 || nout == 0 || nout > 16 || plan.out_b.size() != nout;
  for (uint32_t o = 0; !bad && o < nout; ++o)
    bad = plan.out_a[o] < 0 || plan.out_a[o] >= int(nsig) || plan.out_b[o] >= int(nsig);
  if (bad)
    throw Error("internal: a GPU fast filter plan of " + std::to_string(nsig) + " sigmas and " +
                std::to_string(nout) + " outputs");
  ctx.fast_phases.clear();
  PhaseClock clock{Timer(), ctx.host_waits};
  double extent[3];
  for (int a = 0; a < 3; ++a) extent[a] = box.max[a] - box.min[a];
  vk::Buffer pos32 = upload_float_positions(ctx, mesh);
  // A buffer per sigma (all of them in one passed lavapipe's 128 MiB per buffer at 2
  // million vertices), zero for the vertices that are not mesh points.
  std::vector<vk::Buffer> g;
  for (uint32_t k = 0; k < nsig; ++k) g.emplace_back(ctx, size_t(nv) * 8, "the fast method's averages");
  vk::submit(ctx, stage, [&](VkCommandBuffer cmd) {
    for (const vk::Buffer& b : g) vkCmdFillBuffer(cmd, b.handle(), 0, VK_WHOLE_SIZE, 0);
  });
  const FastInputs in{&pos, &flags, &pos32};
  phase(ctx, "setup", clock);
  uint64_t pairs = 0;
  for (uint32_t k = 0; k < nsig; ++k)
    pairs += filter_one_sigma(ctx, pos, in, box, {plan.sigmas[k], k, nsig, nv, np, extent}, g[k],
                              options, stage);
  clock = {Timer(), ctx.host_waits};

  auto& k_cs = vk::cached_kernel<shader::FastCenterSurround>(ctx, spv_fast_center_surround_comp, sizeof spv_fast_center_surround_comp, "fast_center_surround");
  vk::DescriptorPool pool(ctx, nout, 4 * nout);
  std::vector<VkDescriptorSet> sets;
  for (uint32_t o = 0; o < nout; ++o) {
    const int a = plan.out_a[o], b = plan.out_b[o];
    sets.push_back(pool.bind(k_cs, {&g[size_t(a)], &g[size_t(b < 0 ? a : b)], &flags, &result}));
  }
  vk::submit(ctx, stage, [&](VkCommandBuffer cmd) {
    for (uint32_t o = 0; o < nout; ++o) {
      CenterSurroundPush cp{0, 0, o, plan.out_b[o] >= 0 ? 1u : 0u};
      vk::dispatch(ctx, cmd, k_cs, sets[o], &cp, 0, nv, kLocal);
    }
  });
  phase(ctx, "center-surround", clock);
  return pairs;
}

}  // namespace meshsal::gpu
