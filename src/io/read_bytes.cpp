// meshsal: whole-file reads (regular files and pipes only) and bounded gunzip in memory.
#include "io/read_bytes.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <string>

#include "core/parallel.h"
#include "meshsal/meshsal.h"

namespace meshsal {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& problem) {
  throw Error(path + ": " + problem);
}

// Grows `b` to at least `want` bytes of capacity (mremap: in place where it can).
void grow(const std::string& path, Bytes& b, size_t& capacity, size_t want) {
  if (want <= capacity) return;
  if (!b.reserve(want)) fail(path, "out of memory (" + std::to_string(want >> 20) + " MB)");
  capacity = b.capacity();
}

// A large regular file's first `size` bytes read on every core, each thread a range of its
// own by pread (the copy out of the page cache and the faults on the fresh buffer were a
// single core's 0.2 s for a 330 MB mesh). Returns the bytes read: `size`, or 0 when a range
// came back short (the file shrank), and the caller's sequential loop then reads it whole.
// Either way the descriptor's offset is left where the caller's loop goes on.
size_t read_parallel(const std::string& path, int fd, char* data, size_t size) {
  constexpr size_t kRange = size_t(32) << 20;
  if (size < 2 * kRange || resolve_threads(0) == 1) return 0;
  std::atomic<bool> short_read{false};
  std::atomic<int> error{0};
  parallel_for((size + kRange - 1) / kRange, 0, 1, [&](size_t r0, size_t r1) {
    for (size_t r = r0; r < r1 && !short_read && !error; ++r) {
      size_t at = r * kRange;
      const size_t end = std::min(size, at + kRange);
      while (at < end) {
        const ssize_t n = ::pread(fd, data + at, end - at, off_t(at));
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) error = errno;
        if (n <= 0) {
          short_read = n == 0;
          break;
        }
        at += size_t(n);
      }
    }
  });
  if (error) fail(path, std::string("cannot read: ") + std::strerror(error));
  if (short_read) return 0;
  if (::lseek(fd, off_t(size), SEEK_SET) < 0) fail(path, std::string("cannot read: ") + std::strerror(errno));
  return size;
}

const char* file_kind(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISFIFO(mode)) return "a named pipe (FIFO)";
  return "not a regular file";
}

std::string mib(uint64_t bytes) {
  return bytes % (1 << 20) == 0 ? std::to_string(bytes >> 20) + " MiB" : std::to_string(bytes) + " bytes";
}

}  // namespace

Bytes& Bytes::operator=(Bytes&& o) noexcept {
  if (this != &o) {
    release();
    data_ = o.data_, size = o.size, capacity_ = o.capacity_;
    o.data_ = nullptr, o.size = o.capacity_ = 0;
  }
  return *this;
}

bool Bytes::reserve(size_t bytes) {
  if (bytes <= capacity_) return true;
  const size_t page = size_t(::sysconf(_SC_PAGESIZE));
  const size_t rounded = (bytes + page - 1) / page * page;
  void* p = data_ ? ::mremap(data_, capacity_, rounded, MREMAP_MAYMOVE)
                  : ::mmap(nullptr, rounded, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) return false;
  data_ = static_cast<char*>(p);
  capacity_ = rounded;
  return true;
}

void Bytes::release() {
  if (data_) ::munmap(data_, capacity_);
  data_ = nullptr, size = capacity_ = 0;
}

Bytes read_file(const std::string& path, uint64_t max_pipe_bytes, bool regular_only) {
  // A device (/dev/zero, /dev/urandom, a terminal) never ends or may block: look before
  // opening, then check again on what was opened. stat follows symlinks.
  struct stat st;
  auto refuse_kind = [&] {
    if (!S_ISREG(st.st_mode) && (regular_only || !S_ISFIFO(st.st_mode)))
      fail(path, std::string("is ") + file_kind(st.st_mode) + ", not a mesh file");
  };
  if (::stat(path.c_str(), &st) == 0) refuse_kind();
  // A FIFO waits for a writer, unless only regular files are wanted: then O_NONBLOCK
  // opens it at once and fstat below refuses it (a regular file ignores the flag).
  int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | (regular_only ? O_NONBLOCK : 0));
  if (fd < 0) fail(path, std::string("cannot open: ") + std::strerror(errno));
  if (::fstat(fd, &st) != 0) {
    int e = errno;
    ::close(fd);
    fail(path, std::string("cannot stat: ") + std::strerror(e));
  }
  try {
    refuse_kind();
  } catch (...) {
    ::close(fd);
    throw;
  }
  const bool regular = S_ISREG(st.st_mode);
  // Regular files: one buffer of the right size (+1 so the final read sees EOF without
  // growing); they may still grow while being read (or report size 0, as /proc files do),
  // so what is read beyond the size is capped as a pipe is.
  const uint64_t cap = regular ? static_cast<uint64_t>(st.st_size) + max_pipe_bytes : max_pipe_bytes;
  Bytes b;
  size_t capacity = 0;
  try {
    grow(path, b, capacity, regular ? static_cast<size_t>(st.st_size) + 1 : size_t(1) << 16);
    if (regular) b.size = read_parallel(path, fd, b.data(), static_cast<size_t>(st.st_size));
    for (;;) {
      if (b.size == capacity) grow(path, b, capacity, std::min<uint64_t>(capacity * 2, cap + 1));
      ssize_t n = ::read(fd, b.data() + b.size, capacity - b.size);
      if (n < 0) {
        if (errno == EINTR) continue;
        fail(path, std::string("cannot read: ") + std::strerror(errno));
      }
      if (n == 0) break;
      b.size += static_cast<size_t>(n);
      if (b.size > cap)
        fail(path, "more than " + mib(cap) + " came from " + (regular ? "a growing file" : "a pipe") +
                       " (the limit for input of unknown size; MESHSAL_MAX_INPUT raises it)");
    }
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
  return b;
}

