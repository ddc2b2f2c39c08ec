// CPU twin: most_candidates() in src/gpu/gpu_fast_bound.cpp
// meshsal: --method fast, the most candidates any query can walk, on the device: the
// aggregates in the (2r+1)^3 cells of the query grid around each cell (clipped to the grid),
// from the grid's cell starts, in three passes of sums along x (mode 0: from the starts, in
// O(1)), y (mode 1) and z (mode 2, which takes the maximum into counts[most_slot], one atomic
// per work group after a maximum in shared memory). The host splits each query's candidates
// into windows by it.
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Start { uint starts[]; };  // cells + 1
layout(std430, binding = 1) buffer A { uint a[]; };  // along x
layout(std430, binding = 2) buffer B { uint b[]; };  // along x and y
layout(std430, binding = 3) buffer Counts { uint counts[]; };
layout(push_constant) uniform Push { uint base; uint n; uint nx; uint ny; uint nz; uint r; uint mode; uint most_slot; } pc;
shared uint best[64];
void main() {
  const uint cell = pc.base + gl_GlobalInvocationID.x;
  const uint x = cell % pc.nx, y = cell / pc.nx % pc.ny, z = cell / pc.nx / pc.ny;
  const uint row = cell - x;
  if (pc.mode != 2u && cell >= pc.n) return;  // (no barrier in modes 0 and 1)
  if (pc.mode == 0u) {
    const uint hi = min(x + pc.r, pc.nx - 1u), lo = x >= pc.r ? x - pc.r : 0u;
    a[cell] = starts[row + hi + 1u] - starts[row + lo];
    return;
  }
  if (pc.mode == 1u) {
    const uint lo = y >= pc.r ? y - pc.r : 0u, hi = min(y + pc.r, pc.ny - 1u);
    uint s = 0u;
    for (uint t = lo; t <= hi; ++t) s += a[cell + (t - y) * pc.nx];
    b[cell] = s;
    return;
  }
  uint s = 0u;
  if (cell < pc.n) {
    const uint lo = z >= pc.r ? z - pc.r : 0u, hi = min(z + pc.r, pc.nz - 1u);
    const uint plane = pc.nx * pc.ny;
    for (uint t = lo; t <= hi; ++t) s += b[cell + (t - z) * plane];
  }
  const uint l = gl_LocalInvocationID.x;
  best[l] = s;
  barrier();
  for (uint off = 32u; off > 0u; off >>= 1u) {
    if (l < off) best[l] = max(best[l], best[l + off]);
    barrier();
  }
  if (l == 0u) atomicMax(counts[pc.most_slot], best[0]);
}
