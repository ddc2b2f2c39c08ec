// meshsal (internal): the simplifier's triangles and, per vertex, the fan of triangles
// around it. A collapse merges the fan of the vertex that goes into the fan of the one
// that stays; dead triangles linger in fans until compact() drops them.
#pragma once
#include <cstdint>
#include <vector>

#include "simplify/edge_queue.h"  // keep_if

namespace meshsal {
namespace detail {

class TriangleFans {
 public:
  // Where v's fan lies in the pool: `count` triangles from `start`, room for `cap`. A fan
  // that outgrows its room moves to the end of the pool. One record: one miss per vertex.
  struct alignas(16) FanPlace {
    uint32_t start, count, cap;
  };
  struct Range {
    const uint32_t* b;
    const uint32_t* e;
    const uint32_t* begin() const { return b; }
    const uint32_t* end() const { return e; }
  };

  std::vector<uint32_t> corners;  // 3 per triangle; a collapse rewrites them in place
  std::vector<uint8_t> live;      // per triangle: 0 once a collapse removed it
  std::vector<uint32_t> pool;     // every vertex's fan, one after another
  std::vector<FanPlace> place;    // per vertex

  // The fans of `vertex_count` vertices over `corners` (filled in before); every triangle
  // live.
  void build(size_t vertex_count);

  size_t triangle_count() const { return live.size(); }
  const uint32_t* corners_of(uint32_t t) const { return &corners[3 * size_t(t)]; }
  uint32_t* fan_begin(uint32_t v) { return pool.data() + place[v].start; }
  const uint32_t* fan_begin(uint32_t v) const { return pool.data() + place[v].start; }
  uint32_t fan_size(uint32_t v) const { return place[v].count; }
  // v's fan, dead triangles included.
  Range fan(uint32_t v) const { return {fan_begin(v), fan_begin(v) + place[v].count}; }

  // Drops the dead triangles from v's fan.
  void compact(uint32_t v) {
    const auto is_live = [&](uint32_t t) { return live[t] != 0; };
    place[v].count = uint32_t(keep_if(fan_begin(v), place[v].count, is_live));
  }

  // Collapse of b into a: the triangles on edge (a, b) die, b's others take a for b and
  // join a's fan, b's fan empties. vertex_live is read when the pool is laid out again
  // (see repack). Returns how many triangles died.
  size_t merge(uint32_t a, uint32_t b, const std::vector<uint8_t>& vertex_live);

  // Lays all fans out again in vertex order, live triangles only (and none of a dead
  // vertex), each with room for half as many more: instead of growing the pool (a copy of
  // all of it, and page faults), and it puts the fans back in vertex order.
  void repack(const std::vector<uint8_t>& vertex_live);
};

}  // namespace detail
}  // namespace meshsal
