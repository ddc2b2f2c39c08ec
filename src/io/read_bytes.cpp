// meshsal: whole-file reads with transparent gunzip (zlib inflate on the in-memory bytes).
#include "io/read_bytes.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <string>

#include "meshsal/meshsal.h"

namespace meshsal {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& problem) {
  throw Error(path + ": " + problem);
}

// Grows `b` to at least `want` bytes of capacity (realloc: in place where it can).
void grow(const std::string& path, Bytes& b, size_t& capacity, size_t want) {
  if (want <= capacity) return;
  void* p = std::realloc(b.data.get(), want);
  if (!p) fail(path, "out of memory (" + std::to_string(want >> 20) + " MB)");
  b.data.release();
  b.data.reset(static_cast<char*>(p));
  capacity = want;
}

Bytes read_raw(const std::string& path) {
  int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail(path, std::string("cannot open: ") + std::strerror(errno));
  struct stat st;
  if (::fstat(fd, &st) != 0) {
    int e = errno;
    ::close(fd);
    fail(path, std::string("cannot stat: ") + std::strerror(e));
  }
  if (S_ISDIR(st.st_mode)) {
    ::close(fd);
    fail(path, "is a folder, not a mesh file");
  }
  // Regular files: one buffer of the right size (+1 so the final read sees EOF without
  // growing); others (pipes) grow as they come.
  Bytes b;
  size_t capacity = 0;
  try {
    grow(path, b, capacity, S_ISREG(st.st_mode) ? static_cast<size_t>(st.st_size) + 1 : size_t(1) << 16);
    for (;;) {
      if (b.size == capacity) grow(path, b, capacity, capacity * 2);
      ssize_t n = ::read(fd, b.data.get() + b.size, capacity - b.size);
      if (n < 0) {
        if (errno == EINTR) continue;
        fail(path, std::string("cannot read: ") + std::strerror(errno));
      }
      if (n == 0) break;
      b.size += static_cast<size_t>(n);
    }
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
  return b;
}

bool ends_with_gz(const std::string& path) {
  if (path.size() < 3) return false;
  std::string ext = path.substr(path.size() - 3);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".gz";
}

bool has_gzip_magic(std::string_view data, size_t at = 0) {
  return data.size() >= at + 2 && static_cast<unsigned char>(data[at]) == 0x1f &&
         static_cast<unsigned char>(data[at + 1]) == 0x8b;
}

Bytes gunzip(const std::string& path, std::string_view in) {
  Bytes out;
  size_t capacity = 0;
  // The gzip trailer holds the uncompressed size mod 2^32: a good first guess.
  size_t guess = in.size() * 4;
  if (in.size() >= 4) {
    const unsigned char* t = reinterpret_cast<const unsigned char*>(in.data() + in.size() - 4);
    size_t hint = t[0] | (t[1] << 8) | (t[2] << 16) | (size_t(t[3]) << 24);
    if (hint < in.size() * size_t(1100)) guess = hint + 1;  // deflate can't beat ~1032:1
  }
  grow(path, out, capacity, std::max<size_t>(guess, 1 << 16));
  z_stream zs;
  std::memset(&zs, 0, sizeof zs);
  if (inflateInit2(&zs, 15 + 16) != Z_OK) fail(path, "cannot start gzip decompression");
  struct End {
    z_stream* z;
    ~End() { inflateEnd(z); }
  } end_guard{&zs};
  size_t used = 0;  // input bytes consumed
  for (;;) {
    // One gzip member per pass; files may hold several concatenated members.
    int rc = Z_OK;
    while (rc != Z_STREAM_END) {
      if (capacity - out.size < (1 << 16)) grow(path, out, capacity, capacity * 2);
      // zlib counts in 32 bits: feed at most 1 GiB at a time.
      zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data() + used));
      zs.avail_in = static_cast<uInt>(std::min<size_t>(in.size() - used, 1u << 30));
      zs.next_out = reinterpret_cast<Bytef*>(out.data.get() + out.size);
      zs.avail_out = static_cast<uInt>(std::min<size_t>(capacity - out.size, 1u << 30));
      const uInt in_before = zs.avail_in, out_before = zs.avail_out;
      rc = inflate(&zs, Z_NO_FLUSH);
      used += in_before - zs.avail_in;
      out.size += out_before - zs.avail_out;
      if (rc == Z_DATA_ERROR || rc == Z_NEED_DICT || rc == Z_MEM_ERROR || rc == Z_STREAM_ERROR)
        fail(path, std::string("corrupt gzip data (") + (zs.msg ? zs.msg : "bad data") + ")");
      if (rc != Z_STREAM_END && used == in.size() && zs.avail_in == in_before && zs.avail_out == out_before)
        fail(path, "truncated gzip data (the file ends inside the compressed stream)");
    }
    if (!has_gzip_magic(in, used)) break;
    inflateReset(&zs);
  }
  // Anything after the last member other than zero padding is garbage.
  for (size_t i = used; i < in.size(); ++i)
    if (in[i] != 0) fail(path, "unexpected data after the gzip stream");
  return out;
}

}  // namespace

Bytes read_bytes(const std::string& path) {
  Bytes data = read_raw(path);
  if (has_gzip_magic(data.view())) return gunzip(path, data.view());
  if (ends_with_gz(path)) fail(path, "not a gzip file (the name ends in .gz but the data is not gzip)");
  return data;
}

}  // namespace meshsal
