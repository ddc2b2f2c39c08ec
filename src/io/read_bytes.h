// meshsal: read a whole file into memory, gunzipping it when it is gzip-compressed.
#pragma once
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

namespace meshsal {

// A file's bytes in a malloc'd block: unlike std::string it is not zero-filled before the
// read (a real cost for 80 MB meshes), and realloc can grow it in place while gunzipping.
struct Bytes {
  std::unique_ptr<char, void (*)(void*)> data{nullptr, std::free};
  size_t size = 0;
  std::string_view view() const { return std::string_view(data.get(), size); }
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
