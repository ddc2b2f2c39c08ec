// meshsal batch: the resume records (see batch_state.h).
#include "batch_state.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <vector>

#include "io/atomic_write.h"
#include "json_valid.h"
#include "meshsal/meshsal.h"

namespace meshsal::cli {
namespace {

using meshsal::Error;

constexpr uint64_t kWholeFileBytes = uint64_t(1) << 20;
constexpr size_t kEndBytes = size_t(64) << 10, kSampleBytes = 4096, kSamples = 64;
const char kMagic[] = "meshsal-batch-state 1";
// A state file is a few KB (its record is one log line); anything larger is no state this
// program wrote, and is not read (a record that large would go into the log whole).
constexpr size_t kMaxStateBytes = size_t(1) << 20;
constexpr size_t kMaxOutputs = 16;  // ModelOutputs::all() has at most 5

uint64_t fnv1a(uint64_t h, const char* data, size_t n) {
  for (size_t i = 0; i < n; ++i) h = (h ^ static_cast<unsigned char>(data[i])) * 0x100000001b3ULL;
  return h;
}

// Hashes n bytes at `offset` (fewer where the file ends).
uint64_t hash_range(int fd, uint64_t offset, size_t n, uint64_t h, const std::string& path) {
  char buf[1 << 16];
  while (n > 0) {
    const ssize_t got = ::pread(fd, buf, std::min(n, sizeof buf), off_t(offset));
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw Error(path + ": cannot read: " + std::strerror(errno));
    if (got == 0) break;
    h = fnv1a(h, buf, size_t(got));
    offset += uint64_t(got);
    n -= size_t(got);
  }
  return h;
}

}  // namespace

InputFingerprint fingerprint(const std::string& path) {
  // O_NONBLOCK: a FIFO put there since the input was checked is not waited on.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw Error(path + ": cannot open: " + std::strerror(errno));
  InputFingerprint f;
  try {
    struct stat st;
    if (::fstat(fd, &st) != 0) throw Error(path + ": cannot stat: " + std::strerror(errno));
    if (!S_ISREG(st.st_mode)) throw Error(path + ": not a regular file");
    f.size = uint64_t(st.st_size);
    f.mtime_ns = int64_t(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
    uint64_t h = 0xcbf29ce484222325ULL;
    if (f.size <= kWholeFileBytes) {
      h = hash_range(fd, 0, size_t(f.size), h, path);
    } else {
      h = hash_range(fd, 0, kEndBytes, h, path);
      const uint64_t span = f.size - 2 * kEndBytes - kSampleBytes;
      for (size_t k = 0; k < kSamples; ++k)
        h = hash_range(fd, kEndBytes + span * k / (kSamples - 1), kSampleBytes, h, path);
      h = hash_range(fd, f.size - kEndBytes, kEndBytes, h, path);
    }
    f.hash = h;
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
  return f;
}

std::string state_path(const std::string& dir, const std::string& name) {
  return dir + (dir.empty() || dir.back() == '/' ? "" : "/") + ".meshsal-batch/" + name + ".state";
}

void save_state(const std::string& path, const ModelState& s) {
  std::error_code ec;
  std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
  if (ec) throw Error(path + ": cannot create the folder: " + ec.message());
  // The state file is batch's own: a link, FIFO or device found in its place (load_state
  // read none of them) is replaced by a regular file, not written through.
  struct stat st;
  if (::lstat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode)) ::unlink(path.c_str());
  // One item per line: neither the record (JSON) nor the options hold a newline. The
  // outputs are known by their order (the options decide which there are), not by path.
  std::ostringstream o;
  o << kMagic << "\n"
    << "input " << s.input.size << " " << s.input.mtime_ns << " " << s.input.hash << "\n"
    << "options " << s.options << "\n";
  for (uint64_t size : s.output_sizes) o << "output " << size << "\n";
  o << "record " << s.record << "\n";
  const std::string text = o.str();
  meshsal::write_file_atomically(path, [&](std::FILE* f) { meshsal::write_all(f, text.data(), text.size(), path); });
}

void mark_started(const std::string& path) {
  struct stat st;
  if (::lstat(path.c_str(), &st) == 0) return;
  std::error_code ec;
  std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
  if (ec) throw Error(path + ": cannot create the folder: " + ec.message());
  const std::string text = std::string(kMagic) + "\nstarted\n";
  meshsal::write_file_atomically(path, [&](std::FILE* f) { meshsal::write_all(f, text.data(), text.size(), path); });
}

namespace {

// The whole of `path` when it is a regular file (not a link, a FIFO or a device, which
// could block or never end) of at most kMaxStateBytes.
bool read_state_file(const std::string& path, std::string* text) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOFOLLOW);
  if (fd < 0) return false;
  struct stat st;
  bool ok = ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && uint64_t(st.st_size) <= kMaxStateBytes;
  if (ok) {
    text->resize(kMaxStateBytes + 1);  // one more: a file grown since fstat is seen
    size_t got = 0;
    while (got < text->size()) {
      const ssize_t n = ::read(fd, &(*text)[got], text->size() - got);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        ok = n == 0;
        break;
      }
      got += size_t(n);
    }
    text->resize(got);
    ok = ok && got <= kMaxStateBytes;
  }
  ::close(fd);
  return ok;
}

