// meshsal: the float/double throughput probe (see gpu_fp64_rate.h).
#include "gpu/gpu_fp64_rate.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/timer.h"
#include "gpu/shader_interfaces.h"
#include "gpu/vk_compute.h"
#include "meshsal/meshsal.h"

#include "fp64_rate_comp.h"

namespace meshsal::gpu {

namespace {

using Push = shader::Fp64RatePush;  // gpu/shader_interfaces.h

template <typename T>
double chain(uint32_t lane, uint32_t iterations, T m, T c) {
  T a = T(lane & 7u), b = a + T(1), d = a + T(2), e = a + T(3);
  for (uint32_t k = 0; k < iterations; ++k) {
    a = std::fma(a, m, c), b = std::fma(b, m, c), d = std::fma(d, m, c), e = std::fma(e, m, c);
  }
  return double(a + b + d + e);
}

}  // namespace

double fp64_rate_chain(uint32_t lane, uint32_t iterations, float mul, float add, bool use_double) {
  return use_double ? chain<double>(lane, iterations, mul, add) : chain<float>(lane, iterations, mul, add);
}

Fp64Probe measure_fp64_rate(vk::Context& ctx, uint32_t lanes, uint32_t iterations, double min_seconds) {
  if (!ctx.has_float64) throw Error("the Vulkan device has no 64-bit floats in shaders");
  Fp64Probe probe;
  probe.lanes = lanes ? lanes : 1u << 18;
  // mul < 1 keeps every chain bounded (it tends to add / (1 - mul)).
  Push push{0, probe.lanes, std::max(1u, iterations), 0.999f, 0.001f};
  vk::Buffer out(ctx, size_t(probe.lanes) * 8, "the fp64 probe's results");
  vk::Kernel& k_float = vk::cached_kernel<shader::Fp64Rate>(ctx, spv_fp64_rate_comp, sizeof spv_fp64_rate_comp, "fp64_rate (float)", {0});
  vk::Kernel& k_double = vk::cached_kernel<shader::Fp64Rate>(ctx, spv_fp64_rate_comp, sizeof spv_fp64_rate_comp, "fp64_rate (double)", {1});
  vk::DescriptorPool pool(ctx, 2, 2);
  const VkDescriptorSet s_float = pool.bind(k_float, {&out}), s_double = pool.bind(k_double, {&out});
  auto timed = [&](vk::Kernel& k, VkDescriptorSet set) {
    const Timer t;
    vk::submit(ctx, "the fp64 probe", [&](VkCommandBuffer cmd) {
      Push p = push;
      vk::dispatch(ctx, cmd, k, set, &p, 0, probe.lanes, 64);
    });
    return t.seconds();
  };
  auto check = [&](bool use_double) {
    std::vector<double> got(probe.lanes);
    out.download(got.data(), got.size() * 8);
    for (uint32_t lane = 0; lane < 8 && lane < probe.lanes; ++lane) {
      const double want = fp64_rate_chain(lane, push.iterations, push.mul, push.add, use_double);
      if (!(std::fabs(got[lane] - want) <= 1e-4 * std::fabs(want)))
        throw Error("the fp64 probe computed " + std::to_string(got[lane]) + " where " +
                    std::to_string(want) + " was due (lane " + std::to_string(lane) + ")");
    }
  };
  timed(k_float, s_float);  // the first run pays the pipeline's compile
  for (;;) {
    probe.float_seconds = timed(k_float, s_float);
    if (probe.float_seconds >= min_seconds || push.iterations >= (1u << 20)) break;
    push.iterations *= 2;
  }
  check(false);
  timed(k_double, s_double);
  probe.double_seconds = timed(k_double, s_double);
  check(true);
  probe.iterations = push.iterations;
  return probe;
}

double fp64_slowdown(vk::Context& ctx) {
  if (ctx.fp64_slowdown == 0) ctx.fp64_slowdown = measure_fp64_rate(ctx).slowdown();
  return ctx.fp64_slowdown;
}

}  // namespace meshsal::gpu
