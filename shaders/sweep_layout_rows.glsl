// CPU twin: sweep_point_default() in src/saliency/sweep_kernels.inc
// meshsal: main() of the lane-per-point layout (CPU devices: lavapipe).
// The sums of a point are sweep_point() in sweep.glsl, which every layout shares; the
// .comp files include sweep.glsl, then one layout.
void main() {
  // One lane per point (lavapipe, where a lane is an AVX2 slot). The lanes of a subgroup
  // take consecutive sorted points and walk the rows of cells around the box of those of
  // the group's points that lie in their own row of cells, so they load the same
  // candidates at once and their loop bounds agree (except where a group straddles two
  // rows). Any box that holds the lane's own point gives the right sums; the group only
  // decides how much is shared, so a work group holds 64 points whatever the subgroup
  // size. The box must stay small: with the box of all the
  // subgroup's points (by subgroupMin/Max or by these loads alike), a group straddling
  // rows walked a box across the whole mesh, and lavapipe gave fewer pairs than the CPU
  // and wrong sums for ~100 of igea_loop1's 537k points (most likely lavapipe's limit:
  // it ends an invocation's loops silently after 65535 steps in all, and a box across the
  // mesh takes more); with boxes of one row of cells igea_loop1 matches the CPU exactly.
  const uint gid = gl_GlobalInvocationID.x;
  const uint i = min(pc.base + gid, pc.n - 1u);
  const bool live = pc.base + gid < pc.n;
  const uint g0 = pc.base + gid - gid % gl_SubgroupSize;
  dvec4 p = sorted_pos[i];
  dvec3 lo = p.xyz, hi = p.xyz;
  const ivec2 my_row = ivec2(p.yz / pc.h);
  for (uint e = 0u; e < gl_SubgroupSize; ++e) {
    dvec3 o = sorted_pos[min(g0 + e, pc.n - 1u)].xyz;
    if (ivec2(o.yz / pc.h) == my_row) {
      lo = min(lo, o);
      hi = max(hi, o);
    }
  }
  // A row whose points lie far apart (two crossings of the surface): each lane alone.
  if (hi.x - lo.x > 2.0LF * pc.h) {
    lo = p.xyz;
    hi = p.xyz;
  }
  sweep_point(i, p, lo, hi, 0u, 1u, live, sorted_vertex[i]);
}
