// meshsal: Vulkan instance, device choice and validation messages (see vk_context.h).
#include "gpu/vk_context.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "meshsal/meshsal.h"
#include "gpu/vk_compute.h"
#include "gpu/vk_staging.h"

namespace meshsal::vk {

static std::atomic<uint64_t> g_validation_messages{0};

static const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

const char* result_name(VkResult r) {
  switch (r) {
    case VK_SUCCESS: return "VK_SUCCESS";
    case VK_NOT_READY: return "VK_NOT_READY";
    case VK_TIMEOUT: return "VK_TIMEOUT";
    case VK_INCOMPLETE: return "VK_INCOMPLETE";
    case VK_ERROR_OUT_OF_HOST_MEMORY: return "VK_ERROR_OUT_OF_HOST_MEMORY";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
    case VK_ERROR_INITIALIZATION_FAILED: return "VK_ERROR_INITIALIZATION_FAILED";
    case VK_ERROR_DEVICE_LOST: return "VK_ERROR_DEVICE_LOST";
    case VK_ERROR_MEMORY_MAP_FAILED: return "VK_ERROR_MEMORY_MAP_FAILED";
    case VK_ERROR_LAYER_NOT_PRESENT: return "VK_ERROR_LAYER_NOT_PRESENT";
    case VK_ERROR_EXTENSION_NOT_PRESENT: return "VK_ERROR_EXTENSION_NOT_PRESENT";
    case VK_ERROR_FEATURE_NOT_PRESENT: return "VK_ERROR_FEATURE_NOT_PRESENT";
    case VK_ERROR_INCOMPATIBLE_DRIVER: return "VK_ERROR_INCOMPATIBLE_DRIVER";
    case VK_ERROR_TOO_MANY_OBJECTS: return "VK_ERROR_TOO_MANY_OBJECTS";
    case VK_ERROR_OUT_OF_POOL_MEMORY: return "VK_ERROR_OUT_OF_POOL_MEMORY";
    default: return "VkResult error";
  }
}

void check(VkResult r, const char* what) {
  if (r == VK_SUCCESS) return;
  if (r == VK_ERROR_DEVICE_LOST)
    throw Error(std::string(what) + ": the Vulkan device was lost (driver reset or crash)");
  throw Error(std::string(what) + " failed: " + result_name(r) + " (" +
              std::to_string(static_cast<int>(r)) + ")");
}

bool validation_requested_by_env() {
  const char* v = std::getenv("MESHSAL_VALIDATION");
  return v && *v && std::strcmp(v, "0") != 0;
}

bool force_staging_by_env() {
  const char* v = std::getenv("MESHSAL_FORCE_STAGING");
  return v && *v && std::strcmp(v, "0") != 0;
}

uint64_t device_memory_available(const DeviceInfo& info) {
  uint64_t best = 0;
  for (const HeapInfo& h : info.heaps) {
    if (!h.device_local) continue;
    uint64_t usable = h.budget ? std::min(h.budget, h.bytes) : h.bytes;
    best = std::max(best, usable);
  }
  if (!best || (info.device_local_bytes && info.device_local_bytes < best))
    best = info.device_local_bytes;
  return best;
}

uint64_t heap_room(const Context& ctx, uint32_t heap) {
  uint64_t room = ctx.memory.memoryHeaps[heap].size;
  if (ctx.info.has_memory_budget) {
    VkPhysicalDeviceMemoryBudgetPropertiesEXT budget{};
    budget.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_BUDGET_PROPERTIES_EXT;
    VkPhysicalDeviceMemoryProperties2 m2{};
    m2.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_PROPERTIES_2;
    m2.pNext = &budget;
    vkGetPhysicalDeviceMemoryProperties2(ctx.physical, &m2);
    const uint64_t b = budget.heapBudget[heap], used = budget.heapUsage[heap];
    if (b) room = std::min(room, b > used ? b - used : 0);
  } else if (heap < ctx.info.heaps.size() && ctx.info.heaps[heap].budget) {
    room = std::min(room, ctx.info.heaps[heap].budget);  // set by hand (tests)
  }
  return room;
}

uint64_t validation_message_count() { return g_validation_messages.load(); }

static VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
  if (severity & (VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                  VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT)) {
    g_validation_messages++;
    std::fprintf(stderr, "vulkan validation: %s\n", data && data->pMessage ? data->pMessage : "?");
  }
  return VK_FALSE;
}

