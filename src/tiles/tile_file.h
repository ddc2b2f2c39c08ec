// meshsal: a tile's state to and from its scratch file in TileBytes' layout (a value, or a
// count and then the values), streamed: the file is never held whole in memory beside the
// vectors it fills, which would double a tile's peak (the tile's raw maps are the largest
// thing a tile keeps between phases).
#pragma once
#include <sys/stat.h>

#include <cstdint>
#include <string>
#include <vector>

#include "meshsal/meshsal.h"
#include "tiles/scratch_files.h"

namespace meshsal {

class TileFileWriter {
 public:
  explicit TileFileWriter(const std::string& path) : out_(path) {}
  template <class T>
  void put(const T& x) { out_.write(&x, sizeof(T)); }
  template <class T>
  void put(const std::vector<T>& v) {
    put(uint64_t(v.size()));
    out_.write_vector(v);
  }
  // The values alone (their count is the caller's: a header before them).
  template <class T>
  void put_raw(const T* v, size_t n) { out_.write(v, n * sizeof(T)); }
  void close() { out_.close(); }

 private:
  ScratchWriter out_;
};

class TileFileReader {
 public:
  explicit TileFileReader(const std::string& path) : in_(path) {
    struct stat st;
    left_ = ::stat(path.c_str(), &st) == 0 ? uint64_t(st.st_size) : 0;
  }
  template <class T>
  T get() {
    T x;
    take(&x, sizeof(T));
    return x;
  }
  // A count beyond what the file still holds is refused before anything is allocated.
  template <class T>
  std::vector<T> get_vector() {
    const uint64_t n = get<uint64_t>();
    if (n > left_ / sizeof(T)) throw Error("tiled saliency: a short tile file");
    std::vector<T> v(n);
    take(v.data(), n * sizeof(T));
    return v;
  }
  // n values into `to` (their count from a header, checked against left()).
  template <class T>
  void get_raw(T* to, size_t n) { take(to, n * sizeof(T)); }
  // Bytes not read yet.
  uint64_t left() const { return left_; }
  void skip(uint64_t bytes) {
    if (bytes > left_) throw Error("tiled saliency: a short tile file");
    at_ += bytes;
    left_ -= bytes;
    in_.seek(at_);
  }

 private:
  void take(void* to, size_t bytes) {
    if (bytes > left_) throw Error("tiled saliency: a short tile file");
    in_.read_exact(to, bytes);
    at_ += bytes;
    left_ -= bytes;
  }
  ScratchReader in_;
  uint64_t left_ = 0, at_ = 0;
};

}  // namespace meshsal
