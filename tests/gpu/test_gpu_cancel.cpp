// Issue 21 (5) on the Vulkan path: a set cancel flag stops the GPU saliency (exact and fast)
// between submissions with Cancelled, and the cached device stays usable afterwards.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "cli/synthetic.h"
#include "meshsal/meshsal.h"

using namespace meshsal;

TEST_CASE("gpu cancel: a set flag stops the GPU saliency, the device works after it", "[gpu][cancel]") {
  const Mesh m = make_bumpy_sphere(3);
  std::atomic<bool> stop{false};
  SaliencyOptions so;
  so.backend = Backend::Gpu;
  so.device = 0;
  so.cancel = &stop;
  // Set during the GPU's own work (its first progress report comes after a submission), so
  // that the GPU loop's poll, not the CPU curvature's, is what stops it.
  so.progress = [&](const char*, double) { stop = true; };
  for (Method method : {Method::Exact, Method::Fast}) {
    stop = false;
    so.method = method;
    bool cancelled = false;
    try {
      compute_saliency(m, so);
    } catch (const Cancelled&) {
      cancelled = true;
    }
    CHECK(cancelled);
  }
  stop = false;
  so.progress = nullptr;
  so.method = Method::Exact;
  const SaliencyResult r = compute_saliency(m, so);
  SaliencyOptions cpu = so;
  cpu.backend = Backend::Cpu;
  const SaliencyResult c = compute_saliency(m, cpu);
  REQUIRE(r.saliency.size() == c.saliency.size());
  double worst = 0;
  for (size_t i = 0; i < c.saliency.size(); ++i) worst = std::max(worst, std::fabs(r.saliency[i] - c.saliency[i]));
  CHECK(worst < 1e-6);
}
