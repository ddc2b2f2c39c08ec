// bench_gpu_sweep: the exact sweep's layouts and precisions, and the fast method's phases, on
// one Vulkan device, to choose the defaults for it (docs/benchmarks.md, "NVIDIA").
//   bench_gpu_sweep [--repeat N] [--device I] [--probe-lanes N] [--no-fast] [--no-exact] [MESH ...]
// First the fp64 probe (gpu_fp64_rate.h: what --precision auto decides by; --probe-lanes:
// its lanes, 0 = the library's default) and the layout probe (gpu_layout_probe.h: what a GPU
// takes for the exact sweep).
// Per mesh: the exact method in each layout (shared rows: a lane per point; subgroup: a
// subgroup per point) and precision (mixed, double), then the fast method with the host
// seconds and host waits (submissions the host waited for) of each of its phases, and what
// uploading its mesh ahead (as a run reading a PLY does) takes off it. Times are the fastest of the repeats, after one run that
// compiles the pipelines. Each method's device curvature is compared with its CPU twin bit
// for bit (on a GPU that assumes correctly rounded double division and square root).
// Default mesh: ../shared/data/meshes/igea_134k.ply.gz.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "core/adjacency.h"
#include "core/mesh_points.h"
#include "core/timer.h"
#include "gpu/gpu_fp64_rate.h"
#include "gpu/gpu_layout_probe.h"
#include "gpu/gpu_prestage.h"
#include "gpu/gpu_saliency.h"
#include "gpu/vk_context.h"
#include "meshsal/meshsal.h"
#include "saliency/curvature.h"

using namespace meshsal;

namespace {

double stage(const SaliencyResult& r, const std::string& name) {
  double s = 0;
  for (const auto& st : r.stages)
    if (st.name == name) s += st.seconds;
  return s;
}

double total(const SaliencyResult& r) {
  double s = 0;
  for (const auto& st : r.stages) s += st.seconds;
  return s;
}

// The fastest of `repeat` runs (the context keeps its compiled pipelines between them).
SaliencyResult best_of(vk::Context& ctx, const Mesh& mesh, const SaliencyOptions& o, int repeat,
                       std::vector<vk::Context::FastPhase>* phases) {
  SaliencyResult best;
  for (int i = 0; i < repeat; ++i) {
    SaliencyResult r = compute_saliency_gpu(ctx, mesh, o);
    if (i == 0 || total(r) < total(best)) {
      best = std::move(r);
      if (phases) *phases = ctx.fast_phases;
    }
  }
  return best;
}

// One line: how many of the device's H differ from the CPU twin's in any bit, and by how much.
void print_curvature_check(const std::string& name, const char* method, const std::vector<double>& device,
                           const std::vector<double>& host) {
  size_t differ = 0;
  double worst = 0;
  for (size_t v = 0; v < host.size() && v < device.size(); ++v)
    if (std::memcmp(&host[v], &device[v], 8) != 0) {
      ++differ;
      worst = std::max(worst, std::fabs(host[v] - device[v]) / std::max(std::fabs(host[v]), 1e-300));
    }
  std::printf("%-26s %s curvature against the CPU's: %zu of %zu vertices differ in some bit (largest relative "
              "difference %.3g)%s\n",
              name.c_str(), method, differ, host.size(), worst, device.size() == host.size() ? "" : " SIZE MISMATCH");
}

}  // namespace

