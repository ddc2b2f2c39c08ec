// meshsal: saliency on a Vulkan device (see gpu_saliency.h). The stages and their names
// follow compute_saliency_cpu(); each shader names the CPU function it mirrors.
#include "meshsal/gpu_saliency.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "meshsal/adjacency.h"
#include "meshsal/curvature.h"
#include "meshsal/error.h"
#include "meshsal/gpu_sweep.h"
#include "meshsal/mesh_points.h"
#include "meshsal/vk_buffer.h"
#include "meshsal/vk_compute.h"

#include "final_sum_comp.h"
#include "global_index_comp.h"
#include "grid_key_comp.h"
#include "grid_scan_comp.h"
#include "grid_scatter_comp.h"
#include "grid_sort_cells_comp.h"
#include "local_max_comp.h"
#include "map_max_comp.h"
#include "map_max_final_comp.h"
#include "mbar_comp.h"
#include "selftest_comp.h"
#include "sweep8_comp.h"
#include "sweep8_mixed_comp.h"
#include "sweep8_rows_comp.h"
#include "sweep8_rows_mixed_comp.h"
#include "sweepn_comp.h"

namespace meshsal {

namespace {

using Clock = std::chrono::steady_clock;

#define KERNEL(ctx, spv, bindings, push) \
  vk::cached_kernel(ctx, spv, sizeof(spv), bindings, sizeof(push), #spv)

constexpr uint32_t kLocal = 64;     // local_size_x of the per-item shaders
constexpr int kMaxSigmas = 16;      // sweep.glsl's arrays
constexpr int kMaxScales = 16;      // mbar.comp's factor layout

// Push blocks: each begins with {base, n} (vk::dispatch fills them in).
struct GridKeyPush { uint32_t base, n, nx, ny, nz, pad; double h; };
struct RangePush { uint32_t base, n; };
using gpu::SweepPush;
struct ScalesPush { uint32_t base, n, nscales; };
struct GroupsPush { uint32_t base, n, groups; };

// The sweep's plan (sweep.glsl's Params): sigmas largest first, like the CPU's KernelPlan.
struct SweepParams {
  double cut2[kMaxSigmas];
  double coef[kMaxSigmas];
  int32_t parent[kMaxSigmas];
  int32_t out_a[kMaxSigmas];
  int32_t out_b[kMaxSigmas];
  double bcoef;  // sweep8: b = exp(-d2 * bcoef) (sweep_point_default in gaussian_filter.cpp)
};

// The uniform grid of build_spatial_grid() (spatial_grid.cpp): cells of min_cell, grown
// by 1.25 while there are more than max(2^20, 4 points) cells (or more than one buffer
// holds); coordinates relative to the bbox minimum.
struct GridPlan {
  uint32_t nx = 1, ny = 1, nz = 1;
  double h = 1;
  uint64_t cells() const { return uint64_t(nx) * ny * nz; }
};

GridPlan plan_grid(const double extent[3], double min_cell, uint64_t points, uint64_t limit) {
  const double max_cells = std::min<double>(std::max<double>(1 << 20, 4.0 * double(points)),
                                            double(limit));
  GridPlan g;
  double cell = min_cell;
  for (;;) {
    double cells = 1;
    for (int a = 0; a < 3; ++a) cells *= std::floor(extent[a] / cell) + 1;
    if (cells <= max_cells) break;
    cell *= 1.25;
  }
  g.h = cell;
  g.nx = uint32_t(std::floor(extent[0] / cell)) + 1;
  g.ny = uint32_t(std::floor(extent[1] / cell)) + 1;
  g.nz = uint32_t(std::floor(extent[2] / cell)) + 1;
  return g;
}

// Everything on the device for one saliency computation.
struct DeviceMesh {
  uint32_t nv = 0, np = 0;  // vertices, mesh points
  vk::Buffer pos, flags, offsets, neighbors;
  vk::Buffer cell_count, starts, key, slot, sorted_pos, sorted_vertex;
  vk::Buffer params, result, pairs;
  vk::Buffer sorted_pos32, bound;  // the mixed-precision sweep's (gpu_sweep.h)
};

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Builds the grid for `radius` over the current pos[] (counting sort on the device) and
// returns its plan and the downloaded cell starts (for planning the sweep slices).
GridPlan build_grid(vk::Context& ctx, vk::DescriptorPool& pool, DeviceMesh& m,
                    const double extent[3], double cell, std::vector<uint32_t>* starts_out) {
  GridPlan g = plan_grid(extent, cell, m.np, ctx.properties.limits.maxStorageBufferRange / 4 - 1);
  const uint32_t cells = static_cast<uint32_t>(g.cells());
  m.cell_count = vk::Buffer(ctx, size_t(cells) * 4, "the grid cell counts");
  m.starts = vk::Buffer(ctx, size_t(cells + 1) * 4, "the grid cell starts");

  auto& k_key = KERNEL(ctx, spv_grid_key_comp, 5, GridKeyPush);
  auto& k_scan = KERNEL(ctx, spv_grid_scan_comp, 2, RangePush);
  auto& k_scatter = KERNEL(ctx, spv_grid_scatter_comp, 6, RangePush);
  auto& k_order = KERNEL(ctx, spv_grid_sort_cells_comp, 3, RangePush);
  VkDescriptorSet s_key = pool.bind(k_key, {&m.pos, &m.flags, &m.cell_count, &m.key, &m.slot});
  VkDescriptorSet s_scan = pool.bind(k_scan, {&m.cell_count, &m.starts});
  VkDescriptorSet s_scatter = pool.bind(
      k_scatter, {&m.pos, &m.key, &m.slot, &m.starts, &m.sorted_pos, &m.sorted_vertex});
  VkDescriptorSet s_order = pool.bind(k_order, {&m.starts, &m.sorted_pos, &m.sorted_vertex});
  vk::submit(ctx, "grid", [&](VkCommandBuffer cmd) {
    vkCmdFillBuffer(cmd, m.cell_count.handle(), 0, VK_WHOLE_SIZE, 0);
    vk::barrier(cmd);
    GridKeyPush kp{0, 0, g.nx, g.ny, g.nz, 0, g.h};
    vk::dispatch(ctx, cmd, k_key, s_key, &kp, 0, m.nv, kLocal);
    vk::barrier(cmd);
    // One work group scans all cells.
    RangePush sp{0, cells};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, k_scan.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, k_scan.layout, 0, 1, &s_scan, 0, nullptr);
    vkCmdPushConstants(cmd, k_scan.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof sp, &sp);
    vkCmdDispatch(cmd, 1, 1, 1);
    vk::barrier(cmd);
    RangePush cp{0, 0};
    vk::dispatch(ctx, cmd, k_scatter, s_scatter, &cp, 0, m.nv, kLocal);
    vk::barrier(cmd);
    RangePush op{0, 0};
    vk::dispatch(ctx, cmd, k_order, s_order, &op, 0, cells, kLocal);
    vk::barrier(cmd);
  });
  starts_out->resize(size_t(cells) + 1);
  m.starts.download(starts_out->data(), starts_out->size() * 4);
  if ((*starts_out)[cells] != m.np)
    throw Error("internal: the GPU grid holds " + std::to_string((*starts_out)[cells]) +
                " points instead of " + std::to_string(m.np));
  return g;
}

// Splits the sorted points into submissions of at most ~budget candidate pairs each
// (whole cells), so no single submission runs into a driver time-out.
std::vector<uint32_t> plan_slices(const GridPlan& g, const std::vector<uint32_t>& starts,
                                  double radius, double budget) {
  const int r = int(std::ceil(radius / g.h));
  std::vector<uint32_t> cuts{0};
  double acc = 0;
  const int nx = g.nx, ny = g.ny, nz = g.nz;
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) {
        uint32_t c = uint32_t(x) + g.nx * (uint32_t(y) + g.ny * uint32_t(z));
        uint32_t pts = starts[c + 1] - starts[c];
        if (!pts) continue;
        double cand = 0;
        int x0 = std::max(x - r, 0), x1 = std::min(x + r, nx - 1);
        for (int zz = std::max(z - r, 0); zz <= std::min(z + r, nz - 1); ++zz)
          for (int yy = std::max(y - r, 0); yy <= std::min(y + r, ny - 1); ++yy) {
            uint32_t row = g.nx * (uint32_t(yy) + g.ny * uint32_t(zz));
            cand += starts[row + x1 + 1] - starts[row + x0];
          }
        if (acc > 0 && acc + cand * pts > budget) {
          cuts.push_back(starts[c]);
          acc = 0;
        }
        acc += cand * pts;
      }
  cuts.push_back(starts.back());
  return cuts;
}

// Whether the sweep runs a lane per point over rows shared by the subgroup (sweep8_rows:
// the default plan on CPU devices, or as Context::sweep_variant says) rather than a
// subgroup per point.
bool shared_rows(const vk::Context& ctx, bool fast8) {
  if (!fast8) return false;
  return ctx.sweep_variant < 0 ? ctx.info.vk_type == VK_PHYSICAL_DEVICE_TYPE_CPU
                               : ctx.sweep_variant == 0;
}

// One neighbour sweep over the grid (gaussian_filter): result[o][v] as the plan in
// m.params says; returns the number of pairs strictly inside `radius` (v itself included).
uint64_t sweep(vk::Context& ctx, vk::DescriptorPool& pool, DeviceMesh& m, const GridPlan& g,
               const std::vector<uint32_t>& starts, bool fast8, bool mixed, const SweepParams& params,
               uint32_t nsig, uint32_t nout,
               double radius, const SaliencyOptions& options, const char* stage) {
  // sweep8 has the default plan built in; sweepn is specialised to this plan (count and
  // parents), so the driver unrolls it to exactly the exps it needs.
  std::vector<int32_t> spec;
  if (!fast8) {
    spec.push_back(int32_t(nsig));
    for (uint32_t e = 0; e < 16; ++e) spec.push_back(e < nsig ? params.parent[e] : -1);
  }
  // CPU devices (lavapipe) run the default plan with a lane per point over rows shared by
  // the subgroup (sweep8_rows); otherwise each point gets a subgroup (see sweep.glsl).
  const bool rows = shared_rows(ctx, fast8);
  // Mixed precision (the default plan only) adds the float points and the error bounds.
  auto& k = mixed ? (rows ? KERNEL(ctx, spv_sweep8_rows_mixed_comp, 8, SweepPush)
                          : KERNEL(ctx, spv_sweep8_mixed_comp, 8, SweepPush))
            : rows  ? KERNEL(ctx, spv_sweep8_rows_comp, 6, SweepPush)
            : fast8 ? KERNEL(ctx, spv_sweep8_comp, 6, SweepPush)
                  : vk::cached_kernel(ctx, spv_sweepn_comp, sizeof(spv_sweepn_comp), 6,
                                      sizeof(SweepPush), "sweepn", spec);
  // A lane per point (rows): 64 points per work group whatever the subgroup size. A
  // subgroup per point: sized by the size the device reports; the shader strides over
  // the subgroups the driver really made, so another size still sweeps every point.
  const uint32_t per_group = rows ? kLocal : kLocal / ctx.subgroup_size;
  std::vector<const vk::Buffer*> bufs{&m.sorted_pos, &m.sorted_vertex, &m.starts, &m.params,
                                      &m.result, &m.pairs};
  if (mixed) bufs.insert(bufs.end(), {&m.sorted_pos32, &m.bound});
  VkDescriptorSet set = pool.bind(k, bufs);
  // Candidate pairs per submission: about a second on lavapipe, and on a GPU with slow
  // FP64 (consumer cards run doubles at 1/32..1/64 rate) still well under the usual 2 s
  // driver watchdog; our own fence time-out is never near.
  const bool cpu_device = ctx.info.vk_type == VK_PHYSICAL_DEVICE_TYPE_CPU;
  const double budget = ctx.sweep_pairs_per_submission > 0 ? ctx.sweep_pairs_per_submission
                        : cpu_device                         ? 1e8
                                                             : 5e9;
  std::vector<uint32_t> cuts = plan_slices(g, starts, radius, budget);
  if (gpu::test_sweep_gap_at < m.np) {  // test hook: a plan that leaves one point out
    const uint32_t gap = gpu::test_sweep_gap_at;
    std::vector<uint32_t> holed;
    for (size_t s = 0; s + 1 < cuts.size(); ++s)
      if (gap >= cuts[s] && gap < cuts[s + 1]) {
        holed.insert(holed.end(), {cuts[s], gap, gap + 1, cuts[s + 1]});
      } else {
        holed.insert(holed.end(), {cuts[s], cuts[s + 1]});
      }
    cuts = holed;
  } else {
    std::vector<uint32_t> ranges;  // as [begin, end) pairs
    for (size_t s = 0; s + 1 < cuts.size(); ++s) ranges.insert(ranges.end(), {cuts[s], cuts[s + 1]});
    cuts = ranges;
  }
  SweepPush p{0, 0, g.nx, g.ny, g.nz, per_group, m.nv, nsig, nout, 0, g.h, radius * radius};
  for (size_t s = 0; s + 1 < cuts.size(); s += 2) {
    vk::submit(ctx, stage, [&](VkCommandBuffer cmd) {
      if (s == 0) {  // vertices that are not mesh points get 0, not stale memory; every
                     // point's pair count starts at 0 so that a point never swept shows
        vkCmdFillBuffer(cmd, m.result.handle(), 0, VK_WHOLE_SIZE, 0);
        vkCmdFillBuffer(cmd, m.pairs.handle(), 0, VK_WHOLE_SIZE, 0);
        if (mixed) vkCmdFillBuffer(cmd, m.bound.handle(), 0, VK_WHOLE_SIZE, 0);
        vk::barrier(cmd);
      }
      vk::dispatch(ctx, cmd, k, set, &p, cuts[s], cuts[s + 1], per_group);
    });
    if (options.progress) options.progress(stage, double(cuts[s + 1]) / std::max<uint32_t>(m.np, 1));
  }
  std::vector<uint32_t> pairs(m.np);
  m.pairs.download(pairs.data(), pairs.size() * 4);
  return gpu::total_swept_pairs(pairs);
}

// The sweep plan for `units` (sigmas in eps, any order): largest first, a sigma whose
// double is in the plan takes its weight from it (KernelPlan in gaussian_filter.cpp).
SweepParams make_params(const std::vector<double>& units, double eps, std::vector<int>* plan_of_unit) {
  std::vector<int> idx(units.size());
  for (size_t i = 0; i < idx.size(); ++i) idx[i] = int(i);
  std::stable_sort(idx.begin(), idx.end(), [&](int a, int b) { return units[a] > units[b]; });
  SweepParams p{};
  plan_of_unit->assign(units.size(), -1);
  for (size_t e = 0; e < idx.size(); ++e) {
    double s = units[idx[e]] * eps;
    p.coef[e] = 1.0 / (2.0 * s * s);
    p.cut2[e] = 4.0 * s * s;
    p.parent[e] = -1;
    for (size_t q = 0; q < e; ++q)
      if (std::fabs(units[idx[q]] * eps - 2.0 * s) <= 1e-12 * s) {
        p.parent[e] = int(q);
        break;
      }
    (*plan_of_unit)[idx[e]] = int(e);
  }
  return p;
}

std::vector<double> to_vector(const std::vector<double>& v, size_t begin, size_t count) {
  return std::vector<double>(v.begin() + begin, v.begin() + begin + count);
}

}  // namespace

