// meshsal: --method fast on a Vulkan device (see gpu_fast.h).
#include "gpu/gpu_fast.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/parallel.h"
#include "core/timer.h"
#include "gpu/gpu_fast_bound.h"
#include "gpu/gpu_fast_cells.h"
#include "gpu/gpu_fast_groups.h"
#include "gpu/gpu_grid.h"
#include "gpu/gpu_slices.h"
#include "gpu/gpu_sweep.h"
#include "gpu/shader_interfaces.h"
#include "gpu/vk_compute.h"
#include "saliency/gaussian_filter_fast.h"
#include "saliency/sparse_cells.h"  // usable_cell(): the CPU path's cells, the same here

#include "fast_center_surround_comp.h"
#include "fast_finish_comp.h"
#include "fast_query_comp.h"
#include "pair_sums_comp.h"
#include "core/cancel.h"

namespace meshsal::gpu {

namespace {

constexpr uint32_t kLocal = 64;  // local_size_x of the shaders
constexpr uint32_t kPairGroup = 256;  // pair_sums.comp's local_size_x: queries per partial sum
using shader::CenterSurroundPush;  // the push blocks: gpu/shader_interfaces.h
using shader::FinishPush;
using shader::PairSumsPush;
using shader::QueryPush;

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

// What the host plans for one sigma before anything runs: the grid of its cells, and the
// query grid of its aggregates (planned for as many points as there are mesh points, a
// bound of its cells: the cell count is found on the device).
struct SigmaPlan {
  double sigma;
  FastGrid cells;
  GridPlan queries;
};

// What the device found for one sigma (the counts buffer, read after the submission that
// prepared it) and what the host derives from it.
struct SigmaCounts {
  uint32_t cells, pieces, groups;
  bool dense;
  uint32_t queries;
  uint32_t window, windows;  // candidates a dispatch visits, and how many windows of them
};

SigmaCounts read_counts(const vk::Context& ctx, const vk::Buffer& counts, uint32_t np) {
  uint32_t c[kFastCounts];
  counts.download(c, sizeof c);  // host memory: a copy, no submission
  const FastFilterParams params;
  SigmaCounts out;
  out.cells = c[kCountCells];
  out.pieces = c[kCountPieces];
  out.groups = c[kCountGroups];
  if (out.cells == 0 || out.cells > np || out.pieces < out.cells || out.groups > out.cells)
    throw Error("internal: the GPU fast method found " + std::to_string(out.cells) + " cells, " +
                std::to_string(out.pieces) + " pieces and " + std::to_string(out.groups) +
                " query groups for " + std::to_string(np) + " mesh points");
  out.dense = double(np) >= params.points_per_query_cell * double(out.cells);
  out.queries = out.dense ? out.groups : np;
  out.window = std::max<uint32_t>(1, ctx.fast_window_candidates);
  const uint64_t most = out.cells <= out.window ? out.cells : c[kCountMostCandidates];
  out.windows = uint32_t(std::max<uint64_t>(1, (most + out.window - 1) / out.window));
  return out;
}

// The arrays of one filter, made once for all its sigmas, and the steps that use them.
class FastDevice {
 public:
  FastDevice(const FastDevice&) = delete;
  FastDevice& operator=(const FastDevice&) = delete;
  FastDevice(vk::Context& ctx, const FastInputs& in, uint32_t nv, uint32_t np,
             const std::vector<SigmaPlan>& plans, const FastFilterParams& params)
      : counts_(ctx, kFastCounts * 4, "the fast method's counts"),
        counts_host_(vk::Buffer::host_visible(ctx, kFastCounts * 4, "the fast method's counts")),
        pool_(ctx, FastCells::kSets + FastGroups::kSets + GridBuilder::kSets + CandidateBound::kSets,
              FastCells::kBuffers + FastGroups::kBuffers + GridBuilder::kBuffers + CandidateBound::kBuffers),
        cells_(ctx, pool_, in, counts_, nv, np, most(plans, true)),
        groups_(ctx, pool_, cells_, counts_, most(plans, true), params.query_factor),
        qsorted_(ctx, size_t(np) * 32, "the sorted cell aggregates"),
        qcell_(ctx, size_t(np) * 4, "the sorted cell indices"),
        qgrid_(ctx, pool_, {&cells_.cell_pos, &cells_.is_cell, &qstarts_, &qsorted_, &qcell_}, np,
               most(plans, false)),
        bound_(ctx, pool_, qstarts_, counts_, most(plans, false), kCountMostCandidates),
        np_(np) {}

