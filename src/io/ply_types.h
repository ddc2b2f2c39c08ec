// meshsal: PLY's scalar types, shared by the loader (load_ply.cpp) and the out-of-core
// stream (ply_stream.cpp): their sizes, their names in a header, a binary value as double;
// and the binary records the writers put (write_ply.cpp, the out-of-core outputs).
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string_view>
#include <utility>

namespace meshsal {

enum class PlyType : uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

inline size_t type_size(PlyType t) {
  switch (t) {
    case PlyType::Int8: case PlyType::UInt8: return 1;
    case PlyType::Int16: case PlyType::UInt16: return 2;
    case PlyType::Int32: case PlyType::UInt32: case PlyType::Float32: return 4;
    case PlyType::Float64: return 8;
  }
  return 0;
}

// "uchar", "float32", ... into t; false for a name PLY does not have.
inline bool type_from_name(std::string_view s, PlyType& t) {
  static const struct { const char* name; PlyType type; } names[] = {
      {"char", PlyType::Int8},     {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
      {"uint8", PlyType::UInt8},   {"short", PlyType::Int16},     {"int16", PlyType::Int16},
      {"ushort", PlyType::UInt16}, {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
      {"int32", PlyType::Int32},   {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
      {"float", PlyType::Float32}, {"float32", PlyType::Float32}, {"double", PlyType::Float64},
      {"float64", PlyType::Float64}};
  for (const auto& n : names)
    if (s == n.name) {
      t = n.type;
      return true;
    }
  return false;
}

// One binary value at p as double (exact for every PLY type but 64-bit ints, which PLY lacks);
// Swap: the file's byte order is not the host's.
template <bool Swap>
inline double read_value(const char* p, PlyType t) {
  unsigned char b[8];
  size_t n = type_size(t);
  std::memcpy(b, p, n);
  if (Swap)
    for (size_t i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
  switch (t) {
    case PlyType::Int8: { int8_t v; std::memcpy(&v, b, 1); return v; }
    case PlyType::UInt8: return b[0];
    case PlyType::Int16: { int16_t v; std::memcpy(&v, b, 2); return v; }
    case PlyType::UInt16: { uint16_t v; std::memcpy(&v, b, 2); return v; }
    case PlyType::Int32: { int32_t v; std::memcpy(&v, b, 4); return v; }
    case PlyType::UInt32: { uint32_t v; std::memcpy(&v, b, 4); return v; }
    case PlyType::Float32: { float v; std::memcpy(&v, b, 4); return v; }
    case PlyType::Float64: { double v; std::memcpy(&v, b, 8); return v; }
  }
  return 0;
}

inline double read_value(const void* p, PlyType t, bool swap) {
  const char* c = static_cast<const char*>(p);
  return swap ? read_value<true>(c, t) : read_value<false>(c, t);
}

// The little-endian bytes of a 4- or 8-byte value written at `out`, which steps past them.
template <typename T>
inline void put_le(char*& out, T value) {
  static_assert(sizeof(T) == 4 || sizeof(T) == 8, "4- or 8-byte values only");
  std::memcpy(out, &value, sizeof(T));
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
  std::reverse(out, out + sizeof(T));
#endif
  out += sizeof(T);
}

// A triangle's record in a binary PLY of "property list uchar int vertex_indices": the
// corner count (1 byte) and the three indices as int32.
constexpr size_t kPlyTriangleBytes = 13;
inline void put_ply_triangle(char*& out, const uint32_t corner[3]) {
  *out++ = 3;
  for (int k = 0; k < 3; ++k) put_le(out, static_cast<int32_t>(corner[k]));
}

}  // namespace meshsal
