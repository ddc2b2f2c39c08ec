// meshsal batch: the resume records (see batch_state.h).
#include "batch_state.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/atomic_write.h"
#include "meshsal/meshsal.h"

namespace meshsal_cli {
namespace {

using meshsal::Error;

constexpr uint64_t kWholeFileBytes = uint64_t(1) << 20;
constexpr size_t kEndBytes = size_t(64) << 10, kSampleBytes = 4096, kSamples = 64;
const char kMagic[] = "meshsal-batch-state 1";

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

bool load_state(const std::string& path, ModelState* s) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  if (!in || !std::getline(in, line) || line != kMagic) return false;
  *s = ModelState{};
  bool have_input = false, have_options = false, have_record = false;
  while (std::getline(in, line)) {
    const size_t sp = line.find(' ');
    const std::string key = line.substr(0, sp), rest = sp == std::string::npos ? "" : line.substr(sp + 1);
    std::istringstream r(rest);
    if (key == "input") {
      have_input = bool(r >> s->input.size >> s->input.mtime_ns >> s->input.hash);
    } else if (key == "options") {
      s->options = rest;
      have_options = true;
    } else if (key == "output") {
      uint64_t size = 0;
      if (!(r >> size)) return false;
      s->output_sizes.push_back(size);
    } else if (key == "record") {
      s->record = rest;
      have_record = true;
    }
  }
  return have_input && have_options && have_record;
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

}  // namespace meshsal_cli
