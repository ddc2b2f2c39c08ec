// meshsal: the one way every output file (meshes, PNG pictures) is written.
#pragma once
#include <cstddef>
#include <cstdio>
#include <functional>
#include <string>

namespace meshsal {

// Writes `path` through a fresh temporary file in the same folder (mkstemp: never a fixed
// name, so a symlink planted there is not followed and two writers never share one):
// `body` writes into it (with write_all), then it is flushed, synced, closed and renamed
// over `path`. It gets the mode of the file it replaces, else 0666 minus the umask (not
// mkstemp's 0600). On any failure the temporary file is removed, `path` is left as it was,
// and the Error names `path` ("PATH: write failed: No space left on device").
void write_file_atomically(const std::string& path, const std::function<void(std::FILE*)>& body);

// Writes n bytes to f; throws Error "PATH: write failed: REASON" when fewer went out.
void write_all(std::FILE* f, const void* data, size_t n, const std::string& path);

}  // namespace meshsal