static bool layer_available(const char* name) {
  uint32_t n = 0;
  if (vkEnumerateInstanceLayerProperties(&n, nullptr) != VK_SUCCESS) return false;
  std::vector<VkLayerProperties> layers(n);
  if (vkEnumerateInstanceLayerProperties(&n, layers.data()) != VK_SUCCESS) return false;
  for (const auto& l : layers)
    if (std::strcmp(l.layerName, name) == 0) return true;
  return false;
}

static VkDebugUtilsMessengerCreateInfoEXT messenger_info() {
  VkDebugUtilsMessengerCreateInfoEXT mi{};
  mi.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
  mi.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  mi.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                   VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                   VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  mi.pfnUserCallback = on_validation_message;
  return mi;
}

// Creates the instance (with the validation layer and a messenger when asked).
static VkInstance create_instance(bool validation, VkDebugUtilsMessengerEXT* messenger) {
  if (validation && !layer_available(kValidationLayer))
    throw Error("Vulkan validation was requested but VK_LAYER_KHRONOS_validation is not "
                "installed (Debian: vulkan-validationlayers)");
  VkApplicationInfo app{};
  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = "meshsal";
  app.apiVersion = VK_API_VERSION_1_1;
  VkInstanceCreateInfo ci{};
  ci.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  ci.pApplicationInfo = &app;
  const char* ext = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
  VkDebugUtilsMessengerCreateInfoEXT mi = messenger_info();
  if (validation) {
    ci.enabledLayerCount = 1;
    ci.ppEnabledLayerNames = &kValidationLayer;
    ci.enabledExtensionCount = 1;
    ci.ppEnabledExtensionNames = &ext;
    ci.pNext = &mi;  // also catches messages from vkCreateInstance/vkDestroyInstance
  }
  VkInstance instance = VK_NULL_HANDLE;
  VkResult r = vkCreateInstance(&ci, nullptr, &instance);
  if (r == VK_ERROR_INCOMPATIBLE_DRIVER || r == VK_ERROR_INITIALIZATION_FAILED)
    throw Error("no Vulkan driver found (vkCreateInstance: " + std::string(result_name(r)) + ")");
  check(r, "vkCreateInstance");
  if (validation && messenger) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    if (!create || create(instance, &mi, nullptr, messenger) != VK_SUCCESS) {
      vkDestroyInstance(instance, nullptr);
      throw Error("Vulkan validation: could not create the debug-utils messenger");
    }
  }
  return instance;
}

static void destroy_instance(VkInstance instance, VkDebugUtilsMessengerEXT messenger) {
  if (!instance) return;
  if (messenger) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance, messenger, nullptr);
  }
  vkDestroyInstance(instance, nullptr);
}

static std::vector<VkPhysicalDevice> physical_devices(VkInstance instance) {
  uint32_t n = 0;
  check(vkEnumeratePhysicalDevices(instance, &n, nullptr), "vkEnumeratePhysicalDevices");
  std::vector<VkPhysicalDevice> devs(n);
  if (n) check(vkEnumeratePhysicalDevices(instance, &n, devs.data()), "vkEnumeratePhysicalDevices");
  devs.resize(n);
  return devs;
}

static int compute_family(VkPhysicalDevice pd) {
  uint32_t n = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, nullptr);
  std::vector<VkQueueFamilyProperties> fams(n);
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, fams.data());
  for (uint32_t i = 0; i < n; ++i)
    if (fams[i].queueFlags & VK_QUEUE_COMPUTE_BIT) return static_cast<int>(i);
  return -1;
}

static bool has_device_extension(VkPhysicalDevice pd, const char* name) {
  uint32_t n = 0;
  if (vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr) != VK_SUCCESS) return false;
  std::vector<VkExtensionProperties> ext(n);
  if (vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, ext.data()) != VK_SUCCESS) return false;
  for (const auto& e : ext)
    if (std::strcmp(e.extensionName, name) == 0) return true;
  return false;
}

