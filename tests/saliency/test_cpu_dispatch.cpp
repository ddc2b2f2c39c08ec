// The run-time choice of the CPU hot loops (saliency/cpu_dispatch.h, README "Portable
// build"): the AVX2 copies and the baseline ones give the same bits, in one process.
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "cli/synthetic.h"
#include "meshsal/meshsal.h"
#include "saliency/cpu_dispatch.h"
#include "test_util.h"

using namespace meshsal;

namespace {

SaliencyResult saliency_on(CpuPath path, const Mesh& mesh, SaliencyOptions options) {
  ScopedCpuPathForTests forced(path);
  REQUIRE(cpu_path() == path);
  options.backend = Backend::Cpu;
  options.smoothed = true;
  options.threads = 2;
  return compute_saliency(mesh, options);
}

// How many entries of a and b differ in any bit (0: bit-identical).
size_t bit_differences(const std::vector<double>& a, const std::vector<double>& b) {
  REQUIRE(a.size() == b.size());
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i) n += std::memcmp(&a[i], &b[i], sizeof(double)) != 0;
  return n;
}

// Saliency (curvature, raw maps, S and Sm) on both paths, compared bit for bit.
void check_paths_agree(const Mesh& mesh, Method method, std::vector<double> scales) {
  if (!cpu_avx2_available()) {
    meshsal_test::skip_case("no AVX2+FMA on this CPU (or not an x86-64 build): only the baseline path exists");
    return;
  }
  SaliencyOptions o;
  o.method = method;
  o.scales = std::move(scales);
  const SaliencyResult base = saliency_on(CpuPath::baseline, mesh, o);
  const SaliencyResult avx2 = saliency_on(CpuPath::avx2, mesh, o);
  REQUIRE(base.saliency.size() == mesh.vertex_count());
  CHECK(base.pairs == avx2.pairs);
  CHECK(bit_differences(base.curvature, avx2.curvature) == 0);
  REQUIRE(base.raw.size() == avx2.raw.size());
  for (size_t i = 0; i < base.raw.size(); ++i) {
    INFO("raw map " << i);
    CHECK(bit_differences(base.raw[i], avx2.raw[i]) == 0);
  }
  CHECK(bit_differences(base.saliency, avx2.saliency) == 0);
  CHECK(bit_differences(base.smoothed, avx2.smoothed) == 0);
  // Not all zero: the comparison compared something.
  double most = 0;
  for (double s : base.saliency) most = std::max(most, s);
  CHECK(most > 0);
}

}  // namespace

TEST_CASE("cpu dispatch: AVX2 and baseline paths are bit-identical on a synthetic mesh",
          "[cpu_dispatch][saliency]") {
  const Mesh m = make_bumpy_sphere(3);
  SECTION("exact, default scales (the fixed eight-sigma plan)") {
    check_paths_agree(m, Method::Exact, {2, 3, 4, 5, 6});
  }
  SECTION("exact, other scales (the generic plan)") {
    check_paths_agree(m, Method::Exact, {2.5, 3.5, 7});
  }
  SECTION("fast") { check_paths_agree(m, Method::Fast, {2, 3, 4, 5, 6}); }
}

TEST_CASE("cpu dispatch: AVX2 and baseline paths are bit-identical on a real scan",
          "[cpu_dispatch][saliency]") {
  MESHSAL_REQUIRE_MESH(path, "bunny_36k.obj");
  const Mesh m = load_mesh(path);
  SECTION("exact") { check_paths_agree(m, Method::Exact, {2, 3, 4, 5, 6}); }
  SECTION("fast") { check_paths_agree(m, Method::Fast, {2, 3, 4, 5, 6}); }
}

TEST_CASE("cpu dispatch: MESHSAL_CPU_BASELINE picks the baseline path", "[cpu_dispatch]") {
  const char* v = std::getenv("MESHSAL_CPU_BASELINE");
  const bool forced = v && *v && std::string(v) != "0";
  INFO("MESHSAL_CPU_BASELINE=" << (v ? v : "(unset)") << ", AVX2 available: " << cpu_avx2_available());
  CHECK(cpu_path() == (forced || !cpu_avx2_available() ? CpuPath::baseline : CpuPath::avx2));
  {
    ScopedCpuPathForTests b(CpuPath::baseline);
    CHECK(cpu_path() == CpuPath::baseline);
  }
  CHECK(cpu_path() == (forced || !cpu_avx2_available() ? CpuPath::baseline : CpuPath::avx2));
  if (!cpu_avx2_available()) CHECK_THROWS_AS(ScopedCpuPathForTests(CpuPath::avx2), Error);
}
