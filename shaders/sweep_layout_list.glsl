// CPU twin: sweep_point_default() in src/saliency/sweep_kernels.inc
// meshsal: main() of the point-list sweep (the near-tie recheck).
// The sums of a point are sweep_point() in sweep.glsl, which every layout shares; the
// .comp files include sweep.glsl, then one layout.
void main() {
  // One lane per listed vertex, its own box.
  const uint gid = gl_GlobalInvocationID.x;
  if (pc.base + gid >= pc.n) return;
  const uint v = point_list[pc.base + gid];
  dvec4 p = vertex_pos[v];
  sweep_point(0u, p, p.xyz, p.xyz, 0u, 1u, true, v);
}
