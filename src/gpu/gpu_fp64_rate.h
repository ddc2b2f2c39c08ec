// meshsal: how much slower a Vulkan device runs double than float arithmetic, measured.
// The exact sweep's `--precision auto` takes the mixed sweep (float distances and weights,
// gpu_sweep.h) only where doubles are slow: on NVIDIA's H200, whose doubles run at half the
// float rate, the double sweep took 0.45x the mixed one's time on igea_loop2
// (docs/benchmarks.md, "NVIDIA"), while consumer GPUs run doubles at 1/32 to 1/64.
#pragma once
#include <cstdint>

#include "gpu/vk_context.h"

namespace meshsal::gpu {

// Above this slowdown (double time / float time of the same fma chains) auto takes mixed.
// Measured: 1.7 on the H200, where double won; consumer GPUs' 32-64 is where mixed is
// meant to win (not measured here). 4 sits between them.
constexpr double kMixedAboveFp64Slowdown = 4.0;

// What --precision auto takes for the exact sweep: mixed on GPUs whose doubles are slow,
// double on CPU devices (lavapipe) and on GPUs with fast doubles.
inline bool auto_takes_mixed(bool cpu_device, double fp64_slowdown) {
  return !cpu_device && fp64_slowdown > kMixedAboveFp64Slowdown;
}

// The probe's per-lane result on the CPU: four fma chains from lane's seed, in float
// (use_double false) or double, summed: what shaders/fp64_rate.comp stores. Each chain
// x <- x * mul + add tends to add / (1 - mul).
double fp64_rate_chain(uint32_t lane, uint32_t iterations, float mul, float add, bool use_double);

struct Fp64Probe {
  double float_seconds = 0, double_seconds = 0;  // of the same chains, host-timed
  uint32_t lanes = 0, iterations = 0;
  double slowdown() const { return double_seconds / float_seconds; }
};

// Times the float and the double chains on `lanes` lanes (0: 2^18, enough to fill a large
// GPU), from `iterations` steps doubled until the float run takes at least `min_seconds`
// (at most 2^20 steps); the results are checked against fp64_rate_chain (an Error if they
// differ: a broken probe must not choose the precision).
Fp64Probe measure_fp64_rate(vk::Context& ctx, uint32_t lanes = 0, uint32_t iterations = 4096,
                            double min_seconds = 0.002);

// ctx's slowdown, measured once per context (0 lanes, the defaults) and kept in
// ctx.fp64_slowdown.
double fp64_slowdown(vk::Context& ctx);

}  // namespace meshsal::gpu
