// meshsal CLI: `meshsal devices` lists the Vulkan devices (index for --device, name, type,
// memory) and says which one `--backend auto` would take.
#include <cstdio>
#include <memory>

#include "command.h"
#if MESHSAL_WITH_VULKAN
#include "gpu/vk_context.h"
#endif

namespace meshsal_cli {

#if !MESHSAL_WITH_VULKAN
static RunFn setup_devices(CLI::App&) {
  return []() {
    std::printf("this meshsal was built without Vulkan: the CPU path is used\n");
    return 0;
  };
}
#else
static RunFn setup_devices(CLI::App& sub) {
  auto validation = std::make_shared<bool>(false);
  sub.add_flag("--validation", *validation, "enable the Khronos validation layer");
  return [validation]() {
    auto devices = meshsal::vk::list_devices(*validation);
    if (devices.empty()) {
      std::printf("no Vulkan devices (the CPU path is used)\n");
      return 0;
    }
    int hw = meshsal::vk::pick_hardware_gpu(devices);
    std::printf("%-3s %-40s %-11s %10s  %s\n", "#", "name", "type", "memory", "vulkan");
    for (const auto& d : devices)
      std::printf("%-3d %-40s %-11s %7.1f GiB  %s%s%s\n", d.index, d.name.c_str(), d.type.c_str(),
                  d.device_local_bytes / double(1u << 30), d.api_version.c_str(),
                  d.has_compute ? "" : "  (no compute queue)",
                  d.index == hw ? "  <- auto" : "");
    if (hw < 0) std::printf("--backend auto uses the CPU path (no discrete or integrated GPU)\n");
    return 0;
  };
}

#endif

static bool registered = register_command(
    {"devices", "list the Vulkan devices (for --backend gpu --device N)", 90, setup_devices});

}  // namespace meshsal_cli
