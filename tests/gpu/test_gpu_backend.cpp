// compute_saliency()'s backend switch and the `meshsal devices` command.
#include <catch2/catch.hpp>

#include <cstdio>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include "gpu/gpu_saliency.h"
#include "saliency/saliency.h"
#include "cli/synthetic.h"
#include "gpu/vk_context.h"
#include "test_util.h"

using namespace meshsal;

TEST_CASE("backend gpu runs on a Vulkan device, lavapipe included", "[gpu]") {
  const uint64_t before = vk::validation_message_count();
  Mesh m = make_bumpy_sphere(3);
  SaliencyOptions opt;
  opt.backend = Backend::Gpu;
  opt.device = 0;
  auto devices = vk::list_devices();
  REQUIRE(!devices.empty());
  SaliencyResult r = compute_saliency_gpu(m, opt, true);
  CHECK(r.backend_name == devices[0].name);
  CHECK(r.saliency.size() == m.vertex_count());
  SaliencyResult via = compute_saliency(m, opt);
  CHECK(via.backend_name == devices[0].name);
  CHECK(via.saliency == r.saliency);  // same device, same code: the same numbers
  CHECK(vk::validation_message_count() == before);
}

TEST_CASE("backend auto takes a hardware GPU, else the CPU", "[gpu]") {
  Mesh m = make_bumpy_sphere(3);
  SaliencyOptions opt;
  opt.backend = Backend::Auto;
  int notices = 0;
  opt.notice = [&](const std::string&) { ++notices; };
  SaliencyResult r = compute_saliency(m, opt);
  auto devices = vk::list_devices();
  int hw = vk::pick_hardware_gpu(devices);
  if (hw < 0)
    CHECK(r.backend_name.rfind("cpu", 0) == 0);  // lavapipe alone is not taken by auto
  else
    CHECK(r.backend_name == devices[hw].name);
  CHECK(notices == 0);  // a plain choice, not a fallback
}

namespace {
struct Run {
  int rc;
  std::string out;
};
Run run(const std::string& cmd) {
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  REQUIRE(p);
  std::string out;
  char buf[512];
  while (fgets(buf, sizeof buf, p)) out += buf;
  int status = pclose(p);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}
}  // namespace

TEST_CASE("without any Vulkan driver: gpu is a clear error, auto falls back with a notice", "[gpu]") {
  const std::string cli = MESHSAL_CLI;
  const std::string out = "/tmp/meshsal_gpu_test_" + std::to_string(::getpid()) + ".ply";
  const std::string no_driver = "VK_ICD_FILENAMES=/nonexistent.json VK_DRIVER_FILES=/nonexistent.json ";
  MESHSAL_REQUIRE_MESH(spot, "spot_3k.obj");
  const std::string args = " saliency --threads 2 " + spot + " -o " + out;
  Run gpu = run(no_driver + cli + args + " --backend gpu");
  CHECK(gpu.rc == 1);
  CHECK(gpu.out.find("error: no Vulkan driver found") != std::string::npos);
  Run autorun = run(no_driver + cli + args + " --backend auto");
  CHECK(autorun.rc == 0);
  CHECK(autorun.out.find("auto: no Vulkan") != std::string::npos);
  CHECK(autorun.out.find("using the CPU path") != std::string::npos);
  CHECK(meshsal_test::file_exists(out));
  std::remove(out.c_str());
}

TEST_CASE("backend gpu with a missing device is a clear error", "[gpu]") {
  SaliencyOptions opt;
  opt.backend = Backend::Gpu;
  opt.device = 97;
  CHECK_THROWS_WITH(compute_saliency(make_sphere(1.0, 2), opt),
                    Catch::Contains("no Vulkan device 97"));
}

TEST_CASE("meshsal devices lists the Vulkan devices", "[gpu]") {
  Run r = run(std::string(MESHSAL_CLI) + " devices");
  CHECK(r.rc == 0);
  auto devices = vk::list_devices();
  REQUIRE(!devices.empty());
  CHECK(r.out.find(devices[0].name) != std::string::npos);
  CHECK(r.out.find(devices[0].type) != std::string::npos);
  const auto& d = devices[0];
  CHECK(r.out.find("device 0: " + d.name) != std::string::npos);
  CHECK(r.out.find("  type: " + d.type + ", Vulkan " + d.api_version) != std::string::npos);
  CHECK(r.out.find("subgroup size: " + std::to_string(d.subgroup_size) + ", fp64: " +
                   (d.has_float64 ? "yes" : "no") + ", largest storage buffer: ") != std::string::npos);
  CHECK(r.out.find("heap 0: ") != std::string::npos);
  CHECK(r.out.find(d.unified_memory ? "unified memory: yes" : "unified memory: no") != std::string::npos);
  if (d.type == "cpu") {  // lavapipe: 8 lanes (4 or 16 at other vector widths), 2 GiB heap
    CHECK(d.subgroup_size >= 4);
    CHECK(d.has_float64);
    CHECK(d.unified_memory);
    CHECK(r.out.find("device-local") != std::string::npos);
  }
  Run forced = run("MESHSAL_FORCE_STAGING=1 " + std::string(MESHSAL_CLI) + " devices");
  CHECK(forced.out.find("MESHSAL_FORCE_STAGING is set") != std::string::npos);
}
