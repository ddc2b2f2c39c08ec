// meshsal: read a whole file into memory, gunzipping it when it is gzip-compressed.
#pragma once
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

namespace meshsal {

// A file's bytes in an anonymous memory mapping of their own: not zero-filled before the
// read as a std::string would be (a real cost for 80 MB meshes), grown in place or moved
// without a copy by mremap while gunzipping, and given back to the system when dropped.
// From the heap, a large block stayed resident after the load where a program keeps freed
// memory for reuse (keep_freed_memory_for_reuse, as the meshsal command does): a mesh file
// as large as the mesh held in memory besides it all run long.
class Bytes {
 public:
  Bytes() = default;
  ~Bytes() { release(); }
  Bytes(Bytes&& o) noexcept : size(o.size), data_(o.data_), capacity_(o.capacity_) {
    o.data_ = nullptr, o.size = o.capacity_ = 0;
  }
  Bytes& operator=(Bytes&& o) noexcept;
  Bytes(const Bytes&) = delete;
  Bytes& operator=(const Bytes&) = delete;

  char* data() const { return data_; }
  size_t capacity() const { return capacity_; }
  std::string_view view() const { return std::string_view(data_, size); }
  // Room for at least `bytes` (the first `size` kept); false when the system has no memory.
  bool reserve(size_t bytes);
  void release();  // the mapping given back: empty again

  size_t size = 0;  // bytes held

 private:
  char* data_ = nullptr;
  size_t capacity_ = 0;
};

// Reads the file's raw bytes. Regular files are read whole; a FIFO (named pipe) is read
// up to `max_pipe_bytes`; anything else (a character or block device such as /dev/zero,
// a socket, a folder; symlinks are followed) is refused before reading.
// With `regular_only`, FIFOs are refused too (opened without waiting for a writer).
// Throws Error "PATH: problem".
Bytes read_file(const std::string& path, uint64_t max_pipe_bytes, bool regular_only = false);

bool has_gzip_magic(std::string_view data);

// Decides how many bytes the inflated data may hold from its start: called once with the
// first kGzipHeadBytes inflated bytes (all of them when there are fewer). It may throw
// Error to refuse the data before the rest is inflated.
using InflateLimit = std::function<uint64_t(std::string_view head)>;
constexpr size_t kGzipHeadBytes = size_t(1) << 20;

// Inflates gzip data (concatenated members included). Throws Error "NAME: problem" for
// truncated or corrupt data, data after the stream, or more than `limit` allows.
Bytes gunzip(std::string_view in, const std::string& name, const InflateLimit& limit);

}  // namespace meshsal
