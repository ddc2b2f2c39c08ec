// CPU twin: none: a Vulkan-layer self-test (tests/test_gpu_selftest.cpp)
// meshsal: the smallest useful kernel, y[i] = a * x[i] + i, to check the Vulkan layer
// (buffers, push constants, split dispatches) against the CPU in tests/test_gpu_vulkan.cpp.
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer X { float x[]; };
layout(std430, binding = 1) writeonly buffer Y { float y[]; };
layout(push_constant) uniform Push { uint base; uint n; float a; } pc;
void main() {
  uint i = pc.base + gl_GlobalInvocationID.x;
  if (i >= pc.n) return;
  y[i] = pc.a * x[i] + float(i);
}