// Heaps, their budgets (VK_EXT_memory_budget) and whether the memory is unified.
static void describe_memory(VkPhysicalDevice pd, const VkPhysicalDeviceProperties& p,
                            DeviceInfo* d) {
  VkPhysicalDeviceMemoryProperties m;
  vkGetPhysicalDeviceMemoryProperties(pd, &m);
  VkPhysicalDeviceMemoryBudgetPropertiesEXT budget{};
  budget.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_BUDGET_PROPERTIES_EXT;
  d->has_memory_budget = p.apiVersion >= VK_API_VERSION_1_1 &&
                         has_device_extension(pd, VK_EXT_MEMORY_BUDGET_EXTENSION_NAME);
  if (d->has_memory_budget) {
    VkPhysicalDeviceMemoryProperties2 m2{};
    m2.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_PROPERTIES_2;
    m2.pNext = &budget;
    vkGetPhysicalDeviceMemoryProperties2(pd, &m2);
  }
  for (uint32_t i = 0; i < m.memoryHeapCount; ++i) {
    HeapInfo h;
    h.bytes = m.memoryHeaps[i].size;
    h.device_local = (m.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) != 0;
    h.budget = d->has_memory_budget ? budget.heapBudget[i] : 0;
    d->heaps.push_back(h);
    if (h.device_local) d->device_local_bytes = std::max(d->device_local_bytes, h.bytes);
  }
  const VkMemoryPropertyFlags mapped = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT |
                                       VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                       VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  bool host_maps_device_memory = false;
  for (uint32_t i = 0; i < m.memoryTypeCount; ++i)
    if ((m.memoryTypes[i].propertyFlags & mapped) == mapped &&
        m.memoryHeaps[m.memoryTypes[i].heapIndex].size >= d->device_local_bytes)
      host_maps_device_memory = true;
  d->unified_memory = host_maps_device_memory &&
                      (p.deviceType == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU ||
                       p.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU);
}

// The subgroup properties of a Vulkan 1.1 device (the caller checks the version).
static VkPhysicalDeviceSubgroupProperties subgroup_properties(VkPhysicalDevice pd) {
  VkPhysicalDeviceSubgroupProperties sub{};
  sub.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES;
  VkPhysicalDeviceProperties2 p2{};
  p2.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
  p2.pNext = &sub;
  vkGetPhysicalDeviceProperties2(pd, &p2);
  return sub;
}

static DeviceInfo describe(VkPhysicalDevice pd, int index) {
  VkPhysicalDeviceProperties p;
  vkGetPhysicalDeviceProperties(pd, &p);
  DeviceInfo d;
  d.index = index;
  d.name = p.deviceName;
  d.vk_type = p.deviceType;
  switch (p.deviceType) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: d.type = "discrete"; break;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: d.type = "integrated"; break;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: d.type = "virtual"; break;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: d.type = "cpu"; break;
    default: d.type = "other"; break;
  }
  describe_memory(pd, p, &d);
  d.max_storage_buffer = p.limits.maxStorageBufferRange;
  if (p.apiVersion >= VK_API_VERSION_1_1) d.subgroup_size = subgroup_properties(pd).subgroupSize;
  VkPhysicalDeviceFeatures features{};
  vkGetPhysicalDeviceFeatures(pd, &features);
  d.has_float64 = features.shaderFloat64 == VK_TRUE;
  d.api_version = std::to_string(VK_API_VERSION_MAJOR(p.apiVersion)) + "." +
                  std::to_string(VK_API_VERSION_MINOR(p.apiVersion)) + "." +
                  std::to_string(VK_API_VERSION_PATCH(p.apiVersion));
  d.has_compute = compute_family(pd) >= 0;
  return d;
}

std::vector<DeviceInfo> list_devices(bool validation) {
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkInstance instance = create_instance(validation || validation_requested_by_env(), &messenger);
  std::vector<DeviceInfo> out;
  try {
    auto devs = physical_devices(instance);
    for (size_t i = 0; i < devs.size(); ++i) out.push_back(describe(devs[i], static_cast<int>(i)));
  } catch (...) {
    destroy_instance(instance, messenger);
    throw;
  }
  destroy_instance(instance, messenger);
  return out;
}

static int type_rank(VkPhysicalDeviceType t) {
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
    default: return 4;
  }
}

int pick_hardware_gpu(const std::vector<DeviceInfo>& devices) {
  int best = -1;
  for (const auto& d : devices) {
    if (!d.has_compute || type_rank(d.vk_type) > 1) continue;
    if (best < 0 || type_rank(d.vk_type) < type_rank(devices[best].vk_type)) best = d.index;
  }
  return best;
}

