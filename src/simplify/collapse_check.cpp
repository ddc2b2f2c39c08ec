// meshsal (internal): the collapse check, see collapse_check.h.
#include "simplify/collapse_check.h"

#include <algorithm>
#include <cmath>

#include "simplify/triangle_bits.h"

namespace meshsal {
namespace detail {

Check CollapseCheck::edge(const CheckSurface& s, uint32_t a, uint32_t b, const double np[3]) {
  if (!s.seams || !s.seams->seam_edge(a, b)) return side(s, a, b, np, false);
  if (s.faces < s.target + 2) return Check::Refused;  // two collapses, one face each
  const std::vector<uint32_t>& partner = s.seams->partner;
  Check c = side(s, a, b, np, true);
  if (c == Check::Ok) c = side(s, partner[a], partner[b], np, true);
  if (c == Check::Ok && !s.seams->welded_link_ok(*s.fans, a, b, 2, true)) c = Check::Refused;
  return c;
}

bool CollapseCheck::bad_triangle(const CheckSurface& s, uint32_t t, uint32_t moved, const double np[3]) {
  const uint32_t* v = s.fans->corners_of(t);
  const auto p = [&](uint32_t x) { return s.vert[x].p; };
  const double min_cos = s.min_cos;
  const double* q[3] = {p(v[0]), p(v[1]), p(v[2])};
  const double* r[3] = {q[0], q[1], q[2]};
  for (int k = 0; k < 3; ++k)
    if (v[k] == moved) r[k] = np;
  double e1[3], e2[3], n_old[3], n_new[3];
  for (int k = 0; k < 3; ++k) { e1[k] = q[1][k] - q[0][k]; e2[k] = q[2][k] - q[0][k]; }
  cross3(e1, e2, n_old);
  double l2max = 0;
  for (int k = 0; k < 3; ++k) { e1[k] = r[1][k] - r[0][k]; e2[k] = r[2][k] - r[0][k]; }
  cross3(e1, e2, n_new);
  for (int i = 0; i < 3; ++i) {
    const double* x = r[i];
    const double* y = r[(i + 1) % 3];
    const double d[3] = {y[0] - x[0], y[1] - x[1], y[2] - x[2]};
    l2max = std::max(l2max, dot3(d, d));
  }
  // Squared lengths compared: no square roots in the common case (min_cos 0).
  const double len2_new = dot3(n_new, n_new);
  // Degenerate: twice the area below 1e-6 of the longest edge squared (a needle or cap
  // thinner than about a micro-radian), or no area at all.
  if (!(len2_new > 1e-12 * l2max * l2max) || !(l2max > 0)) return true;
  const double len2_old = dot3(n_old, n_old);
  if (!(len2_old > 0)) return false;
  const double d = dot3(n_old, n_new);
  if (min_cos == 0) return d <= 0;
  return d <= min_cos * std::sqrt(len2_old * len2_new);
}

// Branch-light: which triangles hold both ends is a coin toss per triangle, so the loops
// below write unconditionally and advance their counts by the comparison instead.
Check CollapseCheck::side(const CheckSurface& s, uint32_t a, uint32_t b, const double np[3],
                          bool seam_side) {
  TriangleFans& fans = *s.fans;
  const std::vector<uint32_t>& tri = fans.corners;
  const std::vector<uint8_t>& tri_alive = fans.live;
  const auto p = [&](uint32_t x) { return s.vert[x].p; };
  const uint8_t* const border = s.border;
  const size_t faces = s.faces, target = s.target;
  for (uint32_t v : {a, b})  // scattered loads: issue them together
    for (uint32_t t : fans.fan(v)) {
      __builtin_prefetch(&tri[3 * size_t(t)]);
      __builtin_prefetch(&tri_alive[t]);
    }
  // Drop dead triangles from both lists first (they are only ever appended to).
  fans.compact(a);
  fans.compact(b);
  const uint32_t na = fans.fan_size(a), nb = fans.fan_size(b);
  if (opp_.size() < na) {
    opp_.resize(na);
    flip_a_.resize(na);
  }
  if (flip_b_.size() < nb) flip_b_.resize(nb);
  // a's triangles: those on the edge give the vertices opposite it (k of them); the two
  // other corners of every triangle of a are marked (mark[] == in_a) for the link
  // condition. Marking b changes nothing below: b is never a corner of b's triangles.
  const uint32_t counted = s.marks->new_stamps(2), in_a = counted - 1;
  uint32_t* const mark = s.marks->mark.data();
  uint32_t* const op = opp_.data();
  uint32_t* const fa = flip_a_.data();
  uint32_t* const fb = flip_b_.data();
  size_t k = 0, nfa = 0, nfb = 0;
  const uint32_t* la = fans.fan_begin(a);
  for (uint32_t i = 0; i < na; ++i) {
    const uint32_t t = la[i];
    const uint32_t* v = &tri[3 * size_t(t)];
    const bool has_b = has_corner(v, b);
    uint32_t x, y;
    other_corners(v, a, &x, &y);
    __builtin_prefetch(p(x));  // for the flip tests below: all misses at once
    __builtin_prefetch(p(y));
    mark[x] = in_a;
    mark[y] = in_a;
    op[k] = x ^ y ^ b;  // on the edge, {x, y} = {b, opposite}
    k += has_b;
    fa[nfa] = t;
    nfa += !has_b;
  }
  if (k == 0) return Check::NotEdge;
  if (seam_side && k != 1) return Check::Refused;  // a seam edge is a border on each side
  if (k > 2) return Check::Refused;                 // non-manifold edge
  if (k > faces - target) return Check::Refused;    // would overshoot the target
  if (k == 2 && (op[0] == op[1] || (border[a] && border[b]))) return Check::Refused;

  // Link condition on vertices: the common neighbours of a and b are exactly the k
  // opposites (each counted once: marks turn from in_a to counted). b's triangles on the
  // edge add a (never marked) and an opposite, which is counted here or in its other
  // triangle.
  // A triangle (b, x, y) would also land on a triangle (a, x, y) after the collapse (e.g.
  // the tetrahedron). Then x and y are common neighbours, so when the link condition holds
  // they are the two opposites: only the pair {opp0, opp1} has to be looked for, in both.
  const uint32_t o0 = op[0], o1 = k == 2 ? op[1] : op[0];
  auto is_opp_pair = [&](uint32_t x, uint32_t y) {
    return k == 2 && (((x == o0) & (y == o1)) | ((x == o1) & (y == o0)));
  };
  bool b_has_pair = false, a_has_pair = false;
  size_t common = 0;
  const uint32_t* lb = fans.fan_begin(b);
  for (uint32_t i = 0; i < nb; ++i) {
    const uint32_t t = lb[i];
    const uint32_t* v = &tri[3 * size_t(t)];
    const bool has_a = has_corner(v, a);
    uint32_t x, y;
    other_corners(v, b, &x, &y);
    __builtin_prefetch(p(x));
    __builtin_prefetch(p(y));
    b_has_pair |= is_opp_pair(x, y);
    for (uint32_t z : {x, y}) {
      const bool m = mark[z] == in_a;
      mark[z] = select_u32(m, counted, mark[z]);
      common += m;
    }
    fb[nfb] = t;
    nfb += !has_a;
  }
  if (common != k) return Check::Refused;
  if (b_has_pair) {
    for (uint32_t i = 0; i < na; ++i) {
      uint32_t x, y;
      other_corners(&tri[3 * size_t(la[i])], a, &x, &y);
      a_has_pair |= is_opp_pair(x, y);
    }
    if (a_has_pair) return Check::Refused;
  }

  // Flips, fold-overs and degenerate triangles among those that remain.
  for (size_t i = 0; i < nfa; ++i)
    if (bad_triangle(s, fa[i], a, np)) return Check::Refused;
  for (size_t i = 0; i < nfb; ++i)
    if (bad_triangle(s, fb[i], b, np)) return Check::Refused;
  // Twins at one position are one vertex of the surface: the link condition again, welded
  // (along a seam edge() does it for both sides at once).
  if (s.seams && s.seams->has_twins && !seam_side && (s.seams->near_seam[a] | s.seams->near_seam[b]) &&
      !s.seams->welded_link_ok(fans, a, b, k, false))
    return Check::Refused;
  return Check::Ok;
}

}  // namespace detail
}  // namespace meshsal
