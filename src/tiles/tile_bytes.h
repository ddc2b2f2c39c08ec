// meshsal: plain byte streams of the tiled saliency run: what processes exchange
// (TileExchange) and what the out-of-core path keeps on disk between phases.
#pragma once
#include <cstdint>
#include <cstring>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {

struct TileBytes {
  std::vector<uint8_t> data;
  template <class T>
  void put(const T& x) {
    const auto* b = reinterpret_cast<const uint8_t*>(&x);
    data.insert(data.end(), b, b + sizeof(T));
  }
  template <class T>
  void put(const std::vector<T>& v) {
    put(uint64_t(v.size()));
    const auto* b = reinterpret_cast<const uint8_t*>(v.data());
    data.insert(data.end(), b, b + v.size() * sizeof(T));
  }
};

struct TileBytesReader {
  const std::vector<uint8_t>& data;
  size_t at = 0;
  bool done() const { return at >= data.size(); }
  template <class T>
  T get() {
    if (at + sizeof(T) > data.size()) throw Error("tiled saliency: a short message or tile file");
    T x;
    std::memcpy(&x, &data[at], sizeof(T));
    at += sizeof(T);
    return x;
  }
  template <class T>
  std::vector<T> get_vector() {
    const uint64_t n = get<uint64_t>();
    if (n > (data.size() - at) / sizeof(T)) throw Error("tiled saliency: a short message or tile file");
    std::vector<T> v(n);
    if (n) std::memcpy(v.data(), &data[at], n * sizeof(T));
    at += n * sizeof(T);
    return v;
  }
};

}  // namespace meshsal
