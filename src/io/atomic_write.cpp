#include "io/atomic_write.h"

#include <dirent.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <vector>

#include "io/sigpipe_blocked.h"
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

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
  throw Error(path + ": cannot write: " + why);
}

bool in_proc(const std::string& path) { return path.rfind("/proc/", 0) == 0; }

const char mkstemp_suffix[] = ".tmp.XXXXXX";
constexpr size_t kRandomLetters = 6;

// True for NAME.tmp.XXXXXX with X from mkstemp's alphabet; *base receives NAME.
bool temporary_name(const std::string& name, std::string* base) {
  const size_t tail = sizeof mkstemp_suffix - 1;  // ".tmp." + 6 letters
  if (name.size() <= tail || name.compare(name.size() - tail, 5, ".tmp.") != 0) return false;
  for (size_t i = name.size() - kRandomLetters; i < name.size(); ++i) {
    const char c = name[i];
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9'))) return false;
  }
  *base = name.substr(0, name.size() - tail);
  return true;
}

// Flushes and closes f, throwing the write error (EPIPE, ENOSPC) if any step fails.
void finish_stream(std::FILE* f, const std::string& path) {
  const bool failed = std::fflush(f) != 0 || std::ferror(f);
  const int err = errno ? errno : EIO;
  if (std::fclose(f) != 0 && !failed) fail(path, "write failed", errno);
  if (failed) fail(path, "write failed", err);
}

// A character device or a pipe: opened and written as it is.
void write_in_place(const OutputTarget& t, const std::string& path,
                    const std::function<void(std::FILE*)>& body) {
  struct stat st;
  const bool fifo = ::stat(t.path.c_str(), &st) == 0 && S_ISFIFO(st.st_mode);
  const bool regular = ::stat(t.path.c_str(), &st) == 0 && S_ISREG(st.st_mode);  // /dev/stdout > file
  // A pipe without a reader would block the open forever: O_NONBLOCK makes it ENXIO.
  const int fd = ::open(t.path.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY | (fifo ? O_NONBLOCK : 0) |
                                            (regular ? O_TRUNC : 0));
  if (fd < 0) {
    if (errno == ENXIO) refuse(path, "it is a named pipe (FIFO) and nothing reads from it");
    fail(path, "cannot write", errno);
  }
  if (fifo) ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);  // the reader sets the pace
  std::FILE* f = ::fdopen(fd, "wb");
  if (!f) {
    const int e = errno;
    ::close(fd);
    fail(path, "cannot write", e);
  }
  SigpipeBlocked no_sigpipe;
  try {
    errno = 0;
    body(f);
  } catch (...) {
    std::fclose(f);
    throw;
  }
  finish_stream(f, path);
}

// Creates NAME.tmp.XXXXXX and takes its lock. A cleaner (remove_stale_temporaries) may
// have removed the name between the two (it found it unlocked): then try a fresh name.
int create_locked_temporary(const std::string& target, const std::string& path, std::string* tmp_path) {
  for (int attempt = 0; attempt < 8; ++attempt) {
    std::vector<char> tmp(target.begin(), target.end());
    tmp.insert(tmp.end(), mkstemp_suffix, mkstemp_suffix + sizeof mkstemp_suffix);  // with the 0
    const int fd = ::mkostemp(tmp.data(), O_CLOEXEC);
    if (fd < 0) fail(path, "cannot write", errno);
    struct stat mine, named;
    if (::flock(fd, LOCK_EX) == 0 && ::fstat(fd, &mine) == 0 && ::lstat(tmp.data(), &named) == 0 &&
        mine.st_dev == named.st_dev && mine.st_ino == named.st_ino) {
      *tmp_path = tmp.data();
      return fd;
    }
    ::close(fd);
  }
  throw Error(path + ": cannot write: the temporary file kept disappearing");
}

}  // namespace

OutputTarget output_target(const std::string& path) {
  if (path.empty()) throw Error("cannot write: empty output file name");
  OutputTarget t;
  t.path = path;
  // Follow the symlinks by hand: realpath() fails on a dangling one, whose target is still
  // the file to write.
  for (int hops = 0;; ++hops) {
    struct stat st;
    if (::lstat(t.path.c_str(), &st) != 0 || !S_ISLNK(st.st_mode) || in_proc(t.path)) break;
    if (hops == 40) refuse(path, "too many levels of symbolic links");
    std::vector<char> buf(size_t(st.st_size > 0 ? st.st_size : 255) + 2);
    const ssize_t n = ::readlink(t.path.c_str(), buf.data(), buf.size() - 1);
    if (n < 0 || size_t(n) >= buf.size() - 1) fail(path, "cannot read the symbolic link", n < 0 ? errno : ENAMETOOLONG);
    const std::string to(buf.data(), size_t(n));
    t.path = !to.empty() && to[0] == '/' ? to : folder_of(t.path) + "/" + to;
  }
  struct stat st;
  if (::stat(t.path.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) refuse(path, "it is a folder");
    if (S_ISBLK(st.st_mode)) refuse(path, "it is a block device (a disk); meshsal writes only files, "
                                          "character devices such as /dev/null and named pipes");
    if (S_ISSOCK(st.st_mode)) refuse(path, "it is a socket");
    if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode) || in_proc(t.path)) {
      if (::access(t.path.c_str(), W_OK) != 0) fail(path, "cannot write", errno);
      t.kind = OutputKind::Direct;
      return t;
    }
    t.kind = OutputKind::ReplaceFile;
  } else if (in_proc(t.path)) {
    fail(path, "cannot write", errno);
  }
  // A file: the temporary is made in its folder, and the rename needs that folder.
  const std::string folder = folder_of(t.path);
  struct stat fs;
  if (::stat(folder.c_str(), &fs) != 0 || !S_ISDIR(fs.st_mode))
    refuse(path, "folder '" + folder + "' does not exist");
  if (::access(folder.c_str(), W_OK | X_OK) != 0)
    refuse(path, "folder '" + folder + "' is not writable (" + std::strerror(errno) + ")");
  return t;
}

