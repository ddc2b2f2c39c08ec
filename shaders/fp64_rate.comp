// CPU twin: fp64_rate_chain() in src/gpu/gpu_fp64_rate.cpp (the value each lane must end with)
// meshsal: arithmetic throughput probe. Each lane runs four independent fma chains of
// `iterations` steps in float (specialization constant 0 = 0) or double (= 1); the host
// times both to learn how fast the device's doubles are (gpu_fp64_rate.h). The chains'
// inputs come from push constants and their result is stored, so nothing is folded away.
#version 450
layout(local_size_x = 64) in;
layout(constant_id = 0) const int use_double = 0;
layout(std430, binding = 0) writeonly buffer Out { double result[]; };
layout(push_constant) uniform Push { uint base; uint n; uint iterations; float mul; float add; } pc;

void main() {
  uint i = pc.base + gl_GlobalInvocationID.x;
  if (i >= pc.n) return;
  if (use_double == 1) {
    double m = double(pc.mul), c = double(pc.add);
    double a = double(i & 7u), b = a + 1.0, d = a + 2.0, e = a + 3.0;
    for (uint k = 0u; k < pc.iterations; ++k) {
      a = fma(a, m, c); b = fma(b, m, c); d = fma(d, m, c); e = fma(e, m, c);
    }
    result[i] = a + b + d + e;
  } else {
    float m = pc.mul, c = pc.add;
    float a = float(i & 7u), b = a + 1.0, d = a + 2.0, e = a + 3.0;
    for (uint k = 0u; k < pc.iterations; ++k) {
      a = fma(a, m, c); b = fma(b, m, c); d = fma(d, m, c); e = fma(e, m, c);
    }
    result[i] = double(a + b + d + e);
  }
}
