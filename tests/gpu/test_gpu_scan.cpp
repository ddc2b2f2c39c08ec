// The device prefix sum (gpu_scan.h, scan_blocks.comp) against std::exclusive_scan: lengths
// around the block size (4096), one block, none, and arrays of many blocks, with values up
// to 2^16 (totals in the hundreds of millions).
#include <catch2/catch.hpp>

#include <cstdint>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "gpu/gpu_scan.h"
#include "gpu/vk_compute.h"
#include "gpu/vk_context.h"

using namespace meshsal;

TEST_CASE("gpu scan: exclusive prefix sums of any length, as std::exclusive_scan", "[gpu]") {
  const uint64_t before = vk::validation_message_count();
  for (bool staging : {false, true}) {
    vk::Context ctx(-1, true);
    ctx.use_staging = staging;
    const uint32_t max_n = 300000;
    vk::Buffer in(ctx, size_t(max_n) * 4, "test counts"), out(ctx, size_t(max_n + 1) * 4, "test starts");
    vk::DescriptorPool pool(ctx, gpu::Scan::kSets, gpu::Scan::kBuffers);
    gpu::Scan scan(ctx, pool, in, out, max_n);
    std::mt19937 rng(7);
    for (uint32_t n : {0u, 1u, 5u, 4095u, 4096u, 4097u, 8192u, 65537u, max_n}) {
      INFO("staging " << staging << ", n " << n);
      std::vector<uint32_t> v(n);
      // Mostly small counts with runs of zeros (as cell counts are), some large.
      for (uint32_t& x : v) x = rng() % 4 == 0 ? 0 : (rng() % 64 == 0 ? rng() % 65536 : rng() % 9);
      if (n) in.upload(v.data(), size_t(n) * 4);
      vk::submit(ctx, "test", [&](VkCommandBuffer cmd) { scan.record(ctx, cmd, n); });
      std::vector<uint32_t> want(n + 1, 0), got(n + 1);
      std::exclusive_scan(v.begin(), v.end(), want.begin(), 0u);
      if (n) want[n] = want[n - 1] + v[n - 1];
      out.download(got.data(), got.size() * 4);
      CHECK(got == want);
    }
    CHECK_THROWS_WITH(vk::submit(ctx, "test", [&](VkCommandBuffer cmd) { scan.record(ctx, cmd, max_n + 1); }),
                      Catch::Contains("room for 300000"));
  }
  CHECK(vk::validation_message_count() == before);
}
