// CPU twin: std::exclusive_scan (tests/gpu/test_gpu_scan.cpp holds it to one)
// meshsal: the exclusive prefix sum of count[0, n) into start[0, n] (start[n] = the total) in
// three dispatches that keep every work group busy, for arrays of millions of entries (the
// radix sort's digit counts are as many as its keys): mode 0, each block of BLOCK entries
// summed into block[b]; mode 1, one work group scans the nblocks block sums in place
// (block[nblocks] = the total); mode 2, each block scanned and offset by its block's start.
// Each work group is a block (base: the first block of the dispatch).
#version 450
layout(local_size_x = 256) in;
layout(std430, binding = 0) readonly buffer Count { uint count[]; };
layout(std430, binding = 1) writeonly buffer Start { uint start[]; };
layout(std430, binding = 2) buffer Block { uint block[]; };  // nblocks + 1
layout(push_constant) uniform Push { uint base; uint nblocks; uint n; uint mode; } pc;
shared uint partial[256];
// Entries per thread and per block (gpu_scan.cpp's kBlock): few barriers per entry, which
// a CPU device (lavapipe) pays dearly.
const uint ITEMS = 16u;
const uint BLOCK = 256u * ITEMS;

// The inclusive scan of the 256 threads' values in partial[] (Hillis-Steele).
void scan_partial(uint t) {
  for (uint off = 1u; off < 256u; off <<= 1u) {
    uint add = (t >= off) ? partial[t - off] : 0u;
    barrier();
    partial[t] += add;
    barrier();
  }
}

void main() {
  const uint t = gl_LocalInvocationID.x;
  if (pc.mode == 1u) {  // one work group: the block sums, in chunks of 1024 with a carry
    uint carry = 0u;
    for (uint chunk = 0u; chunk < pc.nblocks; chunk += 1024u) {
      const uint i0 = chunk + 4u * t;
      uint a[4];
      uint sum = 0u;
      for (uint k = 0u; k < 4u; ++k) {
        a[k] = (i0 + k < pc.nblocks) ? block[i0 + k] : 0u;
        sum += a[k];
      }
      partial[t] = sum;
      barrier();
      scan_partial(t);
      uint run = carry + partial[t] - sum;
      for (uint k = 0u; k < 4u; ++k) {
        if (i0 + k < pc.nblocks) block[i0 + k] = run;
        run += a[k];
      }
      carry += partial[255];
      barrier();
    }
    if (t == 0u) block[pc.nblocks] = carry;
    return;
  }
  const uint b = pc.base + gl_WorkGroupID.x;
  if (b >= pc.nblocks) return;  // uniform across the work group
  const uint i0 = b * BLOCK + ITEMS * t;
  uint a[ITEMS];
  uint sum = 0u;
  for (uint k = 0u; k < ITEMS; ++k) {
    a[k] = (i0 + k < pc.n) ? count[i0 + k] : 0u;
    sum += a[k];
  }
  partial[t] = sum;
  barrier();
  if (pc.mode == 0u) {  // the block's sum
    for (uint off = 128u; off > 0u; off >>= 1u) {
      if (t < off) partial[t] += partial[t + off];
      barrier();
    }
    if (t == 0u) block[b] = partial[0];
    return;
  }
  scan_partial(t);
  uint run = block[b] + partial[t] - sum;
  for (uint k = 0u; k < ITEMS; ++k) {
    if (i0 + k < pc.n) start[i0 + k] = run;
    run += a[k];
  }
  if (b == pc.nblocks - 1u && t == 0u) start[pc.n] = block[pc.nblocks];
}
