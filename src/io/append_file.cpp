#include "io/append_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "io/atomic_write.h"
#include "io/sigpipe_blocked.h"
#include "meshsal/meshsal.h"

namespace meshsal {
namespace {

[[noreturn]] void fail(const std::string& path, const char* what, int err) {
  throw Error(path + ": " + what + ": " + std::strerror(err));
}

}  // namespace

AppendFile::AppendFile(const std::string& path) : path_(path) {
  const OutputTarget t = output_target(path);
  struct stat st;
  const bool fifo = ::stat(t.path.c_str(), &st) == 0 && S_ISFIFO(st.st_mode);
  fd_ = ::open(t.path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC | O_NOCTTY | (fifo ? O_NONBLOCK : 0) |
                                   (t.kind == OutputKind::Direct ? 0 : O_CREAT),
               0666);
  if (fd_ < 0) {
    if (errno == ENXIO) throw Error(path + ": cannot write: it is a named pipe (FIFO) and nothing reads from it");
    fail(path, "cannot write", errno);
  }
  if (fifo) ::fcntl(fd_, F_SETFL, ::fcntl(fd_, F_GETFL) & ~O_NONBLOCK);
  if (::fstat(fd_, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0) {
    char last = '\n';
    const int reader = ::open(t.path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);  // fd_ is write-only
    const bool cut = reader >= 0 && ::pread(reader, &last, 1, st.st_size - 1) == 1 && last != '\n';
    if (reader >= 0) ::close(reader);
    if (cut) {
      try {
        append("");  // ends the cut line; what was cut stays recognisably broken
      } catch (...) {
        ::close(fd_);
        throw;
      }
    }
  }
}

AppendFile::~AppendFile() {
  if (fd_ >= 0) ::close(fd_);
}

void AppendFile::append(const std::string& line) {
  // After a failed write cut a line, the next line starts on a line of its own.
  const std::string data = (cut_ ? "\n" : "") + line + "\n";
  const SigpipeBlocked no_sigpipe;  // a reader that went away gives EPIPE, not death
  size_t done = 0;
  int err = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(fd_, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      err = n < 0 ? errno : EIO;
      break;
    }
    done += size_t(n);
  }
  cut_ = err && done > 0 ? true : err ? cut_ : false;
  if (err) fail(path_, "write failed", err);
}

void AppendFile::sync() {
  if (::fsync(fd_) != 0 && errno != EINVAL && errno != EROFS) fail(path_, "write failed", errno);
}

}  // namespace meshsal
