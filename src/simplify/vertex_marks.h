// meshsal (internal): per-vertex marks that never need clearing. Each use takes fresh stamp
// values and marks vertices with them; a mark from an earlier use reads as unmarked.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

namespace meshsal {
namespace detail {

struct VertexMarks {
  std::vector<uint32_t> mark;  // per vertex: the stamp it was last marked with
  uint32_t stamp = 0;          // the last stamp value handed out

  void reset(size_t vertex_count) {
    mark.assign(vertex_count, 0);
    stamp = 0;
  }
  // n fresh stamp values; returns the last. Starts over (all marks cleared) before the
  // counter would wrap.
  uint32_t new_stamps(uint32_t n) {
    if (stamp > UINT32_MAX - n) {
      std::fill(mark.begin(), mark.end(), 0);
      stamp = 0;
    }
    return stamp += n;
  }
};

}  // namespace detail
}  // namespace meshsal
