// CPU twin: the cell starts of build_spatial_grid() in src/saliency/spatial_grid.cpp
// meshsal: exclusive prefix sum of the cell counts into cell starts (starts[n] = total), in
// one work group walking the array in chunks of 1024 with a running carry. The grid has at
// most a few million cells, so this is a small part of the grid build.
#version 450
layout(local_size_x = 256) in;
layout(std430, binding = 0) readonly buffer Count { uint cell_count[]; };
layout(std430, binding = 1) writeonly buffer Start { uint starts[]; };
layout(push_constant) uniform Push { uint base; uint n; } pc;
shared uint partial[256];
void main() {
  uint t = gl_LocalInvocationID.x;
  uint carry = 0u;
  for (uint chunk = 0u; chunk < pc.n; chunk += 1024u) {
    uint i0 = chunk + 4u * t;
    uint a[4];
    uint sum = 0u;
    for (uint k = 0u; k < 4u; ++k) {
      a[k] = (i0 + k < pc.n) ? cell_count[i0 + k] : 0u;
      sum += a[k];
    }
    partial[t] = sum;
    barrier();
    // Hillis-Steele inclusive scan of the 256 thread sums.
    for (uint off = 1u; off < 256u; off <<= 1u) {
      uint add = (t >= off) ? partial[t - off] : 0u;
      barrier();
      partial[t] += add;
      barrier();
    }
    uint run = carry + partial[t] - sum;  // exclusive prefix of this thread's first item
    for (uint k = 0u; k < 4u; ++k) {
      if (i0 + k < pc.n) starts[i0 + k] = run;
      run += a[k];
    }
    carry += partial[255];
    barrier();
  }
  if (t == 0u) starts[pc.n] = carry;
}
