// CPU twin: suppress() in src/saliency/suppression.cpp (the mean of the local maxima)
// meshsal: mbar_i = mean of the normalised local maxima (the global one excluded), and the
// factor (1 - mbar_i)^2 / max_i that suppress() (suppression.cpp) applies. One group per scale.
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Partial { dvec2 partial[]; };
layout(std430, binding = 1) readonly buffer Max { double map_max[]; };
layout(std430, binding = 2) writeonly buffer Factor { double factor[]; };  // [i]; mbar at [16 + i]
layout(push_constant) uniform Push { uint base; uint n; uint groups; } pc;
shared dvec2 red[64];
void main() {
  uint i = gl_WorkGroupID.x + pc.base / 64u;
  uint t = gl_LocalInvocationID.x;
  dvec2 acc = dvec2(0.0LF);
  for (uint g = t; g < pc.groups; g += 64u) acc += partial[i * pc.groups + g];
  red[t] = acc;
  barrier();
  for (uint off = 32u; off > 0u; off >>= 1u) {
    if (t < off) red[t] += red[t + off];
    barrier();
  }
  if (t == 0u) {
    double mx = map_max[i];
    double mbar = red[0].y > 0.0LF ? red[0].x / red[0].y : 0.0LF;
    factor[i] = mx > 0.0LF ? (1.0LF - mbar) * (1.0LF - mbar) / mx : 0.0LF;
    factor[16u + i] = mbar;
  }
}
