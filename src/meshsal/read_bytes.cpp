// meshsal: whole-file reads with transparent gunzip (zlib inflate on the in-memory bytes).
#include "meshsal/read_bytes.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <string>

#include "meshsal/error.h"

namespace meshsal {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& problem) {
  throw Error(path + ": " + problem);
}

std::string read_raw(const std::string& path) {
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
  // Regular files: read straight into a buffer of the right size; others (pipes) grow.
  std::string data;
  size_t size = 0;
  if (S_ISREG(st.st_mode)) data.resize(static_cast<size_t>(st.st_size));
  for (;;) {
    if (size == data.size()) data.resize(std::max<size_t>(size * 2, 1 << 16));
    ssize_t n = ::read(fd, &data[size], data.size() - size);
    if (n < 0) {
      if (errno == EINTR) continue;
      int e = errno;
      ::close(fd);
      fail(path, std::string("cannot read: ") + std::strerror(e));
    }
    if (n == 0) break;
    size += static_cast<size_t>(n);
  }
  data.resize(size);
  ::close(fd);
  return data;
}

bool ends_with_gz(const std::string& path) {
  if (path.size() < 3) return false;
  std::string ext = path.substr(path.size() - 3);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".gz";
}

bool has_gzip_magic(const std::string& data, size_t at = 0) {
  return data.size() >= at + 2 && static_cast<unsigned char>(data[at]) == 0x1f &&
         static_cast<unsigned char>(data[at + 1]) == 0x8b;
}

std::string gunzip(const std::string& path, const std::string& in) {
  std::string out;
  // The gzip trailer holds the uncompressed size mod 2^32: a good first guess.
  if (in.size() >= 4) {
    const unsigned char* t = reinterpret_cast<const unsigned char*>(in.data() + in.size() - 4);
    size_t hint = t[0] | (t[1] << 8) | (t[2] << 16) | (size_t(t[3]) << 24);
    if (hint < in.size() * size_t(1100)) out.reserve(hint);  // deflate can't beat ~1032:1
  }
  z_stream zs;
  std::memset(&zs, 0, sizeof zs);
  if (inflateInit2(&zs, 15 + 16) != Z_OK) fail(path, "cannot start gzip decompression");
  size_t consumed = 0;
  for (;;) {
    // One gzip member at a time; files may hold several concatenated members.
    zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data() + consumed));
    zs.avail_in = static_cast<uInt>(std::min<size_t>(in.size() - consumed, 1u << 30));
    int rc = Z_OK;
    while (rc != Z_STREAM_END) {
      if (out.capacity() - out.size() < (1 << 16)) out.reserve(std::max<size_t>(out.size() * 2, 1 << 20));
      size_t before = out.size();
      size_t room = out.capacity() - before;
      out.resize(out.capacity());
      zs.next_out = reinterpret_cast<Bytef*>(&out[before]);
      zs.avail_out = static_cast<uInt>(std::min<size_t>(room, 1u << 30));
      size_t avail_before = zs.avail_out;
      size_t in_before = zs.avail_in;
      rc = inflate(&zs, Z_NO_FLUSH);
      out.resize(before + (avail_before - zs.avail_out));
      if (rc == Z_DATA_ERROR || rc == Z_NEED_DICT || rc == Z_MEM_ERROR || rc == Z_STREAM_ERROR) {
        std::string msg = zs.msg ? zs.msg : "bad data";
        inflateEnd(&zs);
        fail(path, "corrupt gzip data (" + msg + ")");
      }
      bool progress = zs.avail_in != in_before || zs.avail_out != avail_before;
      if (rc != Z_STREAM_END && zs.avail_in == 0 && !progress) {
        // Refill if the 1 GiB window was used up, else the stream ended early.
        size_t used = static_cast<size_t>(reinterpret_cast<const char*>(zs.next_in) - in.data());
        if (used < in.size()) {
          zs.avail_in = static_cast<uInt>(std::min<size_t>(in.size() - used, 1u << 30));
          continue;
        }
        inflateEnd(&zs);
        fail(path, "truncated gzip data (file ends inside the compressed stream)");
      }
    }
    consumed = static_cast<size_t>(reinterpret_cast<const char*>(zs.next_in) - in.data());
    if (!has_gzip_magic(in, consumed)) break;
    inflateReset(&zs);
  }
  inflateEnd(&zs);
  // Anything after the last member other than zero padding is garbage.
  for (size_t i = consumed; i < in.size(); ++i)
    if (in[i] != 0) fail(path, "unexpected data after the gzip stream");
  return out;
}

}  // namespace

std::string read_bytes(const std::string& path) {
  std::string data = read_raw(path);
  if (has_gzip_magic(data)) return gunzip(path, data);
  if (ends_with_gz(path)) fail(path, "not a gzip file (the name ends in .gz but the data is not gzip)");
  return data;
}

}  // namespace meshsal
