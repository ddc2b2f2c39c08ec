// CPU twin: the run loop of fast_cell_runs() in src/gpu/gpu_fast_cells.cpp (and close_groups()
// in src/saliency/query_groups.cpp)
// meshsal: the second step of finding the runs of equal keys in a sorted array (after
// run_heads.comp and a scan of its heads into scan[0, n], exclusive): run r = scan[i] starts
// at i where scan[i+1] > scan[i], so first[r] = i, and run_first[runs] = count closes the
// last one; with flags bit 0 also run_key[r] = key[i]; with bit 1 item_run[value[i]] = the
// run holding i (the radix sort's values: where item i came from). The run count goes to
// counts[total_slot]; the keys' count comes from counts[count_slot] (~0: n).
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Key { uint key[]; };
layout(std430, binding = 1) readonly buffer Scan { uint scan[]; };  // n + 1
layout(std430, binding = 2) buffer Counts { uint counts[]; };
layout(std430, binding = 3) writeonly buffer RunFirst { uint run_first[]; };  // runs + 1
layout(std430, binding = 4) writeonly buffer RunKey { uint run_key[]; };
layout(std430, binding = 5) readonly buffer Value { uint value[]; };
layout(std430, binding = 6) writeonly buffer ItemRun { uint item_run[]; };
layout(push_constant) uniform Push { uint base; uint n; uint count_slot; uint total_slot; uint flags; } pc;
void main() {
  const uint i = pc.base + gl_GlobalInvocationID.x;
  if (i >= pc.n) return;
  const uint count = pc.count_slot == 0xffffffffu ? pc.n : counts[pc.count_slot];
  if (i == 0u && count == 0u) {
    run_first[0] = 0u;
    counts[pc.total_slot] = 0u;
  }
  if (i >= count) return;
  const uint r = scan[i], next = scan[i + 1u];
  if (next > r) {
    run_first[r] = i;
    if ((pc.flags & 1u) != 0u) run_key[r] = key[i];
  }
  if ((pc.flags & 2u) != 0u) item_run[value[i]] = next - 1u;
  if (i == count - 1u) {
    run_first[next] = count;
    counts[pc.total_slot] = next;
  }
}
