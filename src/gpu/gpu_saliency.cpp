// meshsal: saliency on a Vulkan device (see gpu_saliency.h). The stages and their names
// follow compute_saliency_cpu(); each shader names the CPU function it mirrors.
#include "gpu/gpu_saliency.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>

#include "core/adjacency.h"
#include "saliency/curvature.h"
#include "gpu/gpu_fp64_rate.h"
#include "meshsal/meshsal.h"
#include "gpu/gpu_curvature.h"
#include "gpu/gpu_fast.h"
#include "gpu/gpu_mesh_points.h"
#include "gpu/gpu_prestage.h"
#include "gpu/gpu_grid.h"
#include "gpu/gpu_layout_probe.h"
#include "gpu/gpu_session.h"
#include "gpu/gpu_slices.h"
#include "gpu/gpu_sweep.h"
#include "gpu/vk_staging.h"
#include "core/mesh_points.h"
#include "gpu/vk_buffer.h"
#include "gpu/shader_interfaces.h"
#include "gpu/vk_compute.h"
#include "core/timer.h"

#include "final_sum_comp.h"
#include "global_index_comp.h"
#include "local_max_comp.h"
#include "local_max_faces_comp.h"
#include "map_max_comp.h"
#include "map_max_final_comp.h"
#include "mbar_comp.h"
#include "sweep8_comp.h"
#include "sweep8_mixed_comp.h"
#include "sweep8_rows_comp.h"
#include "sweep8_rows_mixed_comp.h"
#include "sweepn_comp.h"
#include "core/cancel.h"

