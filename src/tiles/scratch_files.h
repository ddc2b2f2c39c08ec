// meshsal: the out-of-core path's files on disk: a private temporary folder removed with
// everything in it when the run ends (an error or Ctrl-C included), locked while it lives so
// that a later run removes it should the process die without doing so (scratch_lock.h), and
// plain binary readers and writers with every failure named.
#pragma once
#include <cstdint>
#include <cstring>
#include <cstdio>
#include <string>
#include <vector>

namespace meshsal {

class ScratchDir {
 public:
  // A new folder meshsal-tiles-XXXXXX in `parent` ("" = $TMPDIR or /tmp), locked; first
  // the stale ones there are removed (note() says what was found).
  explicit ScratchDir(const std::string& parent);
  // Another's folder from the start, never removed by us (ranks in threads of one process:
  // no folder of their own is made).
  struct Borrowed {};
  ScratchDir(const std::string& path, Borrowed) : path_(path), owner_(false) {}
  // Use another process's folder instead (MPI ranks on a shared disk): this one is
  // removed now, that one never by us.
  void borrow(const std::string& path);
  ~ScratchDir();
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  std::string file(const std::string& name) const { return path_ + "/" + name; }
  const std::string& path() const { return path_; }
  // One line for a person about stale folders found in the parent ("" when none): for the
  // call's notice.
  const std::string& note() const { return note_; }

 private:
  void remove();
  std::string path_, note_;
  bool owner_ = true;
  int lock_ = -1;  // held open (and locked) while the folder is ours
};

// Appends to a file through a buffer.
class ScratchWriter {
 public:
  explicit ScratchWriter(const std::string& path, bool append = false);
  // Writes into an existing file from byte `offset` on, the rest of it kept (ranks each
  // write their range of one file).
  ScratchWriter(const std::string& path, uint64_t offset);
  ~ScratchWriter();
  void write(const void* data, size_t bytes);
  template <class T>
  void write_vector(const std::vector<T>& v) { write(v.data(), v.size() * sizeof(T)); }
  void close();  // flushes; throws on a failed write (a full disk)

 private:
  std::string path_;
  std::FILE* f_ = nullptr;
};

// Reads a file front to back.
class ScratchReader {
 public:
  explicit ScratchReader(const std::string& path);
  ~ScratchReader();
  // Up to `bytes` bytes; how many were read (0 at the end).
  size_t read(void* to, size_t bytes);
  void read_exact(void* to, size_t bytes);
  void seek(uint64_t offset);

 private:
  std::string path_;
  std::FILE* f_ = nullptr;
};

// The whole file (a tile's spilled state).
std::vector<uint8_t> read_scratch_file(const std::string& path);

// The whole file's records of type T appended to `into` (a bucket's faces, a group's ids).
template <class T>
void append_scratch_records(const std::string& path, std::vector<T>& into) {
  const std::vector<uint8_t> bytes = read_scratch_file(path);
  const size_t n = bytes.size() / sizeof(T), at = into.size();
  into.resize(at + n);
  if (n) std::memcpy(into.data() + at, bytes.data(), n * sizeof(T));  // (empty: no pointers to copy)
}

// Values at sorted, distinct indices of a file of fixed-size records (the positions file):
// read in windows of nearby records, so a tile's vertices cost few reads; a long list in
// parts on `threads` threads (0 = all cores).
void read_records(const std::string& path, size_t record_bytes, const std::vector<uint32_t>& sorted,
                  void* out, unsigned threads = 1);

// Record i of `data` written over record ids[i] of an existing file (in place: the file
// keeps its size where ids stay inside it).
void write_records(const std::string& path, size_t record_bytes, const std::vector<uint32_t>& ids, const void* data);

}  // namespace meshsal