// A whole number as save_state writes it: decimal digits only, that fit.
bool parse_whole(const std::string& s, uint64_t* value) {
  if (s.empty() || s.size() > 20) return false;
  uint64_t v = 0;
  for (const char c : s) {
    if (c < '0' || c > '9' || v > (UINT64_MAX - uint64_t(c - '0')) / 10) return false;
    v = v * 10 + uint64_t(c - '0');
  }
  *value = v;
  return true;
}

// "SIZE MTIME_NS HASH", MTIME_NS maybe negative.
bool parse_input(const std::string& text, InputFingerprint* f) {
  const size_t a = text.find(' '), b = a == std::string::npos ? a : text.find(' ', a + 1);
  if (b == std::string::npos) return false;
  const bool minus = text[a + 1] == '-';
  uint64_t mtime = 0;
  if (!parse_whole(text.substr(0, a), &f->size) || !parse_whole(text.substr(a + 1 + minus, b - a - 1 - minus), &mtime) ||
      !parse_whole(text.substr(b + 1), &f->hash) || mtime > uint64_t(INT64_MAX))
    return false;
  f->mtime_ns = minus ? -int64_t(mtime) : int64_t(mtime);
  return true;
}

}  // namespace

bool valid_record(const std::string& record) {
  // skipped_line (cmd_batch.cpp) turns its "done" into "skipped" and adds a member before
  // the last '}': valid JSON in, valid JSON out.
  return record.size() > 2 && record.front() == '{' && record.back() == '}' && is_json_line(record) &&
         record.find("\"status\": \"done\"") != std::string::npos;
}

bool load_state(const std::string& path, ModelState* s) {
  std::string text;
  if (!read_state_file(path, &text) || text.empty() || text.back() != '\n') return false;  // torn: no last newline
  std::vector<std::string> lines;
  for (size_t at = 0; at < text.size();) {
    const size_t nl = text.find('\n', at);
    lines.push_back(text.substr(at, nl - at));
    at = nl + 1;
  }
  // save_state's lines, in its order: the magic, input, options, the outputs, the record.
  if (lines.size() < 4 || lines[0] != kMagic || lines.size() - 4 > kMaxOutputs) return false;
  const auto rest = [&](size_t i, const std::string& key, std::string* value) {
    if (lines[i].compare(0, key.size() + 1, key + " ") != 0) return false;
    *value = lines[i].substr(key.size() + 1);
    return true;
  };
  ModelState st;
  std::string value;
  if (!rest(1, "input", &value) || !parse_input(value, &st.input)) return false;
  if (!rest(2, "options", &st.options)) return false;  // compared whole with the run's (up_to_date)
  for (size_t i = 3; i + 1 < lines.size(); ++i) {
    uint64_t size = 0;
    if (!rest(i, "output", &value) || !parse_whole(value, &size)) return false;
    st.output_sizes.push_back(size);
  }
  if (!rest(lines.size() - 1, "record", &st.record) || !valid_record(st.record)) return false;
  *s = std::move(st);
  return true;
}

bool up_to_date(const ModelState& saved, const InputFingerprint& input, const std::string& options,
                const std::vector<std::string>& outputs) {
  if (!(saved.input == input) || saved.options != options || saved.output_sizes.size() != outputs.size())
    return false;
  for (size_t i = 0; i < outputs.size(); ++i) {
    struct stat st;
    if (::stat(outputs[i].c_str(), &st) != 0 || !S_ISREG(st.st_mode) || uint64_t(st.st_size) != saved.output_sizes[i])
      return false;
  }
  return true;
}

}  // namespace meshsal::cli