Context::Context(int device_index, bool want_validation) {
  validation = want_validation || validation_requested_by_env();
  instance = create_instance(validation, &messenger_);
  try {
    auto devs = physical_devices(instance);
    if (devs.empty()) throw Error("no Vulkan device found");
    int chosen = -1;
    if (device_index >= 0) {
      if (device_index >= static_cast<int>(devs.size()))
        throw Error("no Vulkan device " + std::to_string(device_index) + " (there are " +
                    std::to_string(devs.size()) + "; see `meshsal devices`)");
      chosen = device_index;
    } else {
      for (size_t i = 0; i < devs.size(); ++i) {
        DeviceInfo d = describe(devs[i], static_cast<int>(i));
        if (!d.has_compute) continue;
        if (chosen < 0 || type_rank(d.vk_type) < type_rank(info.vk_type)) {
          chosen = static_cast<int>(i);
          info = d;
        }
      }
      if (chosen < 0) throw Error("no Vulkan device with a compute queue");
    }
    physical = devs[chosen];
    info = describe(physical, chosen);
    int family = compute_family(physical);
    if (family < 0) throw Error("Vulkan device '" + info.name + "' has no compute queue");
    queue_family = static_cast<uint32_t>(family);
    vkGetPhysicalDeviceProperties(physical, &properties);
    vkGetPhysicalDeviceMemoryProperties(physical, &memory);
    use_staging = !info.unified_memory || force_staging_by_env();

    float priority = 1.0f;
    VkDeviceQueueCreateInfo qi{};
    qi.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
    qi.queueFamilyIndex = queue_family;
    qi.queueCount = 1;
    qi.pQueuePriorities = &priority;
    if (properties.apiVersion >= VK_API_VERSION_1_1) {
      const VkPhysicalDeviceSubgroupProperties sub = subgroup_properties(physical);
      subgroup_size = sub.subgroupSize;
      subgroup_arithmetic = (sub.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) &&
                            (sub.supportedOperations & VK_SUBGROUP_FEATURE_ARITHMETIC_BIT);
    }
    VkPhysicalDeviceFeatures supported{}, enabled{};
    vkGetPhysicalDeviceFeatures(physical, &supported);
    has_float64 = supported.shaderFloat64 == VK_TRUE;
    enabled.shaderFloat64 = supported.shaderFloat64;
    VkDeviceCreateInfo di{};
    di.pEnabledFeatures = &enabled;
    di.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
    di.queueCreateInfoCount = 1;
    di.pQueueCreateInfos = &qi;
    VkResult r = vkCreateDevice(physical, &di, nullptr, &device);
    if (r != VK_SUCCESS)
      throw Error("could not open Vulkan device '" + info.name + "': " + result_name(r));
    vkGetDeviceQueue(device, queue_family, 0, &queue);

    VkCommandPoolCreateInfo pi{};
    pi.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    pi.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pi.queueFamilyIndex = queue_family;
    check(vkCreateCommandPool(device, &pi, nullptr, &command_pool), "vkCreateCommandPool");
  } catch (...) {
    if (device) vkDestroyDevice(device, nullptr);
    destroy_instance(instance, messenger_);
    throw;
  }
}

// Every submission is waited for by its own fence, so only abandoned (timed-out) work can
// still run here: wait for those fences, bounded, instead of an unbounded vkDeviceWaitIdle.
// If they still do not signal, the device and what it may use are left to the driver's
// process tear-down rather than destroyed under running work (or waited for forever).
Context::~Context() {
  prestaged.reset();  // no work uses them (a call takes a buffer off before it uses it)
  if (device && !abandoned_fences.empty()) {
    const uint64_t timeout_ns = uint64_t(std::max(fence_timeout_s, 1.0) * 1e9);
    VkResult r = vkWaitForFences(device, uint32_t(abandoned_fences.size()),
                                 abandoned_fences.data(), VK_TRUE, timeout_ns);
    if (r != VK_SUCCESS) {
      std::fprintf(stderr, "meshsal: abandoned Vulkan work on '%s' did not finish; "
                           "its device is not destroyed\n", info.name.c_str());
      staging.release();
      for (auto& kernel : kernel_cache) kernel.second.release();
      return;
    }
  }
  if (device) {
    staging.reset();
    for (auto& destroy : deferred_destroy) destroy();
    kernel_cache.clear();
    for (VkFence f : abandoned_fences) vkDestroyFence(device, f, nullptr);
    if (!abandoned_commands.empty())
      vkFreeCommandBuffers(device, command_pool, uint32_t(abandoned_commands.size()),
                           abandoned_commands.data());
    if (command_pool) vkDestroyCommandPool(device, command_pool, nullptr);
    vkDestroyDevice(device, nullptr);
  }
  destroy_instance(instance, messenger_);
}

}  // namespace meshsal::vk
