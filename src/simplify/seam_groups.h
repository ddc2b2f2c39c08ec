// meshsal (internal): seam twins for the simplifier. Mesh::position_vertex names vertices
// that share one position (a UV or normal seam splits one surface point into twins); the
// simplifier keeps twins in place, collapses a seam edge on both sides at once, and checks
// the link condition on the welded surface (twins joined) as well as on the split one.
#pragma once
#include <cstdint>
#include <vector>

#include "meshsal/meshsal.h"
#include "simplify/triangle_fans.h"

namespace meshsal {
namespace detail {

struct SeamGroups {
  static constexpr uint32_t NONE = UINT32_MAX;
  bool has_twins = false;  // some position group has two members or more
  // twin_next[v]: the next vertex of v's position group (a cycle), NONE outside groups.
  std::vector<uint32_t> twin_next;
  // group_of[v] names v's position group (a member's id; v itself outside groups).
  std::vector<uint32_t> group_of;
  // A twin whose group has two members (one each side of the seam) has a partner: a seam
  // edge between two such vertices collapses on both sides at once, along the seam. Empty
  // when borders are locked (then nothing on a seam moves).
  std::vector<uint32_t> partner;
  // 1 for a twin and (at least) every vertex next to one: only their collapses need the
  // welded link condition (elsewhere the split one is the same). Kept by note_collapse().
  std::vector<uint8_t> near_seam;
  // Scratch of welded_link_ok: per group, stamps (nothing is ever cleared).
  std::vector<uint32_t> weld_mark;
  uint32_t weld_stamp = 0;

  // From the input's position_vertex (input ids; checked here), `inv` (input id ->
  // internal id) and the triangles (internal ids). Marks every twin in `locked`.
  void build(const std::vector<uint32_t>& position_vertex, const std::vector<uint32_t>& inv,
             const std::vector<uint32_t>& corners, bool lock_border, std::vector<uint8_t>* locked);

  bool pair(uint32_t v) const { return !partner.empty() && partner[v] != NONE; }
  bool seam_edge(uint32_t a, uint32_t b) const { return pair(a) && pair(b); }

  // The link condition on the welded surface (seams closed): merging b's position group
  // into a's, their only common welded neighbours are the `expected` opposites (k, or one
  // each side along a seam), and no other twin of one end neighbours the other end.
  bool welded_link_ok(const TriangleFans& fans, uint32_t a, uint32_t b, size_t expected,
                      bool along_seam);

  // Before b collapses into a (fans not merged yet): a gains b's neighbours; if a is a
  // twin, they gain a twin neighbour.
  void note_collapse(const TriangleFans& fans, uint32_t a, uint32_t b) {
    near_seam[a] |= near_seam[b];
    if (twin_next[a] != NONE)
      for (uint32_t t : fans.fan(b))
        if (fans.live[t])
          for (int k = 0; k < 3; ++k) near_seam[fans.corners[3 * size_t(t) + k]] = 1;
  }
};

// The output's position_vertex: each survivor points at its group's first survivor
// (`origin`: output vertex -> input vertex); left empty when no group kept two members.
void write_position_vertex(const Mesh& in, const std::vector<uint32_t>& origin, Mesh* out);

}  // namespace detail
}  // namespace meshsal