void write_all(std::FILE* f, const void* data, size_t n, const std::string& path) {
  if (n && std::fwrite(data, 1, n, f) != n) fail(path, "write failed", errno ? errno : EIO);
#if defined(__linux__)
  // Errors are left to the final flush and fsync, which check every step.
  if (n >= (size_t(1) << 20) && std::fflush(f) == 0)
    (void)::sync_file_range(::fileno(f), 0, 0, SYNC_FILE_RANGE_WRITE);
#endif
}

void write_file_atomically(const std::string& path, const std::function<void(std::FILE*)>& body) {
  const OutputTarget t = output_target(path);
  if (t.kind == OutputKind::Direct) return write_in_place(t, path, body);
  mode_t mode = default_file_mode();
  struct stat st;
  if (t.kind == OutputKind::ReplaceFile && ::stat(t.path.c_str(), &st) == 0 && S_ISREG(st.st_mode))
    mode = st.st_mode & 07777 & ~mode_t(S_ISUID | S_ISGID);
  std::string tmp_path;
  const int fd = create_locked_temporary(t.path, path, &tmp_path);
  // The lock lives as long as any descriptor of the open file: this one holds it past the
  // stream's fclose until the rename is done, so no cleaner takes a finished temporary.
  const int lock_fd = ::dup(fd);
  std::FILE* f = nullptr;
  bool fd_open = true;  // until fdopen takes it over, or fclose closes it
  try {
    if (lock_fd < 0) fail(path, "cannot write", errno);
    if (::fchmod(fd, mode) != 0) fail(path, "cannot write", errno);
    f = ::fdopen(fd, "wb");
    if (!f) fail(path, "cannot write", errno);
    errno = 0;
    body(f);
    // Data still in the stdio buffer or the page cache can fail to go out (a full disk):
    // check every step, so that a short file is never renamed into place.
    if (std::fflush(f) != 0 || std::ferror(f)) fail(path, "write failed", errno ? errno : EIO);
    if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) fail(path, "write failed", errno);
    std::FILE* closing = f;
    f = nullptr;
    fd_open = false;
    if (std::fclose(closing) != 0) fail(path, "write failed", errno);
    if (std::rename(tmp_path.c_str(), t.path.c_str()) != 0) fail(path, "cannot replace the file", errno);
  } catch (...) {
    if (f)
      std::fclose(f);
    else if (fd_open)
      ::close(fd);
    ::unlink(tmp_path.c_str());
    if (lock_fd >= 0) ::close(lock_fd);
    throw;
  }
  ::close(lock_fd);
}

size_t remove_stale_temporaries(const std::string& folder,
                                const std::function<bool(const std::string& base)>& ours) {
  DIR* dir = ::opendir(folder.empty() ? "." : folder.c_str());
  if (!dir) return 0;
  const int dir_fd = ::dirfd(dir);
  size_t removed = 0;
  while (const dirent* e = ::readdir(dir)) {
    std::string base;
    if (!temporary_name(e->d_name, &base) || !ours(base)) continue;
    // O_NONBLOCK: should a FIFO have that name, opening it does not wait for a writer.
    const int fd = ::openat(dir_fd, e->d_name, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) continue;
    struct stat st, named;
    // Unlocked: its writer is gone (a live writer holds the lock from creation to rename).
    // Still the same file under that name once locked: remove it while holding the lock.
    if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_uid == ::geteuid() &&
        ::flock(fd, LOCK_EX | LOCK_NB) == 0 && ::fstatat(dir_fd, e->d_name, &named, AT_SYMLINK_NOFOLLOW) == 0 &&
        named.st_dev == st.st_dev && named.st_ino == st.st_ino && ::unlinkat(dir_fd, e->d_name, 0) == 0)
      ++removed;
    ::close(fd);
  }
  ::closedir(dir);
  return removed;
}

}  // namespace meshsal
