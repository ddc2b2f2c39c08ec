// meshsal batch: BatchLog (see batch_log.h).
#include "batch_log.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>

#include "json_string.h"
#include "meshsal/meshsal.h"

namespace meshsal_cli {
namespace {

// Recursive descent over one JSON value (RFC 8259, no extensions).
class JsonCheck {
 public:
  explicit JsonCheck(const std::string& s) : s_(s) {}
  bool whole() { return value(0) && (blank(), i_ == s_.size()); }

 private:
  const std::string& s_;
  size_t i_ = 0;
  void blank() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\n' || s_[i_] == '\r')) ++i_;
  }
  bool eat(char c) {
    blank();
    if (i_ < s_.size() && s_[i_] == c) return ++i_, true;
    return false;
  }
  bool word(const char* w) {
    const std::string t(w);
    if (s_.compare(i_, t.size(), t) != 0) return false;
    i_ += t.size();
    return true;
  }
  bool digit() const { return i_ < s_.size() && s_[i_] >= '0' && s_[i_] <= '9'; }
  bool digits() {
    const size_t start = i_;
    while (digit()) ++i_;
    return i_ > start;
  }
  bool number() {
    if (i_ < s_.size() && s_[i_] == '-') ++i_;
    if (i_ < s_.size() && s_[i_] == '0') ++i_;
    else if (!digits()) return false;
    if (i_ < s_.size() && s_[i_] == '.' && (++i_, !digits())) return false;
    if (i_ < s_.size() && (s_[i_] == 'e' || s_[i_] == 'E')) {
      ++i_;
      if (i_ < s_.size() && (s_[i_] == '+' || s_[i_] == '-')) ++i_;
      if (!digits()) return false;
    }
    return true;
  }
  bool hex() const {
    if (i_ >= s_.size()) return false;
    const char c = s_[i_];
    return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
  }
  bool string() {
    if (!eat('"')) return false;
    while (i_ < s_.size()) {
      const unsigned char c = static_cast<unsigned char>(s_[i_++]);
      if (c == '"') return true;
      if (c < 0x20) return false;
      if (c == '\\') {
        if (i_ >= s_.size()) return false;
        const char e = s_[i_++];
        if (e == 'u') {
          for (int k = 0; k < 4; ++k, ++i_)
            if (!hex()) return false;
        } else if (std::string("\"\\/bfnrt").find(e) == std::string::npos) {
          return false;
        }
      }
    }
    return false;
  }
  bool value(int depth) {
    if (depth > 64) return false;
    blank();
    if (i_ >= s_.size()) return false;
    const char c = s_[i_];
    if (c == '{') {
      ++i_;
      if (eat('}')) return true;
      do {
        if (!string() || !eat(':') || !value(depth + 1)) return false;
      } while (eat(','));
      return eat('}');
    }
    if (c == '[') {
      ++i_;
      if (eat(']')) return true;
      do {
        if (!value(depth + 1)) return false;
      } while (eat(','));
      return eat(']');
    }
    if (c == '"') return string();
    if (c == 't') return word("true");
    if (c == 'f') return word("false");
    if (c == 'n') return word("null");
    return number();
  }
};

// A log line longer than this is no record of a batch (those are a few KB): torn.
constexpr uint64_t kMaxCheckedLine = uint64_t(1) << 20;

}  // namespace

bool is_json(const std::string& text) { return JsonCheck(text).whole(); }

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

}  // namespace meshsal_cli
