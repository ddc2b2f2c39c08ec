// meshsal CLI: `meshsal devices` lists the Vulkan devices (index for --device, name, type,
// subgroup size, fp64, largest storage buffer, memory heaps, unified memory or not) and
// says which one `--backend auto` would take.
#include <cstdio>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "command.h"
#include "json_object.h"
#include "meshsal/meshsal.h"
#if MESHSAL_WITH_VULKAN
#include "gpu/vk_context.h"
#endif

namespace meshsal::cli {

// --json: one JSON array on one line, an object per device as the library lists them
// (meshsal::list_devices; Python's meshsal.devices() gives the same keys); [] without any.
static int print_devices_json() {
  std::vector<meshsal::DeviceInfo> devices;
  if (meshsal::built_with_vulkan()) devices = meshsal::list_devices();
  std::string out = "[";
  for (const meshsal::DeviceInfo& d : devices) {
    if (out.size() > 1) out += ",";
    out += JsonObject()
               .count("index", uint64_t(d.index))
               .text("name", d.name)
               .text("type", d.type)
               .count("device_local_bytes", d.device_local_bytes)
               .text("api_version", d.api_version)
               .flag("has_compute", d.has_compute)
               .str();
  }
  out += "]\n";
  std::fputs(out.c_str(), stdout);
  std::fflush(stdout);
  return 0;
}

static void add_json_flag(CLI::App& sub, bool& json) {
  sub.add_flag("--json", json,
               "Print the devices as one JSON array on stdout: index, name, type, device_local_bytes, "
               "api_version, has_compute");
  // Accepted as every command takes it: the list is the command's result, printed either way.
  sub.add_flag("-q,--quiet", "Print only the list (it has no notes or progress)");
}

#if !MESHSAL_WITH_VULKAN
static RunFn setup_devices(CLI::App& sub) {
  auto json = std::make_shared<bool>(false);
  add_json_flag(sub, *json);
  return [json]() {
    if (*json) return print_devices_json();
    std::printf("this meshsal was built without Vulkan: the CPU path is used\n");
    return 0;
  };
}
#else
static std::string size_text(uint64_t bytes) {
  char buf[32];
  if (bytes >= (uint64_t(1) << 30))
    std::snprintf(buf, sizeof buf, "%.1f GiB", double(bytes) / double(uint64_t(1) << 30));
  else
    std::snprintf(buf, sizeof buf, "%.0f MiB", double(bytes) / double(1u << 20));
  return buf;
}

static RunFn setup_devices(CLI::App& sub) {
  auto validation = std::make_shared<bool>(false);
  sub.add_flag("--validation", *validation, "enable the Khronos validation layer");
  auto json = std::make_shared<bool>(false);
  add_json_flag(sub, *json);
  return [validation, json]() {
    if (*json) return print_devices_json();
    auto devices = meshsal::vk::list_devices(*validation);
    if (devices.empty()) {
      std::printf("no Vulkan devices (the CPU path is used)\n");
      return 0;
    }
    int hw = meshsal::vk::pick_hardware_gpu(devices);
    for (const auto& d : devices) {
      std::printf("device %d: %s%s\n", d.index, d.name.c_str(), d.index == hw ? "  <- auto" : "");
      std::printf("  type: %s, Vulkan %s%s\n", d.type.c_str(), d.api_version.c_str(),
                  d.has_compute ? "" : ", no compute queue");
      std::printf("  subgroup size: %u, fp64: %s, largest storage buffer: %s\n", d.subgroup_size,
                  d.has_float64 ? "yes" : "no", size_text(d.max_storage_buffer).c_str());
      for (size_t h = 0; h < d.heaps.size(); ++h) {
        std::printf("  heap %zu: %s%s", h, size_text(d.heaps[h].bytes).c_str(),
                    d.heaps[h].device_local ? " device-local" : " host");
        if (d.heaps[h].budget) std::printf(", budget %s", size_text(d.heaps[h].budget).c_str());
        std::printf("\n");
      }
      std::printf("  unified memory: %s\n",
                  d.unified_memory ? "yes (buffers mapped, no staging copies)"
                                   : "no (device-local buffers, transfers through staging)");
    }
    if (meshsal::vk::force_staging_by_env())
      std::printf("MESHSAL_FORCE_STAGING is set: every device uses staging copies\n");
    if (hw < 0) std::printf("--backend auto uses the CPU path (no discrete or integrated GPU)\n");
    return 0;
  };
}

#endif

static bool registered = register_command(
    {"devices",
     "list the Vulkan devices (for --backend gpu --device N): type, subgroup size, fp64, "
     "largest storage buffer, memory heaps, unified memory (else transfers go through a "
     "staging area; MESHSAL_FORCE_STAGING=1 forces that on any device)",
     90, setup_devices});

}  // namespace meshsal::cli