namespace {

[[noreturn]] void over_limit(const std::string& path, uint64_t limit) {
  fail(path, "gzip data inflates to more than " + mib(limit) +
                 ", the limit for this file (a gzip bomb?); MESHSAL_MAX_INPUT=BYTES raises it");
}

bool gzip_magic_at(std::string_view data, size_t at) {
  return data.size() >= at + 2 && static_cast<unsigned char>(data[at]) == 0x1f &&
         static_cast<unsigned char>(data[at + 1]) == 0x8b;
}

}  // namespace

bool has_gzip_magic(std::string_view data) { return gzip_magic_at(data, 0); }

Bytes gunzip(std::string_view in, const std::string& path, const InflateLimit& limit) {
  Bytes out;
  size_t capacity = 0;
  // The gzip trailer holds the uncompressed size mod 2^32: a good first guess.
  size_t guess = in.size() * 4;
  if (in.size() >= 4) {
    const unsigned char* t = reinterpret_cast<const unsigned char*>(in.data() + in.size() - 4);
    size_t hint = t[0] | (t[1] << 8) | (t[2] << 16) | (size_t(t[3]) << 24);
    if (hint < in.size() * size_t(1100)) guess = hint + 1;  // deflate can't beat ~1032:1
  }
  // Until the head is seen, inflate no more than the head; then as much as `limit` says.
  // A bomb (a few MB inflating to GB) is refused after inflating what its header allows.
  uint64_t max_out = kGzipHeadBytes;
  bool head_checked = false;
  grow(path, out, capacity, std::min<size_t>(std::max<size_t>(guess, 1 << 16), kGzipHeadBytes + 1));
  z_stream zs;
  std::memset(&zs, 0, sizeof zs);
  if (inflateInit2(&zs, 15 + 16) != Z_OK) fail(path, "cannot start gzip decompression");
  struct End {
    z_stream* z;
    ~End() { inflateEnd(z); }
  } end_guard{&zs};
  auto check_head = [&] {
    head_checked = true;
    max_out = limit(out.view());
    if (out.size > max_out) over_limit(path, max_out);
    grow(path, out, capacity, std::min<uint64_t>(guess, max_out + 1));
  };
  size_t used = 0;  // input bytes consumed
  for (;;) {
    // One gzip member per pass; files may hold several concatenated members.
    int rc = Z_OK;
    while (rc != Z_STREAM_END) {
      if (!head_checked && out.size >= kGzipHeadBytes) check_head();
      // Room for at most one byte past the limit, which tells "more than the limit".
      const uint64_t room = max_out + 1 - out.size;
      if (capacity - out.size < std::min<uint64_t>(room, 1 << 16))
        grow(path, out, capacity, std::min<uint64_t>(capacity * 2, max_out + 1));
      // zlib counts in 32 bits: feed at most 1 GiB at a time.
      zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data() + used));
      zs.avail_in = static_cast<uInt>(std::min<size_t>(in.size() - used, 1u << 30));
      zs.next_out = reinterpret_cast<Bytef*>(out.data() + out.size);
      zs.avail_out = static_cast<uInt>(std::min<uint64_t>({capacity - out.size, room, 1u << 30}));
      const uInt in_before = zs.avail_in, out_before = zs.avail_out;
      rc = inflate(&zs, Z_NO_FLUSH);
      used += in_before - zs.avail_in;
      out.size += out_before - zs.avail_out;
      if (rc == Z_DATA_ERROR || rc == Z_NEED_DICT || rc == Z_MEM_ERROR || rc == Z_STREAM_ERROR)
        fail(path, std::string("corrupt gzip data (") + (zs.msg ? zs.msg : "bad data") + ")");
      if (out.size > max_out) {
        if (!head_checked) check_head();
        if (out.size > max_out) over_limit(path, max_out);
      }
      if (rc != Z_STREAM_END && used == in.size() && zs.avail_in == in_before && zs.avail_out == out_before)
        fail(path, "truncated gzip data (the file ends inside the compressed stream)");
    }
    if (!gzip_magic_at(in, used)) break;
    inflateReset(&zs);
  }
  if (!head_checked) check_head();
  // Anything after the last member other than zero padding is garbage.
  for (size_t i = used; i < in.size(); ++i)
    if (in[i] != 0) fail(path, "unexpected data after the gzip stream");
  return out;
}

}  // namespace meshsal
