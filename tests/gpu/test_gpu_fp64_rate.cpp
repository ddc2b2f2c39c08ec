// The fp64 probe behind --precision auto (gpu_fp64_rate.h): its chains on the device equal
// their CPU twin (the probe checks them and throws otherwise), the chains' values are what
// the arithmetic says, and the rule takes mixed only on GPUs with slow doubles.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

#include "gpu/gpu_fp64_rate.h"
#include "gpu/vk_context.h"

using namespace meshsal;

TEST_CASE("fp64 probe chains: the CPU twin's values", "[gpu]") {
  // No steps: the seeds (lane & 7) + 0, 1, 2, 3.
  CHECK(gpu::fp64_rate_chain(0, 0, 0.999f, 0.001f, true) == 6.0);
  CHECK(gpu::fp64_rate_chain(9, 0, 0.999f, 0.001f, false) == 10.0);
  // One step: 4 * (seed * mul + add) + mul * 6, in double.
  const double mul = double(0.999f), add = double(0.001f);
  CHECK(gpu::fp64_rate_chain(2, 1, 0.999f, 0.001f, true) ==
        Approx(2 * mul + add + 3 * mul + add + 4 * mul + add + 5 * mul + add).epsilon(1e-15));
  // Many steps: each chain near add / (1 - mul) = 1, so about 4 (0.999^100000 ~ e^-100).
  CHECK(gpu::fp64_rate_chain(5, 100000, 0.999f, 0.001f, true) == Approx(4 * add / (1 - mul)).epsilon(1e-9));
  CHECK(gpu::fp64_rate_chain(5, 100000, 0.999f, 0.001f, false) == Approx(4.0).epsilon(1e-3));
}

TEST_CASE("fp64 probe on the device: results checked, both timings taken", "[gpu]") {
  const uint64_t before = vk::validation_message_count();
  vk::Context ctx(-1, true);
  // Small on lavapipe: 4096 lanes, from 64 steps up to 1 ms of float work.
  const gpu::Fp64Probe p = gpu::measure_fp64_rate(ctx, 4096, 64, 0.001);
  CHECK(p.lanes == 4096);
  CHECK(p.iterations >= 64);
  CHECK(p.float_seconds > 0);
  CHECK(p.double_seconds > 0);
  // A ratio of two timings (its value is a measurement, not asserted here: the suite runs
  // beside other tests; 1.4 with 8192 lanes on the 2-core VM, 1.7 on an H200).
  CHECK(std::isfinite(p.slowdown()));
  CHECK(p.slowdown() > 0);
  CHECK(vk::validation_message_count() == before);
}

TEST_CASE("precision auto: mixed only on GPUs with slow doubles", "[gpu]") {
  CHECK_FALSE(gpu::auto_takes_mixed(false, 1.7));  // the H200's measured slowdown
  CHECK_FALSE(gpu::auto_takes_mixed(false, 4.0));
  CHECK(gpu::auto_takes_mixed(false, 32.0));       // a consumer GPU's 1/32 rate
  CHECK_FALSE(gpu::auto_takes_mixed(true, 32.0));  // never on CPU devices
}