int main(int argc, char** argv) {
  int repeat = 3, device = -1, lanes = 0;
  bool fast = true, exact = true;
  std::vector<std::string> meshes;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if ((a == "--repeat" || a == "--device" || a == "--probe-lanes") && i + 1 < argc) {
      (a == "--repeat" ? repeat : a == "--device" ? device : lanes) = std::atoi(argv[++i]);
    } else if (a == "--no-fast") {
      fast = false;
    } else if (a == "--no-exact") {
      exact = false;
    } else if (a == "-h" || a == "--help") {
      std::printf("bench_gpu_sweep [--repeat N] [--device I] [--probe-lanes N] [--no-fast] [--no-exact] [MESH ...]\n");
      return 0;
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "unknown option %s (see --help)\n", a.c_str());
      return 2;
    } else {
      meshes.push_back(a);
    }
  }
  if (meshes.empty()) meshes = {"../shared/data/meshes/igea_134k.ply.gz"};
  if (repeat < 1) repeat = 1;
  try {
    vk::Context ctx(device);
    std::printf("device: %s, subgroup size %u\n", ctx.info.name.c_str(), ctx.subgroup_size);
    const gpu::Fp64Probe probe = gpu::measure_fp64_rate(ctx, lanes);
    std::printf("fp64 probe: %u lanes x %u fma steps x 4 chains: float %.3f ms, double %.3f ms, "
                "slowdown %.2f (auto takes mixed above %.1f on GPUs)\n",
                probe.lanes, probe.iterations, 1e3 * probe.float_seconds, 1e3 * probe.double_seconds,
                probe.slowdown(), gpu::kMixedAboveFp64Slowdown);
    // The layout probe a GPU runs once per process (gpu_layout_probe.h; CPU devices take rows).
    for (bool mixed : {false, true}) {
      const gpu::LayoutProbe lp = gpu::measure_sweep_layout(ctx, mixed);
      std::printf("layout probe (%s): sweep rows %.3f ms, subgroup %.3f ms: a GPU takes %s\n",
                  mixed ? "mixed" : "double", 1e3 * lp.rows_seconds, 1e3 * lp.subgroup_seconds,
                  lp.variant() == 0 ? "rows" : "subgroup");
    }
    std::printf("%-26s %9s %-9s %-7s %8s %8s %8s %8s %10s %8s\n", "mesh", "vertices", "layout", "prec",
                "grid", "sweep", "recheck", "total", "pairs/s", "recheck%");
    for (const std::string& path : meshes) {
      const Mesh mesh = load_mesh(path);
      const std::string name = path.substr(path.find_last_of('/') + 1);
      SaliencyOptions o;
      o.backend = Backend::Gpu;
      o.raw_maps = false;
      for (int variant : {0, 1}) {
        if (!exact) break;
        for (Precision p : {Precision::Mixed, Precision::Double}) {
          ctx.sweep_variant = variant;
          o.precision = p;
          compute_saliency_gpu(ctx, mesh, o);  // the pipelines' first compile
          const SaliencyResult r = best_of(ctx, mesh, o, repeat, nullptr);
          const double sweep = stage(r, "gaussian sweep"), t = total(r);
          std::printf("%-26s %9zu %-9s %-7s %7.3fs %7.3fs %7.3fs %7.3fs %10.3g %7.2f%%\n", name.c_str(),
                      mesh.vertex_count(), variant == 0 ? "rows" : "subgroup",
                      r.mixed_precision ? "mixed" : "double", stage(r, "grid"), sweep,
                      stage(r, "near-tie recheck"), t, double(r.pairs) / sweep,
                      100.0 * double(r.rechecked) / double(mesh.vertex_count()));
          std::fflush(stdout);
        }
      }
      ctx.sweep_variant = -1;
      if (exact) {
        o.precision = Precision::Double;
        SaliencyResult r;
        for (int on_device : {0, 1}) {  // -1 on a CPU device (lavapipe) would take the host's
          ctx.exact_curvature_on_device = on_device;
          const uint64_t sent = ctx.uploaded_bytes;
          r = compute_saliency_gpu(ctx, mesh, o);
          const double up = double(ctx.uploaded_bytes - sent);
          std::printf("%-26s exact, double, curvature on the %s: %.1f MB uploaded, %.1f bytes a vertex; curvature "
                      "%.3fs\n",
                      name.c_str(), on_device ? "device" : "host", up / 1e6, up / double(mesh.vertex_count()),
                      stage(r, "curvature"));
        }
        ctx.exact_curvature_on_device = -1;
        print_curvature_check(name, "exact", r.curvature,  // the device's, the loop's last run
                              mean_curvature(mesh, build_adjacency(mesh), vertex_normals(mesh)));
        o.precision = Precision::Auto;
      }
      if (!fast) continue;
      o.method = Method::Fast;
      const uint64_t sent = ctx.uploaded_bytes;
      const std::vector<double> device_curvature = compute_saliency_gpu(ctx, mesh, o).curvature;
      const double up = double(ctx.uploaded_bytes - sent);
      std::printf("%-26s fast: %.1f MB uploaded, %.1f bytes a vertex\n", name.c_str(), up / 1e6,
                  up / double(mesh.vertex_count()));
      print_curvature_check(name, "fast", device_curvature,
                            mean_curvature_morton(mesh, mesh_points_bbox(mesh, referenced_vertices(mesh))));
      std::vector<vk::Context::FastPhase> phases;
      const SaliencyResult r = best_of(ctx, mesh, o, repeat, &phases);
      std::printf("%-26s fast: curvature %.3fs upload %.3fs sweep %.3fs suppression %.3fs download %.3fs total %.3fs\n",
                  name.c_str(), stage(r, "curvature"), stage(r, "upload"), stage(r, "gaussian sweep"),
                  stage(r, "suppression"), stage(r, "download"), total(r));
      {
        // The mesh uploaded ahead, as a run reading a PLY uploads it while the faces are
        // still read (gpu_prestage.h): the time that moves off the run, which keeps the
        // check of the bytes (the upload stage holds the positions', curvature the triangles').
        const Timer ahead;
        gpu::prestage_float_positions(ctx, mesh.positions.data(), mesh.vertex_count());
        gpu::prestage_triangles(ctx, mesh.triangles.data(), mesh.triangle_count());
        const double ahead_s = ahead.seconds();
        const uint64_t taken = ctx.prestaged_taken;
        const SaliencyResult a = compute_saliency_gpu(ctx, mesh, o);
        std::printf("%-26s fast, uploaded ahead: %.3fs ahead, %llu of 2 buffers taken; the run's upload %.3fs "
                    "curvature %.3fs (above: %.3fs, %.3fs)\n",
                    name.c_str(), ahead_s, (unsigned long long)(ctx.prestaged_taken - taken), stage(a, "upload"),
                    stage(a, "curvature"), stage(r, "upload"), stage(r, "curvature"));
      }
      auto print_phases = [&](const char* what, const std::vector<vk::Context::FastPhase>& list) {
        std::printf("%-26s %s:", name.c_str(), what);
        uint64_t waits = 0;
        for (const auto& p : list) {
          std::printf(" %s %.3fs (%llu waits);", p.name.c_str(), p.seconds, (unsigned long long)p.waits);
          waits += p.waits;
        }
        std::printf(" %llu host waits in all\n", (unsigned long long)waits);
      };
      print_phases("fast sweep's waits", phases);
      // Each phase in a submission of its own: where the time goes (the totals above are
      // the default, with a sigma's finish and the next one's cells in its last submission).
      ctx.fast_phase_timing = true;
      best_of(ctx, mesh, o, repeat, &phases);
      ctx.fast_phase_timing = false;
      print_phases("fast sweep's phases, apart", phases);
      std::fflush(stdout);
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
