// CPU twin: total_swept_pairs() in src/gpu/gpu_sweep.cpp
// meshsal: --method fast, each sigma's (query, cell) pair counts summed on the device: a work
// group of 256 queries adds its counts (in double: exact below 2^53) and counts the queries
// that were never swept (a count of 0; every query counts at least its own cell), into
// partial[offset + group], so the host reads one small array for all sigmas at the end.
#version 450
layout(local_size_x = 256) in;
layout(std430, binding = 0) readonly buffer Pairs { uint pairs[]; };
layout(std430, binding = 1) writeonly buffer Partial { dvec2 partial[]; };  // sum, unswept
layout(push_constant) uniform Push { uint base; uint n; uint first; } pc;  // n = queries; first: the sigma's first partial
shared dvec2 red[256];
void main() {
  const uint q = pc.base + gl_GlobalInvocationID.x;
  const uint t = gl_LocalInvocationID.x;
  dvec2 mine = dvec2(0.0LF);
  if (q < pc.n) mine = dvec2(double(pairs[q]), pairs[q] == 0u ? 1.0LF : 0.0LF);
  red[t] = mine;
  barrier();
  for (uint off = 128u; off > 0u; off >>= 1u) {
    if (t < off) red[t] += red[t + off];
    barrier();
  }
  if (t == 0u) partial[pc.first + pc.base / 256u + gl_WorkGroupID.x] = red[0];
}
