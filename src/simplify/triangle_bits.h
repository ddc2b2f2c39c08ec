// meshsal (internal): branch-free helpers on triangle corners and 3-vectors, shared by the
// simplifier's parts. Branch-free because in their hot loops the outcome is a coin toss
// (GCC turns the obvious ternaries into jumps there).
#pragma once
#include <cstdint>

#include "core/vec3.h"

namespace meshsal {
namespace detail {

inline uint32_t select_u32(bool c, uint32_t x, uint32_t y) {  // c ? x : y
  const uint32_t m = 0u - uint32_t(c);
  return (x & m) | (y & ~m);
}
// Triangle v (three corners) and one of its corners c: is c a corner of it, and which are
// the other two (in an order that is not the triangle's orientation).
inline bool has_corner(const uint32_t* v, uint32_t c) {
  return (v[0] == c) | (v[1] == c) | (v[2] == c);
}
inline void other_corners(const uint32_t* v, uint32_t c, uint32_t* x, uint32_t* y) {
  *x = select_u32(v[0] == c, v[1], v[0]);
  *y = select_u32(v[2] == c, v[1], v[2]);
}


}  // namespace detail
}  // namespace meshsal
