// The Vulkan layer's own check, used only by the tests: y[i] = a * x[i] + i on the device
// (buffers, push constants, dispatches split over maxComputeWorkGroupCount).
#pragma once
#include <vector>

#include "gpu/vk_context.h"

namespace meshsal {

std::vector<float> gpu_selftest(vk::Context& ctx, const std::vector<float>& x, float a);

}  // namespace meshsal
