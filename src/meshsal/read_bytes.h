// meshsal: read a whole file into memory, gunzipping it when it is gzip-compressed.
#pragma once
#include <string>

namespace meshsal {

// Returns the file's bytes. A file whose name ends in .gz (any case) or that starts with
// the gzip magic bytes is decompressed (concatenated gzip members included).
// Throws Error "PATH: problem" when the file is missing, unreadable, a folder, or
// holds truncated / corrupt gzip data.
std::string read_bytes(const std::string& path);

}  // namespace meshsal
