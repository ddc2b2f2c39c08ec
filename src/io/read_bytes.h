// meshsal: read a whole file into memory, gunzipping it when it is gzip-compressed.
#pragma once
#include <cstdlib>
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

// Returns the file's bytes. A file whose name ends in .gz (any case) or that starts with
// the gzip magic bytes is decompressed (concatenated gzip members included).
// Throws Error "PATH: problem" when the file is missing, unreadable, a folder, or
// holds truncated / corrupt gzip data.
Bytes read_bytes(const std::string& path);

}  // namespace meshsal
