// meshsal (internal): triangle fans, see triangle_fans.h.
#include "simplify/triangle_fans.h"

#include <algorithm>

#include "simplify/triangle_bits.h"

namespace meshsal {
namespace detail {

void TriangleFans::build(size_t vertex_count) {
  const size_t nt = corners.size() / 3;
  live.assign(nt, 1);
  std::vector<uint32_t> deg(vertex_count, 0);
  for (uint32_t v : corners) ++deg[v];
  place.assign(vertex_count, FanPlace{0, 0, 0});
  size_t off = 0;
  for (size_t v = 0; v < vertex_count; ++v) {
    place[v].start = uint32_t(off);
    place[v].cap = deg[v];
    off += deg[v];
  }
  // Room to grow: fans that outgrow their place move to the end, until a repack.
  pool.reserve(2 * off + 64);
  pool.resize(off);
  for (size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = corners[3 * t + k];
      pool[place[v].start + place[v].count++] = uint32_t(t);
    }
}

size_t TriangleFans::merge(uint32_t a, uint32_t b, const std::vector<uint8_t>& vertex_live) {
  compact(a);
  const uint32_t need = place[a].count + place[b].count;
  if (need > place[a].cap) {  // move a's fan to the end of the pool, with room to grow
    const uint32_t cap = need + need / 2;
    if (pool.size() + cap > pool.capacity()) repack(vertex_live);
    const size_t start = pool.size();
    pool.resize(start + cap);
    std::copy(pool.begin() + place[a].start, pool.begin() + place[a].start + place[a].count,
              pool.begin() + start);
    place[a].start = uint32_t(start);
    place[a].cap = cap;
  }
  uint32_t* fa = fan_begin(a);
  uint32_t na = place[a].count;
  const uint32_t* fb = fan_begin(b);
  size_t died = 0;
  // Without branches: which of b's triangles is on the edge is a coin toss.
  for (uint32_t i = 0, n = place[b].count; i < n; ++i) {
    const uint32_t t = fb[i];
    uint32_t* v = &corners[3 * size_t(t)];
    const bool was_live = live[t];
    const bool on_edge = has_corner(v, a);
    const bool moves = was_live & !on_edge;
    live[t] = moves;
    died += was_live & on_edge;
    for (int k = 0; k < 3; ++k) v[k] = select_u32(moves & (v[k] == b), a, v[k]);
    fa[na] = t;
    na += moves;
  }
  place[a].count = na;
  compact(a);
  place[b].count = 0;
  return died;
}

void TriangleFans::repack(const std::vector<uint8_t>& vertex_live) {
  std::vector<uint32_t> fresh;
  fresh.reserve(pool.capacity());
  for (size_t v = 0; v < place.size(); ++v) {
    const uint32_t start = uint32_t(fresh.size());
    if (vertex_live[v])
      for (uint32_t t : fan(uint32_t(v)))
        if (live[t]) fresh.push_back(t);
    place[v].start = start;
    place[v].count = uint32_t(fresh.size()) - start;
    place[v].cap = place[v].count + place[v].count / 2;
    fresh.resize(start + place[v].cap);
  }
  pool.swap(fresh);
}

}  // namespace detail
}  // namespace meshsal
