// meshsal batch: BatchLog (see batch_log.h).
#include "batch_log.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>

#include "json_string.h"
#include "json_valid.h"
#include "meshsal/meshsal.h"

namespace meshsal::cli {
namespace {


// A log line longer than this is no record of a batch (those are a few KB): torn.
constexpr uint64_t kMaxCheckedLine = uint64_t(1) << 20;

}  // namespace

uint64_t torn_last_line(const std::string& path) {
  // O_NONBLOCK: a FIFO given as the log is not waited on (and not read: regular files only).
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) return 0;
  struct stat st;
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || st.st_size <= 0) {
    ::close(fd);
    return 0;
  }
  // Backwards from the end, a block at a time: past the blank tail, then to the newline
  // before the last line, which is [start, end).
  char buf[1 << 16];
  const auto read_block = [&](uint64_t to, uint64_t* from) {
    *from = to > sizeof buf ? to - sizeof buf : 0;
    const size_t n = size_t(to - *from);
    ssize_t got;
    do got = ::pread(fd, buf, n, off_t(*from));
    while (got < 0 && errno == EINTR);
    return got == ssize_t(n) ? n : size_t(0);  // 0: unreadable, nothing to say about it
  };
  const auto blank = [](char c) { return c == '\n' || c == '\r' || c == ' ' || c == '\t'; };
  uint64_t end = uint64_t(st.st_size), from = 0;
  while (end > 0) {
    size_t n = read_block(end, &from);
    if (n == 0) break;
    while (n > 0 && blank(buf[n - 1])) --n;
    end = from + n;
    if (n > 0) break;
  }
  std::string line;  // its bytes, while at most kMaxCheckedLine
  uint64_t start = end;
  while (start > 0) {
    size_t n = read_block(start, &from);
    if (n == 0) break;
    size_t k = n;
    while (k > 0 && buf[k - 1] != '\n') --k;
    if (end - (from + k) <= kMaxCheckedLine) line.insert(0, buf + k, n - k);
    start = from + k;
    if (k > 0) break;
  }
  const uint64_t line_bytes = end - start;
  ::close(fd);
  if (line_bytes == 0) return 0;
  return line_bytes > kMaxCheckedLine || !is_json(line) ? line_bytes : 0;
}

void BatchLog::add(const std::string& json_line) {
  // The log stays JSON Lines whatever went wrong before: a line that is not one JSON value
  // on one line is never written (every line comes from JsonObject, or a state file's
  // record load_state checked).
  if (!is_json_line(json_line)) {
    ++lost_;
    failed("a log line that is not one JSON value was left out of " + file_->path());
    return;
  }
  try {
    file_->append(json_line);
  } catch (const meshsal::Error& e) {
    ++lost_;
    failed(std::string(e.what()) + ": the log misses this model's line; the run goes on");
  }
}

void BatchLog::finish() {
  try {
    file_->sync();
  } catch (const meshsal::Error& e) {
    failed(e.what());
  }
}

void BatchLog::failed(const std::string& error) {
  if (!error_.empty()) return;  // once: the same reason would follow every model
  error_ = error;
  std::fprintf(stderr, "error: %s\n", printable(error).c_str());
}

}  // namespace meshsal::cli
