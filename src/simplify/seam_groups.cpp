// meshsal (internal): seam twins, see seam_groups.h.
#include "simplify/seam_groups.h"

#include <string>

namespace meshsal {
namespace detail {

void SeamGroups::build(const std::vector<uint32_t>& pv, const std::vector<uint32_t>& inv,
                       const std::vector<uint32_t>& corners, bool lock_border,
                       std::vector<uint8_t>* locked) {
  const size_t nv = inv.size();
  if (pv.size() != nv) throw Error("simplify: position_vertex does not have one entry per vertex");
  std::vector<uint32_t> group(nv, 0);  // per group (input id): its size
  for (size_t i = 0; i < nv; ++i) {
    if (pv[i] > i || pv[pv[i]] != pv[i])
      throw Error("simplify: position_vertex of vertex " + std::to_string(i) + " is not a lower vertex that stands for itself");
    ++group[pv[i]];
  }
  for (size_t i = 0; i < nv; ++i) (*locked)[inv[i]] |= group[pv[i]] > 1;  // a seam twin
  twin_next.assign(nv, NONE);
  group_of.resize(nv);
  std::vector<uint32_t> last(nv, NONE);  // per group (input id): the member linked last
  for (size_t i = 0; i < nv; ++i) {
    const uint32_t v = inv[i], r = pv[i];
    group_of[v] = inv[r];
    if (group[r] < 2) continue;
    has_twins = true;
    if (last[r] == NONE) {
      twin_next[v] = v;
    } else {  // insert after the last one, closing the cycle through the first
      twin_next[v] = twin_next[last[r]];
      twin_next[last[r]] = v;
    }
    last[r] = v;
  }
  weld_mark.assign(nv, 0);
  near_seam.assign(nv, 0);
  for (size_t t = 0; t < corners.size(); t += 3)
    if (twin_next[corners[t]] != NONE || twin_next[corners[t + 1]] != NONE || twin_next[corners[t + 2]] != NONE)
      near_seam[corners[t]] = near_seam[corners[t + 1]] = near_seam[corners[t + 2]] = 1;
  if (!lock_border) {
    partner.assign(nv, NONE);
    for (size_t v = 0; v < nv; ++v)
      if (twin_next[v] != NONE && twin_next[twin_next[v]] == v && twin_next[v] != v) partner[v] = twin_next[v];
  }
}

bool SeamGroups::welded_link_ok(const TriangleFans& fans, uint32_t a, uint32_t b, size_t expected,
                                bool along_seam) {
  weld_stamp += 2;
  const uint32_t seen = weld_stamp, counted = weld_stamp + 1;
  const uint32_t ga = group_of[a], gb = group_of[b];
  // Calls f(member, corner) over the live triangles of v's group (v alone outside one).
  auto for_group = [&](uint32_t v, auto f) {
    uint32_t w = v;
    do {
      for (uint32_t t : fans.fan(w))
        if (fans.live[t])
          for (int c = 0; c < 3; ++c) f(w, fans.corners[3 * size_t(t) + c]);
      w = twin_next[w] == NONE ? v : twin_next[w];
    } while (w != v);
  };
  bool ok = true;
  // The edge itself (and its twin along a seam) is the only contact between the groups.
  auto allowed_contact = [&](uint32_t w, uint32_t c, uint32_t self, uint32_t other) {
    return (w == self && c == other) || (along_seam && w == partner[self] && c == partner[other]);
  };
  for_group(b, [&](uint32_t w, uint32_t c) {
    const uint32_t g = group_of[c];
    if (g == ga) ok &= allowed_contact(w, c, b, a);
    else if (g != gb) weld_mark[g] = seen;
  });
  size_t common = 0;
  for_group(a, [&](uint32_t w, uint32_t c) {
    const uint32_t g = group_of[c];
    if (g == gb) ok &= allowed_contact(w, c, a, b);
    if (weld_mark[g] == seen) {
      weld_mark[g] = counted;
      ++common;
    }
  });
  return ok && common == expected;
}

void write_position_vertex(const Mesh& in, const std::vector<uint32_t>& origin, Mesh* out) {
  if (in.position_vertex.empty()) return;
  const size_t n = origin.size();
  std::vector<uint32_t> first(in.vertex_count(), UINT32_MAX);
  out->position_vertex.resize(n);
  bool split = false;
  for (size_t o = 0; o < n; ++o) {
    uint32_t& f = first[in.position_vertex[origin[o]]];
    if (f == UINT32_MAX) f = uint32_t(o);
    out->position_vertex[o] = f;
    split |= f != o;
  }
  if (!split) out->position_vertex.clear();
}

}  // namespace detail
}  // namespace meshsal
