// CPU twin: the run loop of fast_cell_runs() in src/gpu/gpu_fast_cells.cpp (and close_groups()
// in src/saliency/query_groups.cpp)
// meshsal: the first step of finding the runs of equal keys in a sorted array on the device:
// head[i] = 1 where a run starts (i == 0 or key[i] != key[i-1]), 0 elsewhere and past the
// keys' count, which is read from counts[count_slot] (written by an earlier step of the same
// submission, so the host never reads it back), or is n when count_slot is ~0. A scan of
// the heads (scan_blocks.comp, gpu_scan.h) numbers the runs; run_starts.comp writes where each begins.
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Key { uint key[]; };
layout(std430, binding = 1) readonly buffer Counts { uint counts[]; };
layout(std430, binding = 2) writeonly buffer Head { uint head[]; };
layout(push_constant) uniform Push { uint base; uint n; uint count_slot; uint total_slot; uint flags; } pc;
void main() {
  const uint i = pc.base + gl_GlobalInvocationID.x;
  if (i >= pc.n) return;
  const uint count = pc.count_slot == 0xffffffffu ? pc.n : counts[pc.count_slot];
  head[i] = (i < count && (i == 0u || key[i] != key[i - 1u])) ? 1u : 0u;
}
