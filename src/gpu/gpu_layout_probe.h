// meshsal: which layout the exact sweep takes on a GPU, measured once per context: the
// shared rows (a lane per point over rows of cells the subgroup shares, sweep8_rows) or a
// subgroup per point (sweep8). Which wins depends on the device (its subgroup width, its
// caches, its double rate); on the H200 a subgroup per point was 0.76 s against the rows'
// 1.2 s on igea_loop2 (docs/benchmarks.md, "NVIDIA"), on lavapipe the rows win. So, as
// --precision auto times the device's doubles (gpu_fp64_rate.h), the layout is chosen by
// timing the sweep of a small synthetic scan in both layouts.
#pragma once
#include <cstdint>

#include "gpu/vk_context.h"
#include "meshsal/meshsal.h"

namespace meshsal::gpu {

// A sphere of about `points` vertices in latitude-longitude rows (open at the poles) with
// bumps: the probes' and the warm-up's synthetic scan.
Mesh probe_sphere(uint32_t points);

struct LayoutProbe {
  double rows_seconds = 0, subgroup_seconds = 0;  // the sweep stage, fastest of the repeats
  int variant() const { return rows_seconds <= subgroup_seconds ? 0 : 1; }  // Context::sweep_variant's
};

// Times the exact sweep (in mixed or double precision) of a bumpy sphere of about `points`
// vertices in both layouts, `repeats` times each (after one run each that compiles the
// pipelines). Its eps gives each point thousands of neighbours, as a scan's default has.
LayoutProbe measure_sweep_layout(vk::Context& ctx, bool mixed, uint32_t points = 16384, int repeats = 2);

// ctx's layout for the sweep in that precision: measured once per context on first need
// and kept (Context::measured_sweep_variant).
int measured_sweep_variant(vk::Context& ctx, bool mixed);

}  // namespace meshsal::gpu
