// meshsal: what a loader tells while it still reads, so that work on the part already read
// can overlap the rest of the read (the GPU path uploads a PLY's positions while its faces
// are parsed: api/read_upload.h).
//
// The calls come on the reading thread: positions_read and triangles_read at most once
// each, read_ended once or more. The arrays they name are the mesh's own. The loader calls read_ended(false) before it throws (the mesh is dropped) or
// changes them (positions made early at another origin: core/model_frame.h's
// EarlyPositions): the observer must read them no more once that returns. It calls
// read_ended(true) as it returns the mesh: the arrays live on, unchanged, in the mesh
// returned, and the observer may go on reading them for as long as their owner (who
// gave the observer to the loader) lets it.
#pragma once
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>

#include "meshsal/meshsal.h"

namespace meshsal {

class ReadObserver {
 public:
  virtual ~ReadObserver() = default;
  // Mesh::positions as the mesh will have them (3 floats a vertex), before the faces are
  // read; or as they may be: nearly always (see EarlyPositions).
  virtual void positions_read(const float* positions, size_t vertex_count) = 0;
  // Mesh::triangles as the mesh will have them (3 indices each); not told where the
  // positions told are made again.
  virtual void triangles_read(const uint32_t* triangles, size_t triangle_count) = 0;
  // The read is over: `returned`, with the mesh the arrays belong to; otherwise the
  // arrays are about to change or go, and this returns once the observer reads them no
  // more. Called at least once; after a read_ended(false), later calls return at once.
  virtual void read_ended(bool returned) noexcept = 0;
};

// Ends `observer` (may be null) when the scope is left, before a mesh declared ahead of
// it is dropped: read_ended(false) when an exception leaves it, read_ended(true) on a
// return unless `on_throw` alone.
class EndObserver {
 public:
  explicit EndObserver(ReadObserver* observer, bool on_throw = false)
      : observer_(observer), on_throw_(on_throw), exceptions_(std::uncaught_exceptions()) {}
  ~EndObserver() {
    if (!observer_) return;
    if (std::uncaught_exceptions() > exceptions_) observer_->read_ended(false);
    else if (!on_throw_) observer_->read_ended(true);
  }
  EndObserver(const EndObserver&) = delete;
  EndObserver& operator=(const EndObserver&) = delete;

 private:
  ReadObserver* observer_;
  bool on_throw_;
  int exceptions_;
};

// read_mesh (meshsal.h) telling `observer` (may be null) what it has read while it reads.
// PLY alone tells anything yet: the format of large scans, whose vertices come before the
// faces; the other formats only end the observer.
LoadedMesh read_mesh_observed(const std::string& path, const LoadOptions& options, ReadObserver* observer);

}  // namespace meshsal
