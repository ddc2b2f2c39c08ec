// meshsal: the exact sweep's layout, measured (gpu_layout_probe.h).
#include "gpu/gpu_layout_probe.h"

#include <algorithm>
#include <cmath>

#include "gpu/gpu_saliency.h"
#include "core/cancel.h"
#include "meshsal/meshsal.h"

namespace meshsal::gpu {

Mesh probe_sphere(uint32_t points) {
  const uint32_t rows = std::max<uint32_t>(8, uint32_t(std::sqrt(points / 2.0)));
  const uint32_t cols = 2 * rows;
  const double pi = 3.141592653589793;
  Mesh m;
  for (uint32_t i = 0; i < rows; ++i)
    for (uint32_t j = 0; j < cols; ++j) {
      const double th = pi * (i + 0.5) / rows, ph = 2 * pi * j / cols;
      const double r = 1 + 0.05 * std::sin(5 * th) * std::cos(7 * ph);
      m.positions.insert(m.positions.end(), {float(r * std::sin(th) * std::cos(ph)),
                                             float(r * std::sin(th) * std::sin(ph)), float(r * std::cos(th))});
    }
  for (uint32_t i = 0; i + 1 < rows; ++i)
    for (uint32_t j = 0; j < cols; ++j) {
      const uint32_t a = i * cols + j, b = i * cols + (j + 1) % cols, c = a + cols, d = b + cols;
      m.triangles.insert(m.triangles.end(), {a, c, b, b, c, d});
    }
  return m;
}

namespace {

double sweep_seconds(const SaliencyResult& r) {
  for (const StageTime& s : r.stages)
    if (s.name == "gaussian sweep") return s.seconds;
  return 0;
}

}  // namespace

LayoutProbe measure_sweep_layout(vk::Context& ctx, bool mixed, uint32_t points, int repeats) {
  const Mesh mesh = probe_sphere(points);
  SaliencyOptions o;
  o.method = Method::Exact;
  o.backend = Backend::Gpu;
  o.precision = mixed ? Precision::Mixed : Precision::Double;
  o.eps_frac = 0.02;  // the ball of 12 eps holds a few thousand of the points, as on a scan
  const int kept = ctx.sweep_variant;
  LayoutProbe p;
  try {
    for (int variant = 0; variant < 2; ++variant) {
      ctx.sweep_variant = variant;
      compute_saliency_gpu(ctx, mesh, o);  // compiles the pipelines
      double best = INFINITY;
      for (int r = 0; r < std::max(1, repeats); ++r) best = std::min(best, sweep_seconds(compute_saliency_gpu(ctx, mesh, o)));
      (variant == 0 ? p.rows_seconds : p.subgroup_seconds) = best;
    }
  } catch (...) {
    ctx.sweep_variant = kept;
    throw;
  }
  ctx.sweep_variant = kept;
  return p;
}

int measured_sweep_variant(vk::Context& ctx, bool mixed) {
  int& v = ctx.measured_sweep_variant[mixed ? 1 : 0];
  if (v >= 0) return v;
  try {
    v = measure_sweep_layout(ctx, mixed).variant();
  } catch (const Cancelled&) {
    throw;
  } catch (const Error&) {
    // A probe that fails must not fail the run: the layout GPUs took before the probe (a
    // subgroup per point); the run itself meets whatever broke, if it persists.
    v = 1;
  }
  return v;
}

}  // namespace meshsal::gpu