std::vector<vk::DeviceInfo> gpu_devices() { return vk::list_devices(); }

SaliencyResult compute_saliency_gpu(const Mesh& mesh, const SaliencyOptions& options,
                                    bool validation) {
  vk::Context ctx(options.device, validation);
  return compute_saliency_gpu(ctx, mesh, options);
}

SaliencyResult compute_saliency_gpu(vk::Context& ctx, const Mesh& mesh,
                                    const SaliencyOptions& options) {
  SaliencyResult res;
  res.backend_name = ctx.info.name;
  const size_t nv = mesh.vertex_count();
  if (nv >= 0xffffffffu / 32) throw Error("mesh too large for the GPU path (vertex count)");
  const size_t nsc = options.scales.size();
  if (nsc == 0) throw Error("at least one scale is needed");
  if (nsc > kMaxScales) throw Error("the GPU path takes at most 16 scales");

  // --- curvature (CPU): the same functions as compute_saliency_cpu --------------------
  auto t0 = Clock::now();
  res.is_point = referenced_vertices(mesh);
  res.eps = scale_unit(mesh, res.is_point, options.eps_frac);
  Adjacency adj = build_adjacency(mesh);
  std::vector<double> normals = vertex_normals(mesh);
  res.curvature = mean_curvature(mesh, adj, normals, options.threads);
  res.stages.push_back({"curvature", seconds_since(t0)});

  // --- the sweep plan: the distinct s_i and 2 s_i (filter_sigma_units), in eps ----------
  std::vector<double> units;
  for (double s : options.scales) {
    units.push_back(s);
    units.push_back(2 * s);
  }
  std::sort(units.begin(), units.end());
  units.erase(std::unique(units.begin(), units.end()), units.end());
  if (units.size() > size_t(kMaxSigmas))
    throw Error("the GPU path takes at most 16 distinct sigmas (s_i and 2 s_i)");
  const double eps = res.eps;
  std::vector<int> plan_of_unit;
  SweepParams params = make_params(units, eps, &plan_of_unit);
  auto plan_index = [&](double u) {
    for (size_t k = 0; k < units.size(); ++k)
      if (units[k] == u) return plan_of_unit[k];
    throw Error("internal: sigma missing from the GPU sweep plan");
  };
  for (size_t i = 0; i < nsc; ++i) {
    params.out_a[i] = plan_index(options.scales[i]);
    params.out_b[i] = plan_index(2 * options.scales[i]);
  }
  // sweep8.comp hard-codes the plan of the default sigmas 12,10,8 (exp), 6,5,4,3,2.
  const bool fast8 = units == std::vector<double>{2, 3, 4, 5, 6, 8, 10, 12};
  if (fast8) {  // the same doubles as sweep_point_default() derives from its plan
    const double e = std::sqrt(1.0 / (2.0 * params.coef[0])) / 12.0;
    params.bcoef = 1.0 / (2.0 * e * e * 14400.0);
  }
  const double radius = 2 * units.back() * eps;

  // --- upload: positions relative to the bbox minimum in double, as the CPU grid has them
  t0 = Clock::now();
  if (!ctx.has_float64)
    throw Error("Vulkan device '" + ctx.info.name + "' has no 64-bit floats in shaders "
                "(shaderFloat64), which the GPU path needs to match the CPU path");
  if (!ctx.subgroup_arithmetic || ctx.subgroup_size == 0 || ctx.subgroup_size > kLocal ||
      kLocal % ctx.subgroup_size != 0)
    throw Error("Vulkan device '" + ctx.info.name + "' lacks subgroup arithmetic in compute "
                "shaders (subgroup size " + std::to_string(ctx.subgroup_size) + "), which the GPU path needs");
  BoundingBox bb = mesh_points_bbox(mesh, res.is_point);
  double extent[3];
  for (int a = 0; a < 3; ++a) extent[a] = bb.max[a] - bb.min[a];
  DeviceMesh m;
  m.nv = static_cast<uint32_t>(nv);
  std::vector<double> pos4(4 * nv);
  std::vector<uint32_t> flags(nv);
  for (size_t v = 0; v < nv; ++v) {
    for (int a = 0; a < 3; ++a) pos4[4 * v + a] = double(mesh.positions[3 * v + a]) - bb.min[a];
    pos4[4 * v + 3] = res.curvature[v];
    flags[v] = res.is_point[v];
    m.np += res.is_point[v];
  }

  // Memory: refuse up front what cannot fit the largest device-local heap.
  const uint64_t need = uint64_t(nv) * (32 * 2 + 4 * 6 + 8 * nsc + 8 + 8) +
                        uint64_t(adj.neighbors.size()) * 4 + (uint64_t(32) << 20);
  if (ctx.info.device_local_bytes && need > ctx.info.device_local_bytes * 0.9)
    throw Error("mesh too large for '" + ctx.info.name + "': needs about " +
                std::to_string(need >> 20) + " MiB of device memory, the device has " +
                std::to_string(ctx.info.device_local_bytes >> 20) +
                " MiB; use the CPU path (--backend cpu)");

  const uint32_t groups = static_cast<uint32_t>((nv + kLocal - 1) / kLocal);
  m.pos = vk::Buffer(ctx, nv * 32, "the vertex positions");
  m.flags = vk::Buffer(ctx, nv * 4, "the mesh-point flags");
  m.offsets = vk::Buffer(ctx, adj.offsets.size() * 4, "the adjacency offsets");
  m.neighbors = vk::Buffer(ctx, adj.neighbors.size() * 4, "the adjacency lists");
  m.key = vk::Buffer(ctx, nv * 4, "the cell keys");
  m.slot = vk::Buffer(ctx, nv * 4, "the cell slots");
  m.sorted_pos = vk::Buffer(ctx, size_t(m.np) * 32, "the sorted points");
  m.sorted_vertex = vk::Buffer(ctx, size_t(m.np) * 4, "the sorted point indices");
  m.params = vk::Buffer(ctx, sizeof(SweepParams), "the sweep parameters");
  m.result = vk::Buffer(ctx, nv * nsc * 8, "the raw saliency maps");
  m.pairs = vk::Buffer(ctx, size_t(m.np) * 4, "the pair counts");
  vk::Buffer partial_max(ctx, size_t(groups) * nsc * 8, "the partial maxima");
  vk::Buffer map_max(ctx, nsc * 8, "the map maxima");
  vk::Buffer global_index(ctx, nsc * 4, "the global maxima");
  vk::Buffer partial(ctx, size_t(groups) * nsc * 16, "the local-maximum sums");
  vk::Buffer factor(ctx, 32 * 8, "the suppression factors");
  vk::Buffer saliency(ctx, nv * 8, "the saliency");

  m.pos.upload(pos4.data(), pos4.size() * 8);
  m.flags.upload(flags.data(), flags.size() * 4);
  m.offsets.upload(adj.offsets.data(), adj.offsets.size() * 4);
  m.neighbors.upload(adj.neighbors.data(), adj.neighbors.size() * 4);
  m.params.upload(&params, sizeof params);
  res.stages.push_back({"upload", seconds_since(t0)});

  vk::DescriptorPool pool(ctx, 32, 128);

  // --- grid + sweep (gaussian_filter), with the center-surround maps ------------------
  t0 = Clock::now();
  std::vector<uint32_t> starts;
  // Cells of a fifth of the radius for the shared-rows sweep (rows are clipped to the
  // ball's chord, so smaller cells mean fewer candidates, and a smaller box around the
  // subgroup's points; on lavapipe, igea_134k, 1/4 to 1/8 were within the noise of each
  // other, 1/5 looked best, 1/3 and 1/2 were slower); half the radius for a subgroup per
  // point, where short rows would leave lanes idle.
  const bool rows = shared_rows(ctx, fast8);
  GridPlan g = build_grid(ctx, pool, m, extent, (rows ? 0.2 : 0.5) * radius, &starts);
  res.stages.push_back({"grid", seconds_since(t0)});

  t0 = Clock::now();
  // Mixed precision where its accuracy is worked out (sweep.glsl): the default sigmas.
  // Auto takes it on GPUs; on CPU devices (lavapipe) the double sweep was faster (a float
  // lane costs lavapipe about what a double one does there: loads and masked stores of
  // the sums dominate, and the mixed sweep adds the bound sums and the cutoff check).
  const bool mixed = fast8 && (options.precision == Precision::Mixed ||
                               (options.precision == Precision::Auto &&
                                ctx.info.vk_type != VK_PHYSICAL_DEVICE_TYPE_CPU));
  res.mixed_precision = mixed;
  if (mixed) {
    m.sorted_pos32 = vk::Buffer(ctx, size_t(m.np) * 16, "the float points");
    m.bound = vk::Buffer(ctx, size_t(nv) * nsc * 4, "the error bounds");
    gpu::make_float_points(ctx, pool, m.sorted_pos, m.sorted_pos32, m.np, bb.min);
  }
  res.pairs = sweep(ctx, pool, m, g, starts, fast8, mixed, params,
                    static_cast<uint32_t>(units.size()), static_cast<uint32_t>(nsc), radius,
                    options, "gaussian sweep");
  res.stages.push_back({"gaussian sweep", seconds_since(t0)});
  if (mixed) {
    t0 = Clock::now();
    gpu::NearTieBuffers nb{&m.result, &m.flags, &m.bound, &m.offsets, &m.neighbors,
                           &m.sorted_pos, &m.sorted_vertex, &m.starts, &m.params, &m.pairs, &m.pos};
    SweepPush p{0, 0, g.nx, g.ny, g.nz, 0, m.nv, static_cast<uint32_t>(units.size()),
                static_cast<uint32_t>(nsc), 0, g.h, radius * radius};
    res.rechecked = gpu::recheck_near_ties(ctx, pool, nb, m.nv, static_cast<uint32_t>(nsc), p);
    res.stages.push_back({"near-tie recheck", seconds_since(t0)});
  }

  // --- suppress() of every map and the final sum ------------------------------------
  t0 = Clock::now();
  {
    vk::Buffer& raw = m.result;
    auto& k_mx = KERNEL(ctx, spv_map_max_comp, 3, GroupsPush);
    auto& k_mf = KERNEL(ctx, spv_map_max_final_comp, 2, GroupsPush);
    auto& k_gi = KERNEL(ctx, spv_global_index_comp, 4, RangePush);
    auto& k_lm = KERNEL(ctx, spv_local_max_comp, 7, GroupsPush);
    auto& k_mb = KERNEL(ctx, spv_mbar_comp, 3, GroupsPush);
    auto& k_fs = KERNEL(ctx, spv_final_sum_comp, 5, ScalesPush);
    VkDescriptorSet s_mx = pool.bind(k_mx, {&raw, &m.flags, &partial_max});
    VkDescriptorSet s_mf = pool.bind(k_mf, {&partial_max, &map_max});
    VkDescriptorSet s_gi = pool.bind(k_gi, {&raw, &m.flags, &map_max, &global_index});
    VkDescriptorSet s_lm = pool.bind(
        k_lm, {&raw, &m.flags, &map_max, &global_index, &m.offsets, &m.neighbors, &partial});
    VkDescriptorSet s_mb = pool.bind(k_mb, {&partial, &map_max, &factor});
    VkDescriptorSet s_fs = pool.bind(k_fs, {&raw, &m.flags, &factor, &saliency, &m.pos});
    const uint32_t n = m.nv, ns = static_cast<uint32_t>(nsc);
    vk::submit(ctx, "suppression", [&](VkCommandBuffer cmd) {
      vkCmdFillBuffer(cmd, global_index.handle(), 0, VK_WHOLE_SIZE, 0xffffffffu);
      vk::barrier(cmd);
      GroupsPush mx{0, 0, groups};
      vk::dispatch(ctx, cmd, k_mx, s_mx, &mx, 0, n, kLocal, ns);
      vk::barrier(cmd);
      GroupsPush mf{0, 0, groups};
      vk::dispatch(ctx, cmd, k_mf, s_mf, &mf, 0, ns * kLocal, kLocal);
      vk::barrier(cmd);
      RangePush gi{0, 0};
      vk::dispatch(ctx, cmd, k_gi, s_gi, &gi, 0, n, kLocal, ns);
      vk::barrier(cmd);
      GroupsPush lm{0, 0, groups};
      vk::dispatch(ctx, cmd, k_lm, s_lm, &lm, 0, n, kLocal, ns);
      vk::barrier(cmd);
      GroupsPush mb{0, 0, groups};
      vk::dispatch(ctx, cmd, k_mb, s_mb, &mb, 0, ns * kLocal, kLocal);
      vk::barrier(cmd);
      ScalesPush fs{0, 0, ns};
      vk::dispatch(ctx, cmd, k_fs, s_fs, &fs, 0, n, kLocal);
      vk::barrier(cmd);
    });
  }
  res.stages.push_back({"suppression", seconds_since(t0)});

  // --- download the maps and S (before the smoothing sweep reuses the result buffer) --
  t0 = Clock::now();
  std::vector<double> raw_h(nv * nsc);
  res.saliency.resize(nv);
  m.result.download(raw_h.data(), raw_h.size() * 8);
  saliency.download(res.saliency.data(), nv * 8);
  res.raw.resize(nsc);
  for (size_t i = 0; i < nsc; ++i) res.raw[i] = to_vector(raw_h, i * nv, nv);
  res.stages.push_back({"download", seconds_since(t0)});

  // --- smoothed saliency G(S, 3 eps) for simplification ---------------------------
  if (options.smoothed) {
    t0 = Clock::now();
    std::vector<int> plan1;
    SweepParams sp = make_params({3.0}, eps, &plan1);
    sp.out_a[0] = 0;
    sp.out_b[0] = -1;
    m.params.upload(&sp, sizeof sp);
    GridPlan g2 = build_grid(ctx, pool, m, extent, 0.5 * 6 * eps, &starts);
    sweep(ctx, pool, m, g2, starts, false, false, sp, 1, 1, 6 * eps, options, "smoothing");
    res.smoothed.resize(nv);
    m.result.download(res.smoothed.data(), nv * 8);
    for (size_t v = 0; v < nv; ++v)
      if (!res.is_point[v]) res.smoothed[v] = 0;
    res.stages.push_back({"smoothing", seconds_since(t0)});
  }
  return res;
}

std::vector<float> gpu_selftest(vk::Context& ctx, const std::vector<float>& x, float a) {
  struct Push { uint32_t base, n; float a; };
  auto& k = KERNEL(ctx, spv_selftest_comp, 2, Push);
  vk::Buffer bx(ctx, x.size() * 4, "x"), by(ctx, x.size() * 4, "y");
  bx.upload(x.data(), x.size() * 4);
  vk::DescriptorPool pool(ctx, 1, 2);
  VkDescriptorSet set = pool.bind(k, {&bx, &by});
  Push p{0, 0, a};
  vk::submit(ctx, "selftest", [&](VkCommandBuffer cmd) {
    vk::dispatch(ctx, cmd, k, set, &p, 0, static_cast<uint32_t>(x.size()), kLocal);
  });
  std::vector<float> y(x.size());
  by.download(y.data(), y.size() * 4);
  return y;
}

}  // namespace meshsal
