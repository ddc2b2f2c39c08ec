// meshsal: mbar_i = mean of the normalised local maxima (the global one excluded), and the
// factor (1 - mbar_i)^2 / max_i that suppress() (suppression.cpp) applies. One group per scale.
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Partial { vec2 partial[]; };
layout(std430, binding = 1) readonly buffer Max { uint max_bits[]; };
layout(std430, binding = 2) writeonly buffer Factor { float factor[]; };  // [i]; mbar at [16 + i]
layout(push_constant) uniform Push { uint base; uint n; uint groups; } pc;
shared vec2 red[64];
void main() {
  uint i = gl_WorkGroupID.x + pc.base / 64u;
  uint t = gl_LocalInvocationID.x;
  vec2 acc = vec2(0.0);
  for (uint g = t; g < pc.groups; g += 64u) acc += partial[i * pc.groups + g];
  red[t] = acc;
  barrier();
  for (uint off = 32u; off > 0u; off >>= 1u) {
    if (t < off) red[t] += red[t + off];
    barrier();
  }
  if (t == 0u) {
    float mx = uintBitsToFloat(max_bits[i]);
    float mbar = red[0].y > 0.0 ? red[0].x / red[0].y : 0.0;
    factor[i] = mx > 0.0 ? (1.0 - mbar) * (1.0 - mbar) / mx : 0.0;
    factor[16u + i] = mbar;
  }
}
