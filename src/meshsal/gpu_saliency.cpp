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
#include "meshsal/mesh_points.h"
#include "meshsal/vk_buffer.h"
#include "meshsal/vk_compute.h"

#include "center_surround_comp.h"
#include "final_sum_comp.h"
#include "global_index_comp.h"
#include "grid_key_comp.h"
#include "grid_scan_comp.h"
#include "grid_scatter_comp.h"
#include "local_max_comp.h"
#include "mbar_comp.h"
#include "selftest_comp.h"
#include "sweep8_comp.h"
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
struct GridKeyPush { uint32_t base, n, nx, ny, nz; float ox, oy, oz, inv_h; };
struct RangePush { uint32_t base, n; };
struct SweepPush {
  uint32_t base, n, nx, ny, nz;
  int32_t r;
  uint32_t stride, nsig;
  float inv_2eps2, radius2;
  float ox, oy, oz, inv_h;
};
struct ScalesPush { uint32_t base, n, nscales; };
struct GroupsPush { uint32_t base, n, groups; };

// A uniform grid over the mesh points: cells of side h >= radius / 2, so a point's
// neighbours within `radius` lie in the cells at most r = 2 (or 1) away on each axis.
struct GridPlan {
  uint32_t nx = 1, ny = 1, nz = 1;
  float origin[3] = {0, 0, 0};
  float inv_h = 1;
  int r = 2;
  uint64_t cells() const { return uint64_t(nx) * ny * nz; }
};

GridPlan plan_grid(const float lo[3], const float hi[3], double radius, uint64_t max_cells) {
  GridPlan g;
  // A little over radius/2: float rounding of the cell index can never push a neighbour
  // inside the radius more than two cells away.
  double h = radius * 0.5 * 1.001;
  for (;;) {
    uint32_t n[3];
    for (int a = 0; a < 3; ++a)
      n[a] = static_cast<uint32_t>(std::min(std::floor((double(hi[a]) - lo[a]) / h) + 1.0, 1e6));
    if (uint64_t(n[0]) * n[1] * n[2] <= max_cells) {
      g.nx = n[0];
      g.ny = n[1];
      g.nz = n[2];
      break;
    }
    h *= 1.25;  // tiny eps on a big mesh: coarser cells, more candidates, same result
  }
  for (int a = 0; a < 3; ++a) g.origin[a] = lo[a];
  g.inv_h = static_cast<float>(1.0 / h);
  g.r = h >= radius * 1.001 ? 1 : 2;
  return g;
}

