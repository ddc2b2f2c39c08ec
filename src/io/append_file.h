// meshsal: an append-only text file (meshsal batch's JSON Lines log), written line by line
// so that what a run has done is on disk at every moment, and earlier runs' lines stay.
#pragma once
#include <string>

namespace meshsal {

class AppendFile {
 public:
  // Opens `path` for appending, creating it (mode 0666 minus the umask) if missing, by the
  // writers' rule (atomic_write.h, output_target): symlinks followed, folders, disks and
  // sockets refused, a character device or a named pipe written in place (a pipe without
  // a reader refused at once). A file whose last line was cut (a run killed mid-line)
  // gets the missing newline first. Throws Error "PATH: cannot write: REASON".
  explicit AppendFile(const std::string& path);
  ~AppendFile();
  AppendFile(const AppendFile&) = delete;
  AppendFile& operator=(const AppendFile&) = delete;

  // Appends `line` and a newline in one write (O_APPEND: lines of concurrent writers do not
  // interleave). Throws Error "PATH: write failed: REASON" (a full disk, a reader gone).
  void append(const std::string& line);
  // Flushes what was written to the disk (fsync; a device or pipe needs none).
  void sync();
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
  bool cut_ = false;  // the last write failed part way through a line
};

}  // namespace meshsal
