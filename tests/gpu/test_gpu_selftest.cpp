#include "test_gpu_selftest.h"

#include "gpu/shader_interfaces.h"
#include "gpu/vk_buffer.h"
#include "gpu/vk_compute.h"

#include "selftest_comp.h"

namespace meshsal {

std::vector<float> gpu_selftest(vk::Context& ctx, const std::vector<float>& x, float a) {
  using Push = gpu::shader::SelftestPush;
  auto& k = vk::cached_kernel<gpu::shader::Selftest>(ctx, spv_selftest_comp, sizeof spv_selftest_comp, "selftest");
  vk::Buffer bx(ctx, x.size() * 4, "x"), by(ctx, x.size() * 4, "y");
  bx.upload(x.data(), x.size() * 4);
  vk::DescriptorPool pool(ctx, 1, 2);
  VkDescriptorSet set = pool.bind(k, {&bx, &by});
  Push p{0, 0, a};
  vk::submit(ctx, "selftest", [&](VkCommandBuffer cmd) {
    vk::dispatch(ctx, cmd, k, set, &p, 0, static_cast<uint32_t>(x.size()), 64);
  });
  std::vector<float> y(x.size());
  by.download(y.data(), y.size() * 4);
  return y;
}

}  // namespace meshsal