// Everything on the device for one saliency computation.
struct DeviceMesh {
  uint32_t nv = 0, np = 0;  // vertices, mesh points
  vk::Buffer pos, flags, offsets, neighbors;
  vk::Buffer cell_count, starts, key, slot, sorted_pos, sorted_vertex, sorted_key;
  vk::Buffer params, filtered, pairs;
};

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Builds the grid for `radius` over the current pos[] (counting sort on the device) and
// returns its plan and the downloaded cell starts (for planning the sweep slices).
GridPlan build_grid(vk::Context& ctx, vk::DescriptorPool& pool, DeviceMesh& m, const float lo[3],
                    const float hi[3], double radius, std::vector<uint32_t>* starts_out) {
  uint64_t max_cells = std::min<uint64_t>(uint64_t(1) << 22,
                                          ctx.properties.limits.maxStorageBufferRange / 4 - 1);
  GridPlan g = plan_grid(lo, hi, radius, max_cells);
  const uint32_t cells = static_cast<uint32_t>(g.cells());
  m.cell_count = vk::Buffer(ctx, size_t(cells) * 4, "the grid cell counts");
  m.starts = vk::Buffer(ctx, size_t(cells + 1) * 4, "the grid cell starts");

  auto& k_key = KERNEL(ctx, spv_grid_key_comp, 5, GridKeyPush);
  auto& k_scan = KERNEL(ctx, spv_grid_scan_comp, 2, RangePush);
  auto& k_scatter = KERNEL(ctx, spv_grid_scatter_comp, 7, RangePush);
  VkDescriptorSet s_key = pool.bind(k_key, {&m.pos, &m.flags, &m.cell_count, &m.key, &m.slot});
  VkDescriptorSet s_scan = pool.bind(k_scan, {&m.cell_count, &m.starts});
  VkDescriptorSet s_scatter = pool.bind(
      k_scatter, {&m.pos, &m.key, &m.slot, &m.starts, &m.sorted_pos, &m.sorted_vertex, &m.sorted_key});
  vk::submit(ctx, "grid", [&](VkCommandBuffer cmd) {
    vkCmdFillBuffer(cmd, m.cell_count.handle(), 0, VK_WHOLE_SIZE, 0);
    vk::barrier(cmd);
    GridKeyPush kp{0, 0, g.nx, g.ny, g.nz, g.origin[0], g.origin[1], g.origin[2], g.inv_h};
    vk::dispatch(ctx, cmd, k_key, s_key, &kp, 0, m.nv, kLocal);
    vk::barrier(cmd);
    RangePush sp{0, 0};
    // one work group scans all cells: n = cells, a single group of 256
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, k_scan.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, k_scan.layout, 0, 1, &s_scan, 0, nullptr);
    sp.n = cells;
    vkCmdPushConstants(cmd, k_scan.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof sp, &sp);
    vkCmdDispatch(cmd, 1, 1, 1);
    vk::barrier(cmd);
    RangePush cp{0, 0};
    vk::dispatch(ctx, cmd, k_scatter, s_scatter, &cp, 0, m.nv, kLocal);
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
                                  double budget) {
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
        int x0 = std::max(x - g.r, 0), x1 = std::min(x + g.r, nx - 1);
        for (int zz = std::max(z - g.r, 0); zz <= std::min(z + g.r, nz - 1); ++zz)
          for (int yy = std::max(y - g.r, 0); yy <= std::min(y + g.r, ny - 1); ++yy) {
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

// One neighbour sweep over the grid: filtered[k][v] for the sigmas in params; returns the
// number of pairs strictly inside `radius` (v itself included).
uint64_t sweep(vk::Context& ctx, vk::DescriptorPool& pool, DeviceMesh& m, const GridPlan& g,
               const std::vector<uint32_t>& starts, bool fast8, uint32_t nsig, double eps,
               double radius, const SaliencyOptions& options, const char* stage) {
  auto& k = fast8 ? KERNEL(ctx, spv_sweep8_comp, 7, SweepPush)
                  : KERNEL(ctx, spv_sweepn_comp, 7, SweepPush);
  VkDescriptorSet set = pool.bind(k, {&m.sorted_pos, &m.sorted_vertex, &m.sorted_key, &m.starts,
                                      &m.params, &m.filtered, &m.pairs});
  const bool cpu_device = ctx.info.vk_type == VK_PHYSICAL_DEVICE_TYPE_CPU;
  const double budget = cpu_device ? 1.5e8 : 2e10;
  std::vector<uint32_t> cuts = plan_slices(g, starts, budget);
  SweepPush p{0, 0, g.nx, g.ny, g.nz, g.r, m.nv, nsig,
              static_cast<float>(1.0 / (2.0 * eps * eps)), static_cast<float>(radius * radius),
              g.origin[0], g.origin[1], g.origin[2], g.inv_h};
  for (size_t s = 0; s + 1 < cuts.size(); ++s) {
    vk::submit(ctx, stage, [&](VkCommandBuffer cmd) {
      vk::dispatch(ctx, cmd, k, set, &p, cuts[s], cuts[s + 1], kLocal);
    });
    if (options.progress) options.progress(stage, double(cuts[s + 1]) / std::max<uint32_t>(m.np, 1));
  }
  std::vector<uint32_t> pairs(m.np);
  m.pairs.download(pairs.data(), pairs.size() * 4);
  uint64_t total = 0;
  for (uint32_t c : pairs) total += c;
  return total;
}

std::vector<double> to_double(const std::vector<float>& v, size_t begin, size_t count) {
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
  if (nv >= 0xffffffffu / 16) throw Error("mesh too large for the GPU path (vertex count)");
  const size_t nsc = options.scales.size();
  if (nsc == 0) throw Error("no scales given");
  if (nsc > kMaxScales) throw Error("the GPU path takes at most 16 scales");

  // --- curvature (CPU): the same functions as compute_saliency_cpu --------------------
  auto t0 = Clock::now();
  res.is_point = referenced_vertices(mesh);
  res.eps = scale_unit(mesh, res.is_point, options.eps_frac);
  Adjacency adj = build_adjacency(mesh);
  std::vector<double> normals = vertex_normals(mesh);
  res.curvature = mean_curvature(mesh, adj, normals, options.threads);
  res.stages.push_back({"curvature", seconds_since(t0)});

  // --- sigmas: the distinct s_i and 2 s_i, in units of eps --------------------------
  std::vector<double> units;
  for (double s : options.scales) {
    units.push_back(s);
    units.push_back(2 * s);
  }
  std::sort(units.begin(), units.end());
  units.erase(std::unique(units.begin(), units.end(),
                          [](double a, double b) { return std::fabs(a - b) <= 1e-12 * b; }),
              units.end());
  if (units.size() > kMaxSigmas)
    throw Error("the GPU path takes at most 16 distinct sigmas (s_i and 2 s_i)");
  auto unit_index = [&](double u) {
    for (size_t k = 0; k < units.size(); ++k)
      if (std::fabs(units[k] - u) <= 1e-12 * u) return static_cast<uint32_t>(k);
    return 0u;
  };
  const bool fast8 = units == std::vector<double>{2, 3, 4, 5, 6, 8, 10, 12};
  const double eps = res.eps;
  const double radius = 2 * units.back() * eps;

  // --- upload: positions relative to the bbox centre (floats keep 1e-7 of the extent) -
  t0 = Clock::now();
  BoundingBox bb = mesh_points_bbox(mesh, res.is_point);
  double centre[3];
  float lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    centre[a] = 0.5 * (bb.min[a] + bb.max[a]);
    lo[a] = static_cast<float>(bb.min[a] - centre[a]);
    hi[a] = static_cast<float>(bb.max[a] - centre[a]);
  }
  DeviceMesh m;
  m.nv = static_cast<uint32_t>(nv);
  std::vector<float> pos4(4 * nv);
  std::vector<uint32_t> flags(nv);
  for (size_t v = 0; v < nv; ++v) {
    for (int a = 0; a < 3; ++a)
      pos4[4 * v + a] = static_cast<float>(double(mesh.positions[3 * v + a]) - centre[a]);
    pos4[4 * v + 3] = static_cast<float>(res.curvature[v]);
    flags[v] = res.is_point[v];
    m.np += res.is_point[v];
  }

  // Memory: refuse up front what cannot fit the largest device-local heap.
  const uint64_t need = uint64_t(nv) * (16 + 4 * 4 + 16 + 4 * 3 + 4 * units.size() + 4 * nsc + 8) +
                        uint64_t(adj.neighbors.size()) * 4 + (uint64_t(4) << 22) * 2;
  if (ctx.info.device_local_bytes && need > ctx.info.device_local_bytes * 0.9)
    throw Error("mesh too large for '" + ctx.info.name + "': needs about " +
                std::to_string(need >> 20) + " MiB of device memory, the device has " +
                std::to_string(ctx.info.device_local_bytes >> 20) +
                " MiB; use the CPU path (--backend cpu)");

  m.pos = vk::Buffer(ctx, nv * 16, "the vertex positions");
  m.flags = vk::Buffer(ctx, nv * 4, "the mesh-point flags");
  m.offsets = vk::Buffer(ctx, adj.offsets.size() * 4, "the adjacency offsets");
  m.neighbors = vk::Buffer(ctx, adj.neighbors.size() * 4, "the adjacency lists");
  m.key = vk::Buffer(ctx, nv * 4, "the cell keys");
  m.slot = vk::Buffer(ctx, nv * 4, "the cell slots");
  m.sorted_pos = vk::Buffer(ctx, size_t(m.np) * 16, "the sorted points");
  m.sorted_vertex = vk::Buffer(ctx, size_t(m.np) * 4, "the sorted point indices");
  m.sorted_key = vk::Buffer(ctx, size_t(m.np) * 4, "the sorted cell keys");
  m.params = vk::Buffer(ctx, 32 * 4, "the sweep parameters");
  m.filtered = vk::Buffer(ctx, nv * units.size() * 4, "the Gaussian-filtered curvature");
  m.pairs = vk::Buffer(ctx, size_t(m.np) * 4, "the pair counts");
  vk::Buffer raw(ctx, nv * nsc * 4, "the raw saliency maps");
  vk::Buffer scale_sigma(ctx, nsc * 8, "the scale table");
  vk::Buffer max_bits(ctx, nsc * 4, "the map maxima");
  vk::Buffer global_index(ctx, nsc * 4, "the global maxima");
  const uint32_t groups = static_cast<uint32_t>((nv + kLocal - 1) / kLocal);
  vk::Buffer partial(ctx, size_t(groups) * nsc * 8, "the local-maximum sums");
  vk::Buffer factor(ctx, 32 * 4, "the suppression factors");
  vk::Buffer saliency(ctx, nv * 4, "the saliency");

  m.pos.upload(pos4.data(), pos4.size() * 4);
  m.flags.upload(flags.data(), flags.size() * 4);
  m.offsets.upload(adj.offsets.data(), adj.offsets.size() * 4);
  m.neighbors.upload(adj.neighbors.data(), adj.neighbors.size() * 4);
  std::vector<float> params(32, 0.0f);
  for (size_t k = 0; k < units.size(); ++k) {
    double s = units[k] * eps;
    params[k] = static_cast<float>((2 * s) * (2 * s));
    params[16 + k] = static_cast<float>(1.0 / (2 * s * s));
  }
  m.params.upload(params.data(), params.size() * 4);
  std::vector<uint32_t> pairs_table(2 * nsc);
  for (size_t i = 0; i < nsc; ++i) {
    pairs_table[2 * i] = unit_index(options.scales[i]);
    pairs_table[2 * i + 1] = unit_index(2 * options.scales[i]);
  }
  scale_sigma.upload(pairs_table.data(), pairs_table.size() * 4);
  res.stages.push_back({"upload", seconds_since(t0)});

  vk::DescriptorPool pool(ctx, 32, 128);

  // --- grid + sweep (gaussian_filter) ----------------------------------------------
  t0 = Clock::now();
  std::vector<uint32_t> starts;
  GridPlan g = build_grid(ctx, pool, m, lo, hi, radius, &starts);
  res.stages.push_back({"grid", seconds_since(t0)});

  t0 = Clock::now();
  res.pairs = sweep(ctx, pool, m, g, starts, fast8, static_cast<uint32_t>(units.size()), eps,
                    radius, options, "gaussian sweep");
  res.stages.push_back({"gaussian sweep", seconds_since(t0)});

  // --- raw maps (center-surround), suppress() and the final sum ----------------------
  t0 = Clock::now();
  {
    auto& k_cs = KERNEL(ctx, spv_center_surround_comp, 5, ScalesPush);
    auto& k_gi = KERNEL(ctx, spv_global_index_comp, 4, RangePush);
    auto& k_lm = KERNEL(ctx, spv_local_max_comp, 7, GroupsPush);
    auto& k_mb = KERNEL(ctx, spv_mbar_comp, 3, GroupsPush);
    auto& k_fs = KERNEL(ctx, spv_final_sum_comp, 5, ScalesPush);
    VkDescriptorSet s_cs = pool.bind(k_cs, {&m.filtered, &m.flags, &scale_sigma, &raw, &max_bits});
    VkDescriptorSet s_gi = pool.bind(k_gi, {&raw, &m.flags, &max_bits, &global_index});
    VkDescriptorSet s_lm = pool.bind(
        k_lm, {&raw, &m.flags, &max_bits, &global_index, &m.offsets, &m.neighbors, &partial});
    VkDescriptorSet s_mb = pool.bind(k_mb, {&partial, &max_bits, &factor});
    VkDescriptorSet s_fs = pool.bind(k_fs, {&raw, &m.flags, &factor, &saliency, &m.pos});
    const uint32_t n = m.nv, ns = static_cast<uint32_t>(nsc);
    vk::submit(ctx, "center-surround", [&](VkCommandBuffer cmd) {
      vkCmdFillBuffer(cmd, max_bits.handle(), 0, VK_WHOLE_SIZE, 0);
      vk::barrier(cmd);
      ScalesPush cs{0, 0, ns};
      vk::dispatch(ctx, cmd, k_cs, s_cs, &cs, 0, n, kLocal);
      vk::barrier(cmd);
    });
    res.stages.push_back({"center-surround", seconds_since(t0)});
    t0 = Clock::now();
    vk::submit(ctx, "suppression", [&](VkCommandBuffer cmd) {
      vkCmdFillBuffer(cmd, global_index.handle(), 0, VK_WHOLE_SIZE, 0xffffffffu);
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

  // --- smoothed saliency G(S, 3 eps) for simplification ---------------------------
  std::vector<float> smoothed;
  if (options.smoothed) {
    t0 = Clock::now();
    std::vector<float> sp(32, 0.0f);
    sp[0] = static_cast<float>((6 * eps) * (6 * eps));
    sp[16] = static_cast<float>(1.0 / (2 * 9 * eps * eps));
    m.params.upload(sp.data(), sp.size() * 4);
    GridPlan g2 = build_grid(ctx, pool, m, lo, hi, 6 * eps, &starts);
    sweep(ctx, pool, m, g2, starts, false, 1, eps, 6 * eps, options, "smoothing");
    smoothed.resize(nv);
    m.filtered.download(smoothed.data(), nv * 4);
    res.stages.push_back({"smoothing", seconds_since(t0)});
  }

  // --- download ------------------------------------------------------------------
  t0 = Clock::now();
  std::vector<float> raw_h(nv * nsc), sal_h(nv);
  raw.download(raw_h.data(), raw_h.size() * 4);
  saliency.download(sal_h.data(), sal_h.size() * 4);
  res.raw.resize(nsc);
  for (size_t i = 0; i < nsc; ++i) res.raw[i] = to_double(raw_h, i * nv, nv);
  res.saliency = to_double(sal_h, 0, nv);
  if (options.smoothed) {
    res.smoothed = to_double(smoothed, 0, nv);
    for (size_t v = 0; v < nv; ++v)
      if (!res.is_point[v]) res.smoothed[v] = 0;
  }
  res.stages.push_back({"download", seconds_since(t0)});
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