  // Records everything one sigma needs before its queries: its cells, query groups, query
  // grid and candidate bound; the counts buffer then holds what read_counts() reads.
  void record_prepare(vk::Context& ctx, VkCommandBuffer cmd, const SigmaPlan& p, const BoundingBox& box) {
    vkCmdFillBuffer(cmd, counts_.handle(), 0, VK_WHOLE_SIZE, 0);
    vk::barrier(cmd);
    cells_.record(ctx, cmd, p.cells, box.min);
    groups_.record(ctx, cmd, p.cells);
    qgrid_.record(ctx, cmd, p.queries, np_);
    bound_.record(ctx, cmd, p.queries, 2 * p.sigma);
    // The counts into host memory (the submission's end makes the copy visible to the host).
    const VkBufferCopy c{0, 0, kFastCounts * 4};
    vkCmdCopyBuffer(cmd, counts_.handle(), counts_host_.handle(), 1, &c);
  }

  // What the last preparation found: read after its submission, without a copy.
  const vk::Buffer& counts() const { return counts_host_; }
  FastCells& cells() { return cells_; }
  FastGroups& groups() { return groups_; }
  vk::Buffer& qstarts() { return qstarts_; }
  vk::Buffer& qsorted() { return qsorted_; }
  vk::Buffer& qcell() { return qcell_; }

 private:
  // The most cells of the sigmas' cell grids (fine) or query grids.
  static uint64_t most(const std::vector<SigmaPlan>& plans, bool fine) {
    uint64_t m = 1;
    for (const SigmaPlan& p : plans) m = std::max(m, fine ? p.cells.cells() : p.queries.cells());
    return m;
  }
  // The counts the steps write and read (device memory: their atomics and reads stay on
  // the device) and their copy in host memory.
  vk::Buffer counts_, counts_host_;
  vk::DescriptorPool pool_;
  FastCells cells_;
  FastGroups groups_;
  vk::Buffer qstarts_, qsorted_, qcell_;
  GridBuilder qgrid_;
  CandidateBound bound_;
  uint32_t np_;
};

}  // namespace

vk::Buffer upload_float_positions(vk::Context& ctx, const Mesh& mesh, unsigned threads) {
  return upload_float_positions(ctx, mesh.positions.data(), mesh.vertex_count(), threads);
}

vk::Buffer upload_float_positions(vk::Context& ctx, const float* positions, size_t nv, unsigned threads) {
  vk::Buffer b(ctx, nv * 16, "the float positions");
  // Packed straight into the staging area (or the mapping), whole vertices: its chunks
  // start at multiples of 64 KiB (vk_staging.h).
  b.upload_with(nv * 16, [&](char* to, size_t first, size_t n) {
    const size_t v0 = first / 16;
    parallel_for(n / 16, threads, 1 << 16, [&](size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i) {
        const float* p = positions + 3 * (v0 + i);
        const float xyzw[4] = {p[0], p[1], p[2], 0.0f};
        std::memcpy(to + 16 * i, xyzw, 16);
      }
    });
  });
  return b;
}

