// compute_saliency()'s backend switch and the `meshsal devices` command.
#include <catch2/catch.hpp>

#include <cstdio>
#include <string>

#include "meshsal/gpu_saliency.h"
#include "meshsal/saliency.h"
#include "meshsal/synthetic.h"
#include "meshsal/vk_context.h"

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

TEST_CASE("backend auto takes a hardware GPU or falls back to the CPU with a notice", "[gpu]") {
  Mesh m = make_bumpy_sphere(3);
  SaliencyOptions opt;
  opt.backend = Backend::Auto;
  std::string notice;
  int notices = 0;
  opt.notice = [&](const std::string& s) { notice = s, ++notices; };
  SaliencyResult r = compute_saliency(m, opt);
  auto devices = vk::list_devices();
  int hw = vk::pick_hardware_gpu(devices);
  if (hw < 0) {
    CHECK(r.backend_name.rfind("cpu", 0) == 0);
    CHECK(notices == 1);
    CHECK(notice.find("CPU") != std::string::npos);
  } else {
    CHECK(r.backend_name == devices[hw].name);
    CHECK(notices == 0);
  }
}

TEST_CASE("backend gpu with a missing device is a clear error", "[gpu]") {
  SaliencyOptions opt;
  opt.backend = Backend::Gpu;
  opt.device = 97;
  CHECK_THROWS_WITH(compute_saliency(make_sphere(1.0, 2), opt),
                    Catch::Contains("no Vulkan device 97"));
}

TEST_CASE("meshsal devices lists the Vulkan devices", "[gpu]") {
  std::string cmd = std::string(MESHSAL_CLI) + " devices 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  REQUIRE(p);
  std::string out;
  char buf[512];
  while (fgets(buf, sizeof buf, p)) out += buf;
  int rc = pclose(p);
  CHECK(rc == 0);
  auto devices = vk::list_devices();
  REQUIRE(!devices.empty());
  CHECK(out.find(devices[0].name) != std::string::npos);
  CHECK(out.find(devices[0].type) != std::string::npos);
}
