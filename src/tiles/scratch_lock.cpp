// meshsal: the temporary folders' locks and the removal of stale ones (scratch_lock.h).
// Every step goes through descriptors opened with O_NOFOLLOW, relative to the folder's
// own, so that a link put in a shared /tmp never sends a removal elsewhere.
#include "tiles/scratch_lock.h"

#include <dirent.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>
#if defined(__linux__)
#include <sys/vfs.h>
#else
#include <sys/mount.h>
#include <sys/param.h>
#endif

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

namespace meshsal {
namespace {

constexpr const char* kLockName = "lock";
constexpr const char* kNewLockName = "lock.new";

// The names in the folder open as `fd` (its descriptor is duplicated, `fd` stays open).
std::vector<std::string> entries(int fd) {
  std::vector<std::string> names;
  const int copy = ::dup(fd);
  if (copy < 0) return names;
  DIR* d = ::fdopendir(copy);
  if (!d) {
    ::close(copy);
    return names;
  }
  ::rewinddir(d);
  while (const dirent* e = ::readdir(d))
    if (std::strcmp(e->d_name, ".") != 0 && std::strcmp(e->d_name, "..") != 0) names.emplace_back(e->d_name);
  ::closedir(d);
  return names;
}

// Everything in the folder open as `fd`, but `keep` ("" = nothing kept); sub-folders too.
// Whether all of it went.
bool remove_contents(int fd, const char* keep) {
  bool all = true;
  for (const std::string& name : entries(fd)) {
    if (name == keep || ::unlinkat(fd, name.c_str(), 0) == 0) continue;
    const int sub = ::openat(fd, name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (sub >= 0) {
      remove_contents(sub, "");
      ::close(sub);
    }
    all = ::unlinkat(fd, name.c_str(), AT_REMOVEDIR) == 0 && all;
  }
  return all;
}

// The folder `name` in `parent_fd`, open as `fd`: its contents, then (only when they all
// went, so that what stays is still locked against the next run's judgement) its lock file
// and the folder itself. Whether the folder is gone.
bool remove_folder(int parent_fd, const std::string& name, int fd) {
  if (!remove_contents(fd, kLockName)) return false;
  ::unlinkat(fd, kLockName, 0);
  return ::unlinkat(parent_fd, name.c_str(), AT_REMOVEDIR) == 0;
}

// `dir` split into the folder that holds it and its name.
void split(const std::string& dir, std::string* parent, std::string* name) {
  std::string d = dir;
  while (d.size() > 1 && d.back() == '/') d.pop_back();
  const size_t slash = d.rfind('/');
  *parent = slash == std::string::npos ? "." : slash == 0 ? "/" : d.substr(0, slash);
  *name = slash == std::string::npos ? d : d.substr(slash + 1);
}

// The folder `name` in the folder open as `parent_fd`, when it is a stale temporary folder
// of this user: removed, and true.
bool remove_if_stale(int parent_fd, const std::string& name) {
  const int fd = ::openat(parent_fd, name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return false;
  bool removed = false;
  struct stat ds {};
  const int lock = ::fstat(fd, &ds) == 0 && ds.st_uid == ::geteuid()
                       ? ::openat(fd, kLockName, O_RDONLY | O_NOFOLLOW | O_CLOEXEC)
                       : -1;
  // No lock file: a run between making its folder and naming its lock (or one before
  // locks): not ours to judge.
  if (lock >= 0) {
    struct stat held {}, named {};
    // Locked, and still the file named `lock` (not one a run that removed the folder
    // meanwhile had unlinked): no run holds it, none can take it while we do.
    if (::flock(lock, LOCK_EX | LOCK_NB) == 0 && ::fstat(lock, &held) == 0 &&
        ::fstatat(fd, kLockName, &named, AT_SYMLINK_NOFOLLOW) == 0 && held.st_dev == named.st_dev &&
        held.st_ino == named.st_ino) {
      removed = remove_folder(parent_fd, name, fd);
    }
    ::close(lock);
  }
  ::close(fd);
  return removed;
}

}  // namespace

int lock_scratch_dir(const std::string& dir) {
  const int fd = ::open((dir + "/" + kNewLockName).c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd < 0) return -1;
  if (::flock(fd, LOCK_EX | LOCK_NB) == 0 &&
      ::rename((dir + "/" + kNewLockName).c_str(), (dir + "/" + kLockName).c_str()) == 0)
    return fd;
  ::close(fd);
  ::unlink((dir + "/" + kNewLockName).c_str());
  return -1;
}

void remove_scratch_dir(const std::string& dir) {
  std::string parent, name;
  split(dir, &parent, &name);
  const int parent_fd = ::open(parent.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (parent_fd < 0) return;
  const int fd = ::openat(parent_fd, name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd >= 0) {
    remove_folder(parent_fd, name, fd);
    ::close(fd);
  }
  ::close(parent_fd);
}

bool scratch_locks_trusted(const std::string& path, std::string* name) {
  name->clear();
#if defined(__linux__)
  struct statfs s {};
  if (::statfs(path.c_str(), &s) != 0) {
    *name = "unknown";
    return false;
  }
  // Local file systems, whose flock is the kernel's own.
  static const struct { uint32_t magic; const char* name; } kLocal[] = {
      {0xEF53, "ext4"},       {0x58465342, "xfs"},      {0x9123683E, "btrfs"},    {0x01021994, "tmpfs"},
      {0x858458F6, "ramfs"},  {0x794C7630, "overlay"},  {0x2FC12FC1, "zfs"},      {0xF2F52010, "f2fs"},
      {0x52654973, "reiserfs"}, {0x3153464A, "jfs"},    {0xCA451A4E, "bcachefs"}, {0x3434, "nilfs"}};
  // Where a lock may hold on one client only, or be refused: named in the note.
  static const struct { uint32_t magic; const char* name; } kShared[] = {
      {0x6969, "nfs"},         {0x517B, "smb"},          {0xFF534D42, "cifs"},   {0xFE534D42, "smb2"},
      {0x65735546, "fuse"},    {0x01021997, "9p"},       {0x00C36400, "ceph"},   {0x0BD00BD0, "lustre"},
      {0x47504653, "gpfs"},    {0x5346414F, "afs"},      {0x564C, "ncp"},        {0x73757245, "coda"}};
  const uint32_t magic = uint32_t(s.f_type);
  for (const auto& f : kLocal)
    if (f.magic == magic) return true;
  for (const auto& f : kShared)
    if (f.magic == magic) *name = f.name;
  if (name->empty()) {
    char hex[32];
    std::snprintf(hex, sizeof hex, "type 0x%x", unsigned(magic));
    *name = hex;
  }
  return false;
#else
  struct statfs s {};
  if (::statfs(path.c_str(), &s) != 0) {
    *name = "unknown";
    return false;
  }
  if (s.f_flags & MNT_LOCAL) return true;
  *name = s.f_fstypename;
  return false;
#endif
}

StaleScratch remove_stale_scratch_dirs(const std::string& parent, bool trusted) {
  StaleScratch found;
  const int parent_fd = ::open(parent.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (parent_fd < 0) return found;
  const size_t prefix = std::strlen(kScratchPrefix);
  for (const std::string& name : entries(parent_fd)) {
    if (name.compare(0, prefix, kScratchPrefix) != 0) continue;
    if (!trusted) {
      struct stat st {};
      if (::fstatat(parent_fd, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISDIR(st.st_mode)) found.left++;
    } else if (remove_if_stale(parent_fd, name)) {
      found.removed++;
    }
  }
  ::close(parent_fd);
  return found;
}

std::string stale_scratch_note(const std::string& parent, const StaleScratch& found, const std::string& file_system) {
  const auto folders = [](size_t n) {
    return std::to_string(n) + " temporary folder" + (n > 1 ? "s " : " ") + kScratchPrefix + "*";
  };
  if (found.removed)  // (a file system whose locks are trusted: nothing left)
    return "note: removed " + folders(found.removed) + " in " + parent +
           " that runs which crashed or were killed left (stale: no run held their lock)";
  if (found.left)
    return "note: " + parent + " holds " + folders(found.left) + " of other runs, left as they are: on " +
           file_system + " a lock cannot be trusted, so a stale one cannot be told from one in use " +
           "(remove them by hand when no meshsal run uses this folder)";
  return "";
}

}  // namespace meshsal
