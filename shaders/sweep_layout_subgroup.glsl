// CPU twin: sweep_point_default() in src/saliency/sweep_kernels.inc
// meshsal: main() of the subgroup-per-point layout (GPUs).
// The sums of a point are sweep_point() in sweep.glsl, which every layout shares; the
// .comp files include sweep.glsl, then one layout.
void main() {
  // One subgroup per point: the lanes take consecutive candidates of each row (contiguous
  // loads, and every lane loops the same rows), then the sums are reduced across lanes.
  // The points are strided over the subgroups the driver actually made, so every point is
  // swept whatever subgroup size it picked (the host sizes the dispatch by the size the
  // device reports; a larger one only gives some subgroups two points).
  const uint stride = gl_NumWorkGroups.x * gl_NumSubgroups;
  const uint end = min(pc.n, pc.base + gl_NumWorkGroups.x * pc.per_group);  // this dispatch's
  for (uint i = pc.base + gl_WorkGroupID.x * gl_NumSubgroups + gl_SubgroupID; i < end; i += stride) {
    dvec4 p = sorted_pos[i];
    sweep_point(i, p, p.xyz, p.xyz, gl_SubgroupInvocationID, gl_SubgroupSize, true, sorted_vertex[i]);
  }
}
