#include "tiles/scratch_files.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include "core/parallel.h"
#include "tiles/scratch_lock.h"
#include "meshsal/meshsal.h"

namespace meshsal {

namespace {
[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw Error(path + ": " + what + " (" + std::strerror(errno) + ")");
}
}  // namespace

ScratchDir::ScratchDir(const std::string& parent) {
  std::string base = parent;
  if (base.empty()) {
    const char* t = std::getenv("TMPDIR");
    base = t && *t ? t : "/tmp";
  }
  // What runs that died left here (removed where the locks can be trusted).
  std::string file_system;
  const bool trusted = scratch_locks_trusted(base, &file_system);
  note_ = stale_scratch_note(base, remove_stale_scratch_dirs(base, trusted), file_system);
  std::string pattern = base + "/" + kScratchPrefix + "XXXXXX";
  std::vector<char> buf(pattern.begin(), pattern.end());
  buf.push_back('\0');
  if (!mkdtemp(buf.data())) fail(base, "cannot create a temporary folder for the tiles");
  path_ = buf.data();
  lock_ = lock_scratch_dir(path_);
}

void ScratchDir::remove() {
  if (owner_ && !path_.empty()) remove_scratch_dir(path_);
  if (lock_ >= 0) ::close(lock_);  // after the folder is gone: no run sees it unlocked
  lock_ = -1;
}

void ScratchDir::borrow(const std::string& path) {
  remove();
  path_ = path;
  owner_ = false;
}

ScratchDir::~ScratchDir() { remove(); }

ScratchWriter::ScratchWriter(const std::string& path, bool append) : path_(path) {
  f_ = std::fopen(path.c_str(), append ? "ab" : "wb");
  if (!f_) fail(path, "cannot write a temporary file");
  std::setvbuf(f_, nullptr, _IOFBF, 1 << 16);
}

ScratchWriter::ScratchWriter(const std::string& path, uint64_t offset) : path_(path) {
  f_ = std::fopen(path.c_str(), "r+b");
  if (!f_) fail(path, "cannot write a temporary file");
  std::setvbuf(f_, nullptr, _IOFBF, 1 << 16);
  if (fseeko(f_, off_t(offset), SEEK_SET) != 0) fail(path, "cannot seek in a temporary file");
}

ScratchWriter::~ScratchWriter() {
  if (f_) std::fclose(f_);
}

void ScratchWriter::write(const void* data, size_t bytes) {
  if (bytes && std::fwrite(data, 1, bytes, f_) != bytes) fail(path_, "cannot write a temporary file (disk full?)");
}

void ScratchWriter::close() {
  if (!f_) return;
  const bool bad = std::fflush(f_) != 0 || std::ferror(f_);
  std::fclose(f_);
  f_ = nullptr;
  if (bad) fail(path_, "cannot write a temporary file (disk full?)");
}

ScratchReader::ScratchReader(const std::string& path) : path_(path) {
  f_ = std::fopen(path.c_str(), "rb");
  if (!f_) fail(path, "cannot read a temporary file");
  std::setvbuf(f_, nullptr, _IOFBF, 1 << 16);
}

ScratchReader::~ScratchReader() {
  if (f_) std::fclose(f_);
}

size_t ScratchReader::read(void* to, size_t bytes) {
  const size_t got = std::fread(to, 1, bytes, f_);
  if (got < bytes && std::ferror(f_)) fail(path_, "cannot read a temporary file");
  return got;
}

void ScratchReader::read_exact(void* to, size_t bytes) {
  if (read(to, bytes) != bytes) throw Error(path_ + ": a temporary file is shorter than written");
}

void ScratchReader::seek(uint64_t offset) {
  if (fseeko(f_, off_t(offset), SEEK_SET) != 0) fail(path_, "cannot seek in a temporary file");
}

std::vector<uint8_t> read_scratch_file(const std::string& path) {
  ScratchReader in(path);
  std::vector<uint8_t> data;
  uint8_t buf[1 << 16];
  for (size_t got; (got = in.read(buf, sizeof buf)) > 0;) data.insert(data.end(), buf, buf + got);
  return data;
}

namespace {

// read_records for sorted[begin, end) from the open file fd.
void read_record_range(int fd, const std::string& path, size_t record_bytes, const std::vector<uint32_t>& sorted,
                       size_t begin, size_t end, uint8_t* dst) {
  constexpr size_t kWindow = 4096;  // records per read at most
  std::vector<uint8_t> window;
  size_t i = begin;
  while (i < end) {
    // One read from sorted[i] to the farthest index within the window.
    const uint64_t first = sorted[i];
    size_t j = i;
    while (j + 1 < end && sorted[j + 1] < first + kWindow) ++j;
    const size_t count = size_t(sorted[j] - first + 1);
    window.resize(count * record_bytes);
    const ssize_t got = ::pread(fd, window.data(), window.size(), off_t(first * record_bytes));
    if (got != ssize_t(window.size())) {
      if (got < 0) fail(path, "cannot read a temporary file");
      throw Error(path + ": a temporary file is shorter than written");
    }
    for (size_t k = i; k <= j; ++k)
      std::memcpy(dst + k * record_bytes, &window[(sorted[k] - first) * record_bytes], record_bytes);
    i = j + 1;
  }
}

}  // namespace

void read_records(const std::string& path, size_t record_bytes, const std::vector<uint32_t>& sorted, void* out,
                  unsigned threads) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) fail(path, "cannot read a temporary file");
  // Parts of at least 64K records, one a thread (pread shares the descriptor).
  const size_t parts = std::max<size_t>(1, std::min<size_t>(resolve_threads(threads), sorted.size() >> 16));
  try {
    parallel_for(parts, unsigned(parts), 1, [&](size_t p0, size_t p1) {
      for (size_t p = p0; p < p1; ++p)
        read_record_range(fd, path, record_bytes, sorted, sorted.size() * p / parts, sorted.size() * (p + 1) / parts,
                          static_cast<uint8_t*>(out));
    });
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
}

void write_records(const std::string& path, size_t record_bytes, const std::vector<uint32_t>& ids, const void* data) {
  const int fd = ::open(path.c_str(), O_WRONLY);
  if (fd < 0) fail(path, "cannot write a temporary file");
  const auto* src = static_cast<const uint8_t*>(data);
  size_t i = 0;
  while (i < ids.size()) {
    size_t j = i;  // one write for a run of consecutive ids
    while (j + 1 < ids.size() && ids[j + 1] == ids[j] + 1) ++j;
    const size_t bytes = (j - i + 1) * record_bytes;
    if (::pwrite(fd, src + i * record_bytes, bytes, off_t(uint64_t(ids[i]) * record_bytes)) != ssize_t(bytes)) {
      ::close(fd);
      fail(path, "cannot write a temporary file");
    }
    i = j + 1;
  }
  if (::close(fd) != 0) fail(path, "cannot write a temporary file");
}

}  // namespace meshsal
