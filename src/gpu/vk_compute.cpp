// meshsal: compute pipelines, descriptor sets and fenced submissions (see vk_compute.h).
#include "gpu/vk_compute.h"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <memory>
#include <string>

#include "meshsal/meshsal.h"

namespace meshsal::vk {

std::atomic<uint64_t> host_barriers_recorded{0};

Kernel::Kernel(Context& ctx, const uint32_t* spirv, size_t spirv_bytes, uint32_t n_bindings,
               uint32_t push, const char* kernel_name, const std::vector<int32_t>& specialization)
    : name(kernel_name), bindings(n_bindings), push_bytes(push), ctx_(ctx) {
  if (push > ctx.properties.limits.maxPushConstantsSize)
    throw Error(std::string("shader ") + name + " needs more push constants than the device has");
  std::vector<VkDescriptorSetLayoutBinding> b(bindings);
  for (uint32_t i = 0; i < bindings; ++i) {
    b[i] = {};
    b[i].binding = i;
    b[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    b[i].descriptorCount = 1;
    b[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
  }
  VkDescriptorSetLayoutCreateInfo dl{};
  dl.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  dl.bindingCount = bindings;
  dl.pBindings = b.data();
  VkShaderModule module = VK_NULL_HANDLE;
  try {
    check(vkCreateDescriptorSetLayout(ctx.device, &dl, nullptr, &set_layout),
          "vkCreateDescriptorSetLayout");
    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes};
    VkPipelineLayoutCreateInfo pl{};
    pl.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    pl.setLayoutCount = 1;
    pl.pSetLayouts = &set_layout;
    pl.pushConstantRangeCount = push_bytes ? 1 : 0;
    pl.pPushConstantRanges = &range;
    check(vkCreatePipelineLayout(ctx.device, &pl, nullptr, &layout), "vkCreatePipelineLayout");
    VkShaderModuleCreateInfo mi{};
    mi.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
    mi.codeSize = spirv_bytes;
    mi.pCode = spirv;
    check(vkCreateShaderModule(ctx.device, &mi, nullptr, &module), "vkCreateShaderModule");
    VkComputePipelineCreateInfo ci{};
    ci.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
    ci.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    ci.stage.module = module;
    ci.stage.pName = "main";
    std::vector<VkSpecializationMapEntry> entries(specialization.size());
    for (size_t i = 0; i < entries.size(); ++i)
      entries[i] = {uint32_t(i), uint32_t(i * sizeof(int32_t)), sizeof(int32_t)};
    VkSpecializationInfo spec{uint32_t(entries.size()), entries.data(),
                              specialization.size() * sizeof(int32_t), specialization.data()};
    if (!specialization.empty()) ci.stage.pSpecializationInfo = &spec;
    ci.layout = layout;
    check(vkCreateComputePipelines(ctx.device, VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline),
          (std::string("creating compute pipeline ") + name).c_str());
    vkDestroyShaderModule(ctx.device, module, nullptr);
  } catch (...) {
    if (module) vkDestroyShaderModule(ctx.device, module, nullptr);
    if (layout) vkDestroyPipelineLayout(ctx.device, layout, nullptr);
    if (set_layout) vkDestroyDescriptorSetLayout(ctx.device, set_layout, nullptr);
    throw;
  }
}

Kernel::~Kernel() {
  vkDestroyPipeline(ctx_.device, pipeline, nullptr);
  vkDestroyPipelineLayout(ctx_.device, layout, nullptr);
  vkDestroyDescriptorSetLayout(ctx_.device, set_layout, nullptr);
}

DescriptorPool::DescriptorPool(Context& ctx, uint32_t max_sets, uint32_t max_buffers) : ctx_(ctx) {
  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, max_buffers};
  VkDescriptorPoolCreateInfo pi{};
  pi.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  pi.maxSets = max_sets;
  pi.poolSizeCount = 1;
  pi.pPoolSizes = &size;
  check(vkCreateDescriptorPool(ctx.device, &pi, nullptr, &pool_), "vkCreateDescriptorPool");
}

DescriptorPool::~DescriptorPool() {
  VkDevice device = ctx_.device;
  VkDescriptorPool pool = pool_;
  auto destroy = [device, pool] { vkDestroyDescriptorPool(device, pool, nullptr); };
  if (ctx_.has_abandoned_work())
    ctx_.deferred_destroy.push_back(destroy);  // a timed-out submission may still use it
  else
    destroy();
}

VkDescriptorSet DescriptorPool::bind(const Kernel& kernel, const std::vector<const Buffer*>& buffers) {
  if (buffers.size() != kernel.bindings)
    throw Error(std::string("internal: wrong number of buffers for shader ") + kernel.name);
  VkDescriptorSetAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  ai.descriptorPool = pool_;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &kernel.set_layout;
  VkDescriptorSet set = VK_NULL_HANDLE;
  check(vkAllocateDescriptorSets(ctx_.device, &ai, &set), "vkAllocateDescriptorSets");
  std::vector<VkDescriptorBufferInfo> infos(buffers.size());
  std::vector<VkWriteDescriptorSet> writes(buffers.size());
  for (size_t i = 0; i < buffers.size(); ++i) {
    infos[i] = {buffers[i]->handle(), 0, VK_WHOLE_SIZE};
    writes[i] = {};
    writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    writes[i].dstSet = set;
    writes[i].dstBinding = static_cast<uint32_t>(i);
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[i].pBufferInfo = &infos[i];
  }
  vkUpdateDescriptorSets(ctx_.device, static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);
  return set;
}

void submit(Context& ctx, const char* what, const std::function<void(VkCommandBuffer)>& record) {
  PendingSubmission(ctx, what, record).wait();
}

PendingSubmission::PendingSubmission(Context& ctx, const char* what,
                                     const std::function<void(VkCommandBuffer)>& record)
    : ctx_(&ctx), what_(what) {
  VkCommandBufferAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  ai.commandPool = ctx.command_pool;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  check(vkAllocateCommandBuffers(ctx.device, &ai, &cmd_), "vkAllocateCommandBuffers");
  try {
    VkCommandBufferBeginInfo bi{};
    bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(cmd_, &bi), "vkBeginCommandBuffer");
    record(cmd_);
    host_barrier(cmd_);
    check(vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");
    VkFenceCreateInfo fi{};
    fi.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    check(vkCreateFence(ctx.device, &fi, nullptr, &fence_), "vkCreateFence");
    VkSubmitInfo si{};
    si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd_;
    const VkResult submitted = vkQueueSubmit(ctx.queue, 1, &si, fence_);
    // The message is built only on failure: past a successful submit nothing may throw
    // (the catch below would free a fence and commands the device is using).
    if (submitted != VK_SUCCESS) check(submitted, (std::string("submitting ") + what).c_str());
  } catch (...) {
    // Nothing was submitted (vkQueueSubmit failed or was never reached).
    release();
    throw;
  }
}

PendingSubmission& PendingSubmission::operator=(PendingSubmission&& o) noexcept {
  if (this != &o) {
    if (fence_) {
      try {
        wait();
      } catch (...) {
        // Dropped, as the destructor drops it.
      }
    }
    release();
    ctx_ = o.ctx_;
    what_ = o.what_;
    fence_ = o.fence_;
    cmd_ = o.cmd_;
    o.fence_ = VK_NULL_HANDLE;
    o.cmd_ = VK_NULL_HANDLE;
  }
  return *this;
}

PendingSubmission::~PendingSubmission() {
  if (fence_) {
    try {
      wait();
    } catch (...) {
      // An error while another is already on its way (or in a destructor): dropped.
    }
  }
  release();
}

void PendingSubmission::release() noexcept {
  if (!ctx_) return;
  if (fence_) vkDestroyFence(ctx_->device, fence_, nullptr);
  if (cmd_) vkFreeCommandBuffers(ctx_->device, ctx_->command_pool, 1, &cmd_);
  fence_ = VK_NULL_HANDLE;
  cmd_ = VK_NULL_HANDLE;
}

void PendingSubmission::wait() {
  if (!fence_) return;
  Context& ctx = *ctx_;
  const uint64_t timeout_ns = static_cast<uint64_t>(ctx.fence_timeout_s * 1e9);
  ++ctx.host_waits;
  const VkResult r = vkWaitForFences(ctx.device, 1, &fence_, VK_TRUE, timeout_ns);
  if (r == VK_TIMEOUT) {
    // The work may still be running: keep what it uses until the context goes.
    ctx.abandoned_fences.push_back(fence_);
    ctx.abandoned_commands.push_back(cmd_);
    fence_ = VK_NULL_HANDLE;
    cmd_ = VK_NULL_HANDLE;
    throw Error(std::string("Vulkan stage '") + what_ + "' did not finish within " +
                std::to_string(ctx.fence_timeout_s) + " s on '" + ctx.info.name + "'");
  }
  if (r != VK_SUCCESS) {
    // Lost device and the like: the fence is signalled or never will be; freed now, as
    // submit() always freed it.
    release();
    check(r, (std::string("waiting for ") + what_).c_str());
  }
  release();
}

void dispatch(Context& ctx, VkCommandBuffer cmd, const Kernel& kernel, VkDescriptorSet set,
              void* push, uint32_t begin, uint32_t end, uint32_t local_size,
              uint32_t groups_y) {
  if (end <= begin || groups_y == 0) return;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, kernel.pipeline);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, kernel.layout, 0, 1, &set, 0, nullptr);
  if (groups_y > ctx.properties.limits.maxComputeWorkGroupCount[1])
    throw Error(std::string("internal: too many work groups in y for shader ") + kernel.name);
  const uint64_t max_groups = std::min<uint64_t>(ctx.properties.limits.maxComputeWorkGroupCount[0], 65535);
  const uint64_t per_dispatch = max_groups * local_size;
  for (uint64_t base = begin; base < end; base += per_dispatch) {
    uint32_t words[2] = {static_cast<uint32_t>(base), end};
    std::memcpy(push, words, sizeof words);
    vkCmdPushConstants(cmd, kernel.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, kernel.push_bytes, push);
    uint64_t items = std::min<uint64_t>(per_dispatch, end - base);
    vkCmdDispatch(cmd, static_cast<uint32_t>((items + local_size - 1) / local_size), groups_y, 1);
  }
}