uint64_t fast_filter_bytes(uint64_t nv, uint64_t np, uint64_t nsig) {
  const uint64_t grid_cells = std::max<uint64_t>(uint64_t(1) << 20, 4 * np) + 1;
  // per sigma: the averages and the pair sums (16 B per 256 queries); per point at most:
  // the query grid's sorted cells (32 + 4), the sums (32: 8 doubles a group, at most a group
  // per 2 points; 16 sparse) and the pair counts (4); the cells, the groups; the grid's
  // scratch and the candidate bound's
  return nsig * (nv * 8 + np / 16) + np * (36 + 32 + 4) + fast_cells_bytes(nv, np) +
         fast_groups_bytes(np) + grid_cells * 4 + gpu_grid_scratch_bytes(np, grid_cells) +
         CandidateBound::bytes(grid_cells);
}

uint64_t fast_filter(vk::Context& ctx, const Mesh& mesh, const vk::Buffer& pos,
                     const vk::Buffer& pos32, const vk::Buffer& flags, uint32_t np, const BoundingBox& box,
                     const FastFilterPlan& plan, vk::Buffer& result,
                     const SaliencyOptions& options, const char* stage) {
  const uint32_t nv = uint32_t(mesh.vertex_count());
  const uint32_t nsig = uint32_t(plan.sigmas.size());
  const uint32_t nout = uint32_t(plan.out_a.size());
  bool bad = nsig == 0 || nout == 0 || nout > 16 || plan.out_b.size() != nout || np == 0;
  for (uint32_t o = 0; !bad && o < nout; ++o)
    bad = plan.out_a[o] < 0 || plan.out_a[o] >= int(nsig) || plan.out_b[o] >= int(nsig);
  if (bad)
    throw Error("internal: a GPU fast filter plan of " + std::to_string(nsig) + " sigmas and " +
                std::to_string(nout) + " outputs over " + std::to_string(np) + " mesh points");
  ctx.fast_phases.clear();
  PhaseClock clock{Timer(), ctx.host_waits};
  const FastFilterParams params;
  double extent[3];
  for (int a = 0; a < 3; ++a) extent[a] = box.max[a] - box.min[a];
  // Every sigma planned on the host first: the arrays are made once, for the largest.
  std::vector<SigmaPlan> plans;
  for (double s : plan.sigmas)
    plans.push_back({s, plan_fast_grid(extent, usable_cell(box, s / params.cells_per_sigma)),
                     plan_grid(extent, 0.5 * s, np, ctx.properties.limits.maxStorageBufferRange / 4 - 1)});
  const FastInputs in{&pos, &flags, &pos32};
  FastDevice dev(ctx, in, nv, np, plans, params);
  // Per sigma its averages (a buffer each: all of them in one passed lavapipe's 128 MiB
  // per buffer at 2 million vertices; zero for the vertices that are not mesh points).
  std::vector<vk::Buffer> g;
  for (uint32_t k = 0; k < nsig; ++k) g.emplace_back(ctx, size_t(nv) * 8, "the fast method's averages");
  // The pair counts per query, summed per 256 queries after each sigma (pair_sums.comp)
  // into host memory the host reads once at the end.
  vk::Buffer pairs(ctx, size_t(np) * 4, "the pair counts");
  const uint32_t pair_groups = (np + kPairGroup - 1) / kPairGroup;
  vk::Buffer pair_sums = vk::Buffer::host_visible(ctx, size_t(nsig) * pair_groups * 16, "the pair sums");
  const double dense_groups = params.points_per_query_cell > 0
                                  ? std::min<double>(np, std::floor(np / params.points_per_query_cell))
                                  : double(np);
  vk::Buffer sums(ctx, size_t(std::max(2.0 * np, 8.0 * dense_groups)) * 8, "the fast method's sums");

  auto& k_query = vk::cached_kernel<shader::FastQuery>(ctx, spv_fast_query_comp, sizeof spv_fast_query_comp, "fast_query");
  auto& k_finish = vk::cached_kernel<shader::FastFinish>(ctx, spv_fast_finish_comp, sizeof spv_fast_finish_comp, "fast_finish");
  FastCells& fc = dev.cells();
  FastGroups& gr = dev.groups();
  // Per sigma and mode (0 sparse, 1 dense): the query and finish sets.
  auto& k_pairs = vk::cached_kernel<shader::PairSums>(ctx, spv_pair_sums_comp, sizeof spv_pair_sums_comp, "pair_sums");
  vk::DescriptorPool pool(ctx, 4 * nsig + 1, 32 * nsig + 2);
  VkDescriptorSet s_pairs = pool.bind(k_pairs, {&pairs, &pair_sums});
  std::vector<VkDescriptorSet> s_query(2 * nsig), s_finish(2 * nsig);
  for (uint32_t k = 0; k < nsig; ++k)
    for (int dense = 0; dense < 2; ++dense) {
      s_query[2 * k + dense] =
          pool.bind(k_query, {&dev.qsorted(), &dev.qcell(), &dev.qstarts(), &fc.cell_count,
                              dense ? &gr.group_pos : &pos, &fc.order(), &sums, &pairs});
      // (sparse: the group buffers are not read; the cells' stand in for the binding)
      s_finish[2 * k + dense] =
          pool.bind(k_finish, {&sums, dense ? &gr.group_pos : &fc.cell_pos, &fc.piece_start, &fc.piece_cell,
                               &fc.order(), &pos, &g[k], dense ? &gr.cell_group : &fc.piece_cell});
    }
  // Separate submissions per phase only when the bench times them (Context::fast_phase_timing);
  // otherwise each sigma's finish and the next one's preparation ride on its last query
  // submission, so the host waits once per submission of queries.
  const bool separate = ctx.fast_phase_timing;
  std::vector<uint32_t> queries(nsig);  // per sigma: its pair counts' length
  vk::submit(ctx, stage, [&](VkCommandBuffer cmd) {
    for (const vk::Buffer& b : g) vkCmdFillBuffer(cmd, b.handle(), 0, VK_WHOLE_SIZE, 0);
    vk::barrier(cmd);
    dev.record_prepare(ctx, cmd, plans[0], box);
  });
  phase(ctx, "setup and the first sigma's cells", clock);

  for (uint32_t k = 0; k < nsig; ++k) {
    const double s = plans[k].sigma;
    const SigmaCounts sc = read_counts(ctx, dev.counts(), np);
    queries[k] = sc.queries;
    const GridPlan& qg = plans[k].queries;
    const uint32_t mode = sc.dense ? 1 : 0;
    // The cutoff's shell, as gaussian_filter_fast() sets it (params.shell_cells cells deep).
    const double t = params.shell_cells * plans[k].cells.cell;
    const double radius = 2 * s;
    QueryPush qp{0, 0, qg.nx, qg.ny, qg.nz, mode, 0, 0, qg.h, 4 * s * s, radius,
                 1.0 / (2 * s * s), t > 0 ? (2 * s - t) * (2 * s - t) : INFINITY,
                 t > 0 ? s * s * std::exp(-2.0) / (2 * s * t) : 0.0};
    // Submissions of a range of queries each: the first small and timed, the next ones
    // sized from the measured rate to about ctx.submission_target_s (gpu_slices.h).
    double budget = std::max(64.0, std::min(4096.0, double(sc.queries) / 16));
    const double total = double(sc.queries) * sc.windows;
    double done = 0;
    auto record_finish = [&](VkCommandBuffer cmd) {
      FinishPush fp{0, 0, mode, 0, 1.0 / (s * s)};
      vk::dispatch(ctx, cmd, k_finish, s_finish[2 * k + mode], &fp, 0, sc.dense ? sc.pieces : np, kLocal);
      PairSumsPush pp{0, 0, k * pair_groups};
      vk::dispatch(ctx, cmd, k_pairs, s_pairs, &pp, 0, sc.queries, kPairGroup);
      vk::barrier(cmd);
    };
    for (uint32_t w = 0; w < sc.windows; ++w) {
      qp.ord_lo = w * sc.window;
      qp.ord_hi = qp.ord_lo + sc.window;
      for (uint32_t at = 0; at < sc.queries;) {
        const uint32_t next = uint32_t(std::min<double>(sc.queries, at + std::max(1.0, std::floor(budget))));
        const bool last = w + 1 == sc.windows && next == sc.queries;
        const Timer timer;
        vk::submit(ctx, stage, [&](VkCommandBuffer cmd) {
          if (w == 0 && at == 0) {
            vkCmdFillBuffer(cmd, sums.handle(), 0, VkDeviceSize(sc.queries) * (sc.dense ? 8 : 2) * 8, 0);
            vkCmdFillBuffer(cmd, pairs.handle(), 0, VkDeviceSize(sc.queries) * 4, 0);
            vk::barrier(cmd);
          }
          vk::dispatch(ctx, cmd, k_query, s_query[2 * k + mode], &qp, at, next, kLocal);
          if (last && !separate) {
            vk::barrier(cmd);
            record_finish(cmd);
            if (k + 1 < nsig) dev.record_prepare(ctx, cmd, plans[k + 1], box);
          }
        });
        if (!last) budget = next_budget(budget, next - at, timer.seconds(), ctx.submission_target_s);
        done += next - at;
        at = next;
        if (options.progress) options.progress(stage, (k + done / total) / nsig);
        throw_if_cancelled();  // between submissions: nothing of this one is still running
      }
    }
    phase(ctx, "queries", clock);
    if (separate) {
      vk::submit(ctx, stage, [&](VkCommandBuffer cmd) { record_finish(cmd); });
      phase(ctx, "finish", clock);
      if (k + 1 < nsig) {
        vk::submit(ctx, stage, [&](VkCommandBuffer cmd) { dev.record_prepare(ctx, cmd, plans[k + 1], box); });
        phase(ctx, "cells, groups and grid", clock);
      }
    }
  }

  auto& k_cs = vk::cached_kernel<shader::FastCenterSurround>(ctx, spv_fast_center_surround_comp, sizeof spv_fast_center_surround_comp, "fast_center_surround");
  vk::DescriptorPool cs_pool(ctx, nout, 4 * nout);
  std::vector<VkDescriptorSet> sets;
  for (uint32_t o = 0; o < nout; ++o) {
    const int a = plan.out_a[o], b = plan.out_b[o];
    sets.push_back(cs_pool.bind(k_cs, {&g[size_t(a)], &g[size_t(b < 0 ? a : b)], &flags, &result}));
  }
  vk::submit(ctx, stage, [&](VkCommandBuffer cmd) {
    for (uint32_t o = 0; o < nout; ++o) {
      CenterSurroundPush cp{0, 0, o, plan.out_b[o] >= 0 ? 1u : 0u};
      vk::dispatch(ctx, cmd, k_cs, sets[o], &cp, 0, nv, kLocal);
    }
  });
  phase(ctx, "center-surround", clock);
  // Every query counts at least its own cell (a centroid at distance 0, or the vertex's
  // own cell's centroid within sqrt(3)/6 sigma): 0 means it was never swept.
  std::vector<double> part(size_t(nsig) * pair_groups * 2);
  pair_sums.download(part.data(), part.size() * 8);  // host memory: a copy, no submission
  uint64_t swept = 0;
  for (uint32_t k = 0; k < nsig; ++k) {
    double sum = 0, missed = 0;
    for (uint32_t i = 0; i < (queries[k] + kPairGroup - 1) / kPairGroup; ++i) {
      sum += part[2 * (size_t(k) * pair_groups + i)];
      missed += part[2 * (size_t(k) * pair_groups + i) + 1];
    }
    if (missed > 0)
      throw Error("internal: the GPU fast method left " + std::to_string(uint64_t(missed)) + " of " +
                  std::to_string(queries[k]) + " queries of sigma " + std::to_string(k) +
                  " unswept (pair count 0)");
    swept += uint64_t(sum);
  }
  phase(ctx, "pair counts", clock);
  return swept;
}

}  // namespace meshsal::gpu
