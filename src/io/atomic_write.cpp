#include "io/atomic_write.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {
namespace {

std::string folder_of(const std::string& path) {
  size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

// The mode a new file gets from open(..., 0666): 0666 minus the umask. umask() can only be
// read by setting it, so read it once.
mode_t default_file_mode() {
  static const mode_t mode = [] {
    const mode_t mask = ::umask(0);
    ::umask(mask);
    return mode_t(0666 & ~mask);
  }();
  return mode;
}

[[noreturn]] void fail(const std::string& path, const char* what, int err) {
  throw Error(path + ": " + what + ": " + std::strerror(err));
}

}  // namespace

void write_all(std::FILE* f, const void* data, size_t n, const std::string& path) {
  if (n && std::fwrite(data, 1, n, f) != n) fail(path, "write failed", errno ? errno : EIO);
}

void write_file_atomically(const std::string& path, const std::function<void(std::FILE*)>& body) {
  if (path.empty()) throw Error("cannot write: empty output file name");
  const std::string folder = folder_of(path);
  struct stat st;
  if (::stat(folder.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
    throw Error(path + ": cannot write: folder '" + folder + "' does not exist");
  mode_t mode = default_file_mode();
  if (::stat(path.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) throw Error(path + ": cannot write: it is a folder");
    if (S_ISREG(st.st_mode)) mode = st.st_mode & 07777 & ~mode_t(S_ISUID | S_ISGID);
  }
  std::vector<char> tmp(path.begin(), path.end());
  const char suffix[] = ".tmp.XXXXXX";
  tmp.insert(tmp.end(), suffix, suffix + sizeof suffix);  // includes the terminating 0
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0) fail(path, "cannot write", errno);
  const std::string tmp_path(tmp.data());
  std::FILE* f = nullptr;
  bool fd_open = true;  // until fdopen takes it over, or fclose closes it
  try {
    if (::fchmod(fd, mode) != 0) fail(path, "cannot write", errno);
    f = ::fdopen(fd, "wb");
    if (!f) fail(path, "cannot write", errno);
    body(f);
    // Data still in the stdio buffer or the page cache can fail to go out (a full disk):
    // check every step, so that a short file is never renamed into place.
    if (std::fflush(f) != 0 || std::ferror(f)) fail(path, "write failed", errno ? errno : EIO);
    if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) fail(path, "write failed", errno);
    std::FILE* closing = f;
    f = nullptr;
    fd_open = false;
    if (std::fclose(closing) != 0) fail(path, "write failed", errno);
    if (std::rename(tmp_path.c_str(), path.c_str()) != 0) fail(path, "cannot replace the file", errno);
  } catch (...) {
    if (f)
      std::fclose(f);
    else if (fd_open)
      ::close(fd);
    ::unlink(tmp_path.c_str());
    throw;
  }
}

}  // namespace meshsal