namespace meshsal {

namespace {


#define KERNEL(ctx, spv, shader) vk::cached_kernel<shader>(ctx, spv, sizeof(spv), #spv)

constexpr uint32_t kLocal = 64;     // local_size_x of the per-item shaders
constexpr int kMaxSigmas = 16;      // sweep.glsl's arrays
constexpr int kMaxScales = 16;      // mbar.comp's factor layout

// Push blocks: each begins with {base, n} (vk::dispatch fills them in); gpu/shader_interfaces.h.
namespace shader = gpu::shader;
using shader::GroupsPush;
using shader::RangePush;
using shader::ScalesPush;
using shader::SweepPush;

// The sweep's plan (sweep.glsl's Params): sigmas largest first, like the CPU's KernelPlan.
struct SweepParams {
  double cut2[kMaxSigmas];
  double coef[kMaxSigmas];
  int32_t parent[kMaxSigmas];
  int32_t out_a[kMaxSigmas];
  int32_t out_b[kMaxSigmas];
  double bcoef;  // sweep8: b = exp(-d2 * bcoef) (sweep_point_default in gaussian_filter.cpp)
};

// Everything on the device for one saliency computation.
struct DeviceMesh {
  uint32_t nv = 0, np = 0;  // vertices, mesh points
  vk::Buffer pos, flags, offsets, neighbors;
  vk::Buffer starts, sorted_pos, sorted_vertex;
  vk::Buffer params, result, pairs;
  vk::Buffer sorted_pos32, bound;  // the mixed-precision sweep's (gpu_sweep.h)
  // Where the device computes the curvature (see compute_saliency_gpu): the float
  // coordinates, the curvature and its incidence (the local maxima's neighbours in place of
  // the 1-rings).
  vk::Buffer pos32;
  std::unique_ptr<gpu::DeviceCurvature> curvature;
};

// Device bytes of one saliency computation: the buffers below, the largest grid
// plan_grid() allows (cell counts and starts), and the staging area when transfers use it.
uint64_t gpu_memory_estimate(uint64_t nv, uint64_t np, uint64_t nsc, uint64_t neighbors,
                             bool staging, bool mixed) {
  const uint64_t groups = (nv + kLocal - 1) / kLocal;
  uint64_t bytes = nv * (32 + 4 + 4 + 8 * nsc + 8) + np * (32 + 4 + 4) + neighbors * 4 +
                   groups * nsc * (8 + 16) + (uint64_t(1) << 16);
  const uint64_t cells = std::max<uint64_t>(uint64_t(1) << 20, 4 * np) + 1;
  bytes += cells * 4 + gpu_grid_scratch_bytes(nv, cells);
  if (mixed) bytes += np * 16 + nv * nsc * 4;  // float points, error bounds (gpu_sweep.h)
  if (staging) bytes += vk::staging_bytes_for(std::max(nv * 32, nv * nsc * 8));  // largest copy
  return bytes;
}

// Builds the grid of cells >= `cell` over the current pos[] (gpu_grid.h) and returns its
// plan and the downloaded cell starts (for planning the sweep slices).
GridPlan build_grid(vk::Context& ctx, DeviceMesh& m, const double extent[3], double cell,
                    std::vector<uint32_t>* starts_out) {
  return build_gpu_grid(ctx, {&m.pos, &m.flags, &m.starts, &m.sorted_pos, &m.sorted_vertex},
                        m.nv, m.np, extent, cell, starts_out);
}

// Whether the sweep runs a lane per point over rows shared by the subgroup (sweep8_rows)
// rather than a subgroup per point: as Context::sweep_variant says, else on CPU devices
// (lavapipe: rows, measured in docs/benchmarks.md) and on GPUs as timed once per context
// (gpu_layout_probe.h).
bool shared_rows(vk::Context& ctx, bool fast8, bool mixed) {
  if (!fast8) return false;
  if (ctx.sweep_variant >= 0) return ctx.sweep_variant == 0;
  if (ctx.info.vk_type == VK_PHYSICAL_DEVICE_TYPE_CPU) return true;
  return gpu::measured_sweep_variant(ctx, mixed) == 0;
}

// One neighbour sweep over the grid (gaussian_filter): result[o][v] as the plan in
// m.params says; returns the number of pairs strictly inside `radius` (v itself included).
// rows: the default plan (fast8) with a lane per point over shared rows (shared_rows()).
uint64_t sweep(vk::Context& ctx, vk::DescriptorPool& pool, DeviceMesh& m, const GridPlan& g,
               const std::vector<uint32_t>& starts, bool fast8, bool rows, bool mixed, const SweepParams& params,
               uint32_t nsig, uint32_t nout,
               double radius, const SaliencyOptions& options, const char* stage) {
  // sweep8 has the default plan built in; sweepn is specialised to this plan (count and
  // parents), so the driver unrolls it to exactly the exps it needs.
  std::vector<int32_t> spec;
  if (!fast8) {
    spec.push_back(int32_t(nsig));
    for (uint32_t e = 0; e < 16; ++e) spec.push_back(e < nsig ? params.parent[e] : -1);
  }
  if (rows && !fast8) throw Error("internal: the shared rows take the default plan only");
  // Mixed precision (the default plan only) adds the float points and the error bounds.
  auto& k = mixed ? (rows ? KERNEL(ctx, spv_sweep8_rows_mixed_comp, shader::Sweep8RowsMixed)
                          : KERNEL(ctx, spv_sweep8_mixed_comp, shader::Sweep8Mixed))
            : rows  ? KERNEL(ctx, spv_sweep8_rows_comp, shader::Sweep8Rows)
            : fast8 ? KERNEL(ctx, spv_sweep8_comp, shader::Sweep8)
                  : vk::cached_kernel<shader::SweepN>(ctx, spv_sweepn_comp, sizeof spv_sweepn_comp, "sweepn", spec);
  // A lane per point (rows): 64 points per work group whatever the subgroup size. A
  // subgroup per point: sized by the size the device reports; the shader strides over
  // the subgroups the driver really made, so another size still sweeps every point.
  const uint32_t per_group = rows ? kLocal : kLocal / ctx.subgroup_size;
  std::vector<const vk::Buffer*> bufs{&m.sorted_pos, &m.sorted_vertex, &m.starts, &m.params,
                                      &m.result, &m.pairs};
  if (mixed) bufs.insert(bufs.end(), {&m.sorted_pos32, &m.bound});
  VkDescriptorSet set = pool.bind(k, bufs);
  // Slices of whole cells, each one submission: the first small and timed, the rest
  // sized to ~ctx.submission_target_s of device time (gpu_slices.h); a fixed budget of
  // candidate pairs when ctx.sweep_pairs_per_submission says so (tests).
  const bool fixed = ctx.sweep_pairs_per_submission > 0;
  const SweepWork work = sweep_work(g, starts, radius);
  double budget = fixed ? ctx.sweep_pairs_per_submission
                        : first_slice_budget(ctx.info.vk_type == VK_PHYSICAL_DEVICE_TYPE_CPU,
                                             work.before.back());
  SweepPush p{0, 0, g.nx, g.ny, g.nz, per_group, m.nv, nsig, nout, 0, g.h, radius * radius};
  // Slice ends on multiples of kLocal points (the last at the end): the lane-per-point layout
  // shares a box among the points of a subgroup counted from the slice's start, and the box
  // decides where its sums of PER_STEP candidates begin. Cell-aligned, timed slices made the
  // sums' last bits depend on the machine's load.
  const auto slice_point = [&](size_t cut) {
    return cut + 1 == work.first.size() ? work.first[cut] : work.first[cut] / kLocal * kLocal;
  };
  ctx.sweep_slices = 0;
  ctx.sweep_longest_s = 0;
  for (size_t at = 0; at + 1 < work.first.size();) {
    const size_t next = next_cut(work, at, budget);
    const Timer t_slice;
    vk::submit(ctx, stage, [&](VkCommandBuffer cmd) {
      if (at == 0) {  // vertices that are not mesh points get 0, not stale memory; every
                      // point's pair count starts at 0 so that a point never swept shows
        vkCmdFillBuffer(cmd, m.result.handle(), 0, VK_WHOLE_SIZE, 0);
        vkCmdFillBuffer(cmd, m.pairs.handle(), 0, VK_WHOLE_SIZE, 0);
        if (mixed) vkCmdFillBuffer(cmd, m.bound.handle(), 0, VK_WHOLE_SIZE, 0);
        vk::barrier(cmd);
      }
      const uint32_t begin = slice_point(at), end = slice_point(next);
      const uint32_t gap = gpu::test_sweep_gap_at;  // test hook: a plan that leaves one point out
      if (gap >= begin && gap < end) {
        if (gap > begin) vk::dispatch(ctx, cmd, k, set, &p, begin, gap, per_group);
        if (gap + 1 < end) vk::dispatch(ctx, cmd, k, set, &p, gap + 1, end, per_group);
      } else {
        vk::dispatch(ctx, cmd, k, set, &p, begin, end, per_group);
      }
    });
    const double took = t_slice.seconds();  // host time: an upper bound of device time
    ctx.sweep_slices++;
    ctx.sweep_longest_s = std::max(ctx.sweep_longest_s, took);
    if (!fixed)
      budget = next_budget(budget, work.before[next] - work.before[at], took,
                           ctx.submission_target_s);
    at = next;
    if (options.progress) options.progress(stage, double(work.first[at]) / std::max<uint32_t>(m.np, 1));
    throw_if_cancelled();  // between submissions: nothing of this slice is still running
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

}  // namespace

std::vector<vk::DeviceInfo> gpu_devices() { return vk::list_devices(); }

// On the process's cached device (gpu_session.h): only the first call on a device pays its
// start-up (stage "device setup") and pipeline compilation.
SaliencyResult compute_saliency_gpu(const Mesh& mesh, const SaliencyOptions& options,
                                    bool validation) {
  gpu::DeviceLease lease = gpu::lease_device(options.device, validation);
  SaliencyResult res;
  try {
    res = compute_saliency_gpu(lease.context(), mesh, options);
  } catch (const std::exception& e) {
    lease.discard_if_broken(e.what());
    throw;
  }
  if (lease.opened()) res.stages.insert(res.stages.begin(), {"device setup", lease.open_seconds()});
  return res;
}

namespace {

// Whether a run of `method` on `ctx` uploads the float positions and the triangles: its
// curvature computed on the device, unless the device's memory decides otherwise
// (Method::Auto: as the fast method, which the meshes worth uploading ahead, the large
// ones, resolve to).
bool device_curvature_by_default(const vk::Context& ctx, Method method) {
  return method != Method::Exact || (ctx.exact_curvature_on_device >= 0 ? ctx.exact_curvature_on_device == 1
                                                                         : ctx.info.vk_type != VK_PHYSICAL_DEVICE_TYPE_CPU);
}

// Only on the cached context the run will lease (opened by the warm-up), where it is free;
// a failure that leaves it unusable drops it from the cache, as a run's does.
bool on_cached_device(const SaliencyOptions& options, const std::function<void(vk::Context&)>& body) {
  gpu::DeviceLease lease = gpu::lease_cached_device(options.device, false);
  if (!lease.held()) return false;
  try {
    body(lease.context());
  } catch (const std::exception& e) {
    lease.discard_if_broken(e.what());
    throw;
  }
  return true;
}

// `upload` on the cached context where a run with `options` would upload it itself.
bool prestage(const SaliencyOptions& options, const std::function<void(vk::Context&)>& upload) {
  bool uploaded = false;
  on_cached_device(options, [&](vk::Context& ctx) {
    if ((uploaded = device_curvature_by_default(ctx, options.method))) upload(ctx);
  });
  return uploaded;
}

}  // namespace

bool prestage_positions_gpu(const SaliencyOptions& options, const float* positions, size_t vertex_count) {
  return prestage(options, [&](vk::Context& ctx) {
    gpu::prestage_float_positions(ctx, positions, vertex_count, options.threads);
  });
}

bool prestage_triangles_gpu(const SaliencyOptions& options, const uint32_t* triangles, size_t triangle_count) {
  return prestage(options, [&](vk::Context& ctx) {
    gpu::prestage_triangles(ctx, triangles, triangle_count, options.threads);
  });
}

void drop_prestaged_gpu(const SaliencyOptions& options) {
  on_cached_device(options, [](vk::Context& ctx) { gpu::drop_prestaged(ctx); });
}

void warm_up_saliency_gpu(const SaliencyOptions& options) {
  gpu::DeviceLease lease = gpu::lease_device(options.device, false);
  const Mesh mesh = gpu::probe_sphere(2048);
  SaliencyOptions o = options;
  o.progress = nullptr;
  o.notice = nullptr;
  o.session = nullptr;
  o.tiles = 0;
  try {
    for (Method m : {Method::Exact, Method::Fast})
      if (options.method == Method::Auto || options.method == m) {
        o.method = m;
        compute_saliency_gpu(lease.context(), mesh, o);
      }
  } catch (const std::exception& e) {
    lease.discard_if_broken(e.what());
    throw;
  }
}

namespace {

// The sweep plan for `scales`: the distinct s_i and 2 s_i (filter_sigma_units), in eps.
struct SweepPlan {
  std::vector<double> units;
  SweepParams params{};
  bool fast8 = false;  // the default sigmas 2,3,4,5,6,8,10,12: sweep8's built-in plan
  double radius = 0;   // the largest cutoff, 2 * 12 eps by default
};

SweepPlan plan_sweep(const std::vector<double>& scales, double eps) {
  SweepPlan plan;
  std::vector<double>& units = plan.units;
  for (double s : scales) {
    units.push_back(s);
    units.push_back(2 * s);
  }
  std::sort(units.begin(), units.end());
  units.erase(std::unique(units.begin(), units.end()), units.end());
  if (units.size() > size_t(kMaxSigmas))
    throw Error("the GPU path takes at most " + std::to_string(kMaxSigmas) + " distinct sigmas (s_i and 2 s_i)");
  std::vector<int> plan_of_unit;
  SweepParams& params = plan.params;
  params = make_params(units, eps, &plan_of_unit);
  auto plan_index = [&](double u) {
    for (size_t k = 0; k < units.size(); ++k)
      if (units[k] == u) return plan_of_unit[k];
    throw Error("internal: sigma missing from the GPU sweep plan");
  };
  for (size_t i = 0; i < scales.size(); ++i) {
    params.out_a[i] = plan_index(scales[i]);
    params.out_b[i] = plan_index(2 * scales[i]);
  }
  // sweep8.comp hard-codes the plan of the default sigmas 12,10,8 (exp), 6,5,4,3,2.
  plan.fast8 = units == std::vector<double>{2, 3, 4, 5, 6, 8, 10, 12};
  if (plan.fast8) {  // the same doubles as sweep_point_default() derives from its plan
    const double e = std::sqrt(1.0 / (2.0 * params.coef[0])) / 12.0;
    params.bcoef = 1.0 / (2.0 * e * e * 14400.0);
  }
  plan.radius = 2 * units.back() * eps;
  return plan;
}

// Mixed precision where its accuracy is worked out (sweep.glsl): the default sigmas.
// Auto takes it on GPUs whose doubles are slow (gpu_fp64_rate.h). On CPU devices
// (lavapipe) the double sweep was faster (a float lane costs lavapipe about what a double
// one does there: loads and masked stores of the sums dominate, and the mixed sweep adds
// the bound sums and the cutoff check), and so it was on the H200, whose doubles run at
// half the float rate.
bool use_mixed(vk::Context& ctx, bool fast8, Precision precision) {
  if (!fast8 || precision == Precision::Double) return false;
  if (precision == Precision::Mixed) return true;
  // A CPU device is never probed: the rule takes double there whatever the slowdown.
  const bool cpu_device = ctx.info.vk_type == VK_PHYSICAL_DEVICE_TYPE_CPU;
  return gpu::auto_takes_mixed(cpu_device, cpu_device ? 0.0 : gpu::fp64_slowdown(ctx));
}

void check_device(const vk::Context& ctx) {
  if (!ctx.has_float64)
    throw Error("Vulkan device '" + ctx.info.name + "' has no 64-bit floats in shaders "
                "(shaderFloat64), which the GPU path needs to match the CPU path");
  if (!ctx.subgroup_arithmetic || ctx.subgroup_size == 0 || ctx.subgroup_size > kLocal ||
      kLocal % ctx.subgroup_size != 0)
    throw Error("Vulkan device '" + ctx.info.name + "' lacks subgroup arithmetic in compute "
                "shaders (subgroup size " + std::to_string(ctx.subgroup_size) + "), which the GPU path needs");
}

// m.pos: the positions less bb.min in double (as the CPU grid has them) with the curvature
// as w (gpu_mesh_points.h's local_points).
void upload_positions(const Mesh& mesh, const SaliencyResult& res, const BoundingBox& bb, DeviceMesh& m,
                      unsigned threads) {
  // Packed straight into the staging area (or the mapping): 32 bytes a vertex, no host copy.
  m.pos.upload_with(size_t(m.nv) * 32, [&](char* to, size_t first, size_t n) {
    gpu::pack_local_points(mesh, res.curvature, bb, first / 32, n / 32, reinterpret_cast<double*>(to), threads);
  });
}

// m.offsets, m.neighbors: the 1-rings of the local-maximum test (local_max.comp).
void upload_rings(vk::Context& ctx, const Adjacency& adj, DeviceMesh& m) {
  m.offsets = vk::Buffer(ctx, adj.offsets.size() * 4, "the adjacency offsets");
  m.neighbors = vk::Buffer(ctx, adj.neighbors.size() * 4, "the adjacency lists");
  m.offsets.upload(adj.offsets.data(), adj.offsets.size() * 4);
  m.neighbors.upload(adj.neighbors.data(), adj.neighbors.size() * 4);
}

// Whether `need` bytes fit the device: at most 90% of its device-local heap (or budget);
// true where the device says nothing of its memory.
bool fits_device(const vk::Context& ctx, uint64_t need) {
  const uint64_t have = vk::device_memory_available(ctx.info);
  return !have || need <= have * 0.9;
}

// The device buffers of the mesh, after checking that everything the computation will
// allocate fits the device (`device_bytes`: what the caller allocates besides); the
// positions (m.pos) and the mesh-point flags uploaded unless `on_device` (built there from
// the float coordinates: gpu_mesh_points.h), the 1-rings unless `adj` is empty.
void upload_mesh(vk::Context& ctx, const Mesh& mesh, const SaliencyResult& res,
                 const Adjacency& adj, size_t nsc, bool mixed, const BoundingBox& bb,
                 uint64_t device_bytes, unsigned threads, bool on_device, DeviceMesh* out) {
  DeviceMesh& m = *out;
  const size_t nv = mesh.vertex_count();
  m.nv = static_cast<uint32_t>(nv);
  for (size_t v = 0; v < nv; ++v) m.np += res.is_point[v];

  // Memory: refuse up front what cannot fit the device-local heap (or its budget).
  const uint64_t need = gpu_memory_estimate(nv, m.np, nsc, adj.neighbors.size(),
                                            ctx.use_staging, mixed) + device_bytes;
  if (!fits_device(ctx, need))
    throw Error("mesh too large for '" + ctx.info.name + "': needs about " + std::to_string(need >> 20) +
                " MiB of device memory, the device has " +
                std::to_string(vk::device_memory_available(ctx.info) >> 20) + " MiB; use the CPU path (--backend cpu)");

  m.pos = vk::Buffer(ctx, nv * 32, "the vertex positions");
  m.flags = vk::Buffer(ctx, nv * 4, "the mesh-point flags");
  upload_rings(ctx, adj, m);
  m.sorted_pos = vk::Buffer(ctx, size_t(m.np) * 32, "the sorted points");
  m.sorted_vertex = vk::Buffer(ctx, size_t(m.np) * 4, "the sorted point indices");
  m.params = vk::Buffer(ctx, sizeof(SweepParams), "the sweep parameters");
  m.result = vk::Buffer(ctx, nv * nsc * 8, "the raw saliency maps");
  m.pairs = vk::Buffer(ctx, size_t(m.np) * 4, "the pair counts");
  if (on_device) return;
  upload_positions(mesh, res, bb, m, threads);
  const std::vector<uint32_t> flags(res.is_point.begin(), res.is_point.end());
  m.flags.upload(flags.data(), flags.size() * 4);
}

// suppress() of every raw map in m.result and the final sum S into `saliency`.
// The neighbours of the local-maximum test: the 1-rings (m.offsets, m.neighbors), or where
// the device computed the curvature the triangles of each vertex (m.curvature's
// incidence), as the CPU's suppress() and suppress_faces() take them (the same bits).
void suppress_on_device(vk::Context& ctx, vk::DescriptorPool& pool, DeviceMesh& m, size_t nsc,
                        vk::Buffer& saliency) {
  const uint32_t groups = (m.nv + kLocal - 1) / kLocal;
  vk::Buffer partial_max(ctx, size_t(groups) * nsc * 8, "the partial maxima");
  vk::Buffer map_max(ctx, nsc * 8, "the map maxima");
  vk::Buffer global_index(ctx, nsc * 4, "the global maxima");
  vk::Buffer partial(ctx, size_t(groups) * nsc * 16, "the local-maximum sums");
  vk::Buffer factor(ctx, 32 * 8, "the suppression factors");
  vk::Buffer& raw = m.result;
  auto& k_mx = KERNEL(ctx, spv_map_max_comp, shader::MapMax);
  auto& k_mf = KERNEL(ctx, spv_map_max_final_comp, shader::MapMaxFinal);
  auto& k_gi = KERNEL(ctx, spv_global_index_comp, shader::GlobalIndex);
  auto& k_lm = KERNEL(ctx, spv_local_max_comp, shader::LocalMax);
  auto& k_mb = KERNEL(ctx, spv_mbar_comp, shader::Mbar);
  auto& k_fs = KERNEL(ctx, spv_final_sum_comp, shader::FinalSum);
  VkDescriptorSet s_mx = pool.bind(k_mx, {&raw, &m.flags, &partial_max});
  VkDescriptorSet s_mf = pool.bind(k_mf, {&partial_max, &map_max});
  VkDescriptorSet s_gi = pool.bind(k_gi, {&raw, &m.flags, &map_max, &global_index});
  gpu::DeviceCurvature* faces = m.curvature.get();
  auto& k_lmf = KERNEL(ctx, spv_local_max_faces_comp, shader::LocalMaxFaces);
  VkDescriptorSet s_lm =
      faces ? pool.bind(k_lmf, {&raw, &m.flags, &map_max, &global_index, &faces->start, &faces->entry(),
                                &faces->triangle_order(), &faces->triangles, &partial})
            : pool.bind(k_lm, {&raw, &m.flags, &map_max, &global_index, &m.offsets, &m.neighbors, &partial});
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
    vk::dispatch(ctx, cmd, faces ? k_lmf : k_lm, s_lm, &lm, 0, n, kLocal, ns);
    vk::barrier(cmd);
    GroupsPush mb{0, 0, groups};
    vk::dispatch(ctx, cmd, k_mb, s_mb, &mb, 0, ns * kLocal, kLocal);
    vk::barrier(cmd);
    ScalesPush fs{0, 0, ns};
    vk::dispatch(ctx, cmd, k_fs, s_fs, &fs, 0, n, kLocal);
    vk::barrier(cmd);
  });
}

// Smoothed saliency G(S, 3 eps) for simplification: one more sweep, of S, over a grid
// of its own (reuses m.params and m.result).
void smooth_on_device(vk::Context& ctx, vk::DescriptorPool& pool, DeviceMesh& m,
                      const double extent[3], double eps, const SaliencyOptions& options,
                      const Mesh& mesh, const BoundingBox& bb, SaliencyResult* res) {
  const size_t nv = m.nv;
  if (options.method == Method::Fast) {  // the same method as the averages (meshsal.h)
    gpu::fast_filter(ctx, mesh, m.pos, m.pos32, m.flags, m.np, bb, {{3.0 * eps}, {0}, {-1}}, m.result,
                     options, "smoothing");
    res->smoothed.resize(nv);
    m.result.download(res->smoothed.data(), nv * 8);
    return;
  }
  std::vector<uint32_t> starts;
  std::vector<int> plan1;
  SweepParams sp = make_params({3.0}, eps, &plan1);
  sp.out_a[0] = 0;
  sp.out_b[0] = -1;
  m.params.upload(&sp, sizeof sp);
  GridPlan g2 = build_grid(ctx, m, extent, 0.5 * 6 * eps, &starts);
  sweep(ctx, pool, m, g2, starts, false, false, false, sp, 1, 1, 6 * eps, options, "smoothing");
  res->smoothed.resize(nv);
  m.result.download(res->smoothed.data(), nv * 8);
  for (size_t v = 0; v < nv; ++v)
    if (!res->is_point[v]) res->smoothed[v] = 0;
}

}  // namespace

SaliencyResult compute_saliency_gpu(vk::Context& ctx, const Mesh& mesh,
                                    const SaliencyOptions& options) {
  // What was uploaded ahead for this call and it does not take is freed at its end
  // (gpu_prestage.h: held for the next call only).
  struct DropPrestaged {
    vk::Context& ctx;
    ~DropPrestaged() { gpu::drop_prestaged(ctx); }
  } drop_prestaged{ctx};
  SaliencyResult res;
  res.backend_name = ctx.info.name;
  ctx.host_threads = options.threads;  // the uploads' copies and packing
  const size_t nv = mesh.vertex_count();
  if (nv >= 0xffffffffu / 32) throw Error("mesh too large for the GPU path (vertex count)");
  const size_t nsc = options.scales.size();
  if (nsc == 0) throw Error("at least one scale is needed");
  if (nsc > kMaxScales) throw Error("the GPU path takes at most " + std::to_string(kMaxScales) + " scales");

  if (options.method == Method::Auto) throw Error("internal: method auto not resolved");
  const bool fast = options.method == Method::Fast;
  res.is_point = referenced_vertices(mesh);
  res.eps = scale_unit(mesh, res.is_point, options.eps_frac);
  const double eps = res.eps;
  const SweepPlan plan = plan_sweep(options.scales, eps);
  const uint32_t nsig = static_cast<uint32_t>(plan.units.size());

  // --- the sweep's precision: --precision auto may time the device's doubles, once --------
  Timer t0;
  check_device(ctx);
  res.method = options.method;
  const bool probed = ctx.fp64_slowdown != 0;
  const bool mixed = !fast && use_mixed(ctx, plan.fast8, options.precision);
  res.mixed_precision = mixed;
  if (!probed && ctx.fp64_slowdown != 0) res.stages.push_back({"fp64 probe", t0.seconds()});
  // --- and its layout: on a GPU timed once per context (gpu_layout_probe.h) -------------
  t0.restart();
  const int measured = ctx.measured_sweep_variant[mixed ? 1 : 0];
  const bool rows = !fast && shared_rows(ctx, plan.fast8, mixed);
  if (measured != ctx.measured_sweep_variant[mixed ? 1 : 0]) res.stages.push_back({"layout probe", t0.seconds()});

  // --- curvature: on the device after the upload (gpu_curvature.h), the twin of the CPU's
  // for the method: mean_curvature_morton() for the fast one, mean_curvature() over the
  // 1-rings for the exact one, neither building 1-rings on the host (the local maxima and
  // the mixed sweep's near ties take the neighbours from the triangles). For the exact
  // method on a CPU device, where the host is the faster, the host computes H with the
  // 1-rings first, as compute_saliency_cpu() does (Context::exact_curvature_on_device).
  bool device_curvature = device_curvature_by_default(ctx, options.method);
  const uint64_t curvature_bytes = nv * 16 + gpu::DeviceCurvature::bytes(nv, mesh.triangle_count());
  if (device_curvature && !fast) {
    // Its sorts hold about 230 bytes a vertex where the 1-rings take about 30: where that
    // does not fit the device and the host's way might, the host computes H.
    const uint64_t points = uint64_t(std::count(res.is_point.begin(), res.is_point.end(), uint8_t(1)));
    device_curvature =
        fits_device(ctx, gpu_memory_estimate(nv, points, nsc, 0, ctx.use_staging, mixed) + curvature_bytes);
  }
  Adjacency adj;
  if (!device_curvature) {
    // A run that will not take the float mesh frees what was uploaded ahead before it
    // allocates anything (where the device's memory decided, that is what it lacked).
    gpu::drop_prestaged(ctx);
    t0.restart();
    adj = build_adjacency(mesh);
    res.curvature = mean_curvature(mesh, adj, vertex_normals(mesh), options.threads);
    res.stages.push_back({"curvature", t0.seconds()});
  }

  // --- upload ---------------------------------------------------------------------------
  t0.restart();
  const BoundingBox bb = mesh_points_bbox(mesh, res.is_point);
  double extent[3];
  for (int a = 0; a < 3; ++a) extent[a] = bb.max[a] - bb.min[a];
  DeviceMesh m;
  const uint64_t device_bytes =
      (fast ? gpu::fast_filter_bytes(nv, nv, plan.units.size()) : 0) + (device_curvature ? curvature_bytes : 0);
  upload_mesh(ctx, mesh, res, adj, nsc, mixed, bb, device_bytes, options.threads, device_curvature, &m);
  m.params.upload(&plan.params, sizeof plan.params);
  vk::Buffer saliency(ctx, nv * 8, "the saliency");
  if (device_curvature) m.pos32 = gpu::float_positions(ctx, mesh, options.threads);
  res.stages.push_back({"upload", t0.seconds()});

  if (device_curvature) {  // --- the mesh points and the curvature, on the device -----------
    t0.restart();
    m.curvature = std::make_unique<gpu::DeviceCurvature>(
        ctx, mesh, m.pos32, m.pos, bb, fast ? gpu::TriangleOrder::morton : gpu::TriangleOrder::input);
    gpu::drop_prestaged(ctx);  // what it did not take (another mesh's) before anything else
    const gpu::DeviceMeshPoints points(ctx, m.pos32, m.curvature->triangles, m.pos, m.flags, m.nv,
                                       mesh.triangle_count());
    vk::submit(ctx, "curvature", [&](VkCommandBuffer cmd) {
      points.record(ctx, cmd, bb);
      m.curvature->record(ctx, cmd);
    });
    const uint32_t flagged = m.curvature->most_flagged_corners();
    if (flagged <= gpu::DeviceCurvature::kMortonCorners) {
      res.curvature.resize(nv);
      m.curvature->curvature.download(res.curvature.data(), nv * 8);
    }
    if (flagged != 0 && flagged <= gpu::DeviceCurvature::kMortonCorners) {
      // Input order leaves vertices of more than 64 triangles to the host: their H from
      // the triangles around them (the same bits), and the positions uploaded with it.
      std::vector<uint32_t> corners(nv, 0), many;
      for (uint32_t v : mesh.triangles) ++corners[v];
      for (size_t v = 0; v < nv; ++v)
        if (corners[v] > gpu::DeviceCurvature::kInputOrderCorners) many.push_back(uint32_t(v));
      mean_curvature_at(mesh, many, res.curvature.data(), options.threads);
      upload_positions(mesh, res, bb, m, options.threads);
    } else if (flagged != 0) {
      // A vertex of more triangles than one invocation may visit (lavapipe's loop limit):
      // the host's H (the method's CPU twin), and the suppression over the 1-rings
      // (local_max.comp) rather than over each vertex's triangles.
      adj = build_adjacency(mesh);
      res.curvature = fast ? mean_curvature_morton(mesh, bb, options.threads)
                           : mean_curvature(mesh, adj, vertex_normals(mesh), options.threads);
      upload_positions(mesh, res, bb, m, options.threads);
      upload_rings(ctx, adj, m);
      m.curvature.reset();
    }
    res.stages.push_back({"curvature", t0.seconds()});
  }

  vk::DescriptorPool pool(ctx, 32, 128);

  if (fast) {
    // --- the fast method's averages (gaussian_filter_fast), with the center-surround maps
    t0.restart();
    gpu::FastFilterPlan fp;
    for (double u : plan.units) fp.sigmas.push_back(u * eps);  // as compute_saliency_cpu()
    auto index_of = [&](double u) {
      return int(std::find(plan.units.begin(), plan.units.end(), u) - plan.units.begin());
    };
    for (double k : options.scales) {
      fp.out_a.push_back(index_of(k));
      fp.out_b.push_back(index_of(2 * k));
    }
    res.pairs = gpu::fast_filter(ctx, mesh, m.pos, m.pos32, m.flags, m.np, bb, fp, m.result, options,
                                 "gaussian sweep");
    res.stages.push_back({"gaussian sweep", t0.seconds()});
  } else {
    // --- grid + sweep (gaussian_filter), with the center-surround maps ------------------
    t0.restart();
    std::vector<uint32_t> starts;
    // Cells of a fifth of the radius for the shared-rows sweep (rows are clipped to the
    // ball's chord, so smaller cells mean fewer candidates, and a smaller box around the
    // subgroup's points; on lavapipe, igea_134k, 1/4 to 1/8 were within the noise of each
    // other, 1/5 looked best, 1/3 and 1/2 were slower); half the radius for a subgroup per
    // point, where short rows would leave lanes idle.
    GridPlan g = build_grid(ctx, m, extent, (rows ? 0.2 : 0.5) * plan.radius, &starts);
    res.stages.push_back({"grid", t0.seconds()});

    t0.restart();
    if (mixed) {
      m.sorted_pos32 = vk::Buffer(ctx, size_t(m.np) * 16, "the float points");
      m.bound = vk::Buffer(ctx, size_t(nv) * nsc * 4, "the error bounds");
      gpu::make_float_points(ctx, pool, m.sorted_pos, m.sorted_pos32, m.np, bb.min);
    }
    res.pairs = sweep(ctx, pool, m, g, starts, plan.fast8, rows, mixed, plan.params, nsig,
                      static_cast<uint32_t>(nsc), plan.radius, options, "gaussian sweep");
    res.stages.push_back({"gaussian sweep", t0.seconds()});
    if (mixed) {
      t0.restart();
      gpu::NearTieBuffers nb{&m.result, &m.flags, &m.bound, &m.offsets, &m.neighbors,
                             &m.sorted_pos, &m.sorted_vertex, &m.starts, &m.params, &m.pairs, &m.pos};
      if (m.curvature) {  // the neighbours from the curvature's incidence (no 1-rings)
        nb.start = &m.curvature->start;
        nb.entry = &m.curvature->entry();
        nb.order = &m.curvature->triangle_order();
        nb.triangles = &m.curvature->triangles;
      }
      SweepPush p{0, 0, g.nx, g.ny, g.nz, 0, m.nv, nsig,
                  static_cast<uint32_t>(nsc), 0, g.h, plan.radius * plan.radius};
      res.rechecked = gpu::recheck_near_ties(ctx, pool, nb, m.nv, static_cast<uint32_t>(nsc), p);
      res.stages.push_back({"near-tie recheck", t0.seconds()});
    }
  }

  // --- suppress() of every map and the final sum ------------------------------------
  t0.restart();
  suppress_on_device(ctx, pool, m, nsc, saliency);
  res.stages.push_back({"suppression", t0.seconds()});

  // --- download S and the maps (before the smoothing sweep reuses the result buffer),
  // the maps only when asked for (SaliencyOptions::raw_maps: 8 bytes a vertex a scale,
  // the most of the download; the CPU paths leave them empty too) ---------------------
  t0.restart();
  res.saliency.resize(nv);
  saliency.download(res.saliency.data(), nv * 8);
  if (options.raw_maps) {
    res.raw.resize(nsc);
    for (size_t i = 0; i < nsc; ++i) {
      res.raw[i].resize(nv);
      m.result.download(res.raw[i].data(), nv * 8, i * nv * 8);
    }
  }
  res.stages.push_back({"download", t0.seconds()});

  if (options.smoothed) {
    t0.restart();
    smooth_on_device(ctx, pool, m, extent, eps, options, mesh, bb, &res);
    res.stages.push_back({"smoothing", t0.seconds()});
  }
  return res;
}


}  // namespace meshsal