Kernel& cached_kernel(Context& ctx, const uint32_t* spirv, size_t spirv_bytes,
                      uint32_t bindings, uint32_t push_bytes, const char* name,
                      const std::vector<int32_t>& specialization) {
  std::string key = std::to_string(reinterpret_cast<uintptr_t>(spirv));
  for (int32_t v : specialization) key += "," + std::to_string(v);
  auto& slot = ctx.kernel_cache[key];
  if (!slot)
    slot = std::make_unique<Kernel>(ctx, spirv, spirv_bytes, bindings, push_bytes, name, specialization);
  return *slot;
}

void host_barrier(VkCommandBuffer cmd) {
  VkMemoryBarrier b{};
  b.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
  b.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  b.dstAccessMask = VK_ACCESS_HOST_READ_BIT | VK_ACCESS_SHADER_READ_BIT |
                    VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT |
                    VK_ACCESS_TRANSFER_WRITE_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT |
                           VK_PIPELINE_STAGE_TRANSFER_BIT,
                       0, 1, &b, 0, nullptr, 0, nullptr);
  ++host_barriers_recorded;
}

void barrier(VkCommandBuffer cmd) {
  VkMemoryBarrier b{};
  b.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
  b.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  b.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                    VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1,
                       &b, 0, nullptr, 0, nullptr);
}

}  // namespace meshsal::vk
