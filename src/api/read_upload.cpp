// meshsal: the device's warm-up and the mesh's upload while a run reads (read_upload.h).
#include "api/read_upload.h"

#include <system_error>

#include "api/gpu_backend.h"
#include "core/cancel.h"
#include "core/timer.h"

namespace meshsal {

ReadUpload::ReadUpload(const SaliencyOptions& options) : options_(options), resolved_(options) {
  try {
    thread_ = std::thread([this] { run(); });
  } catch (const std::system_error&) {
    // No thread to spare (a process limit): the run opens the device itself.
  }
}

ReadUpload::~ReadUpload() {
  read_ended(false);
  if (thread_.joinable()) thread_.join();
  if (uploaded_) {
    try {
      linked_gpu_backend()->drop_prestaged(resolved_);
    } catch (...) {  // the device is gone: so is what it held
    }
  }
}

void ReadUpload::positions_read(const float* positions, size_t vertex_count) {
  std::lock_guard<std::mutex> hold(lock_);
  positions_ = positions;
  vertex_count_ = vertex_count;
  changed_.notify_all();
}

void ReadUpload::triangles_read(const uint32_t* triangles, size_t triangle_count) {
  std::lock_guard<std::mutex> hold(lock_);
  triangles_ = triangles;
  triangle_count_ = triangle_count;
  changed_.notify_all();
}

void ReadUpload::read_ended(bool returned) noexcept {
  std::unique_lock<std::mutex> hold(lock_);
  if (returned) {
    returned_ = true;
    changed_.notify_all();
    return;
  }
  ended_ = true;
  changed_.notify_all();
  changed_.wait(hold, [this] { return !uploading_; });
}

bool ReadUpload::join(SaliencyOptions& resolved, double& waited, double& uploading) {
  read_ended(true);  // where the reader said nothing (a read that tells nothing)
  if (!thread_.joinable()) return false;
  const Timer wait;
  thread_.join();
  waited = wait.seconds();
  uploading = uploading_seconds_;
  resolved = resolved_;
  return true;
}

const void* ReadUpload::next(bool& positions, size_t& count) {
  positions = positions_ != nullptr;  // the positions first: they were told first
  count = positions ? vertex_count_ : triangle_count_;
  const void* p = positions ? static_cast<const void*>(positions_) : triangles_;
  if (positions) positions_ = nullptr;
  else triangles_ = nullptr;
  return p;
}

void ReadUpload::run() {
  CancelScope scope(options_.cancel);  // a cancelled read ends the warm-up too
  const SaliencyOptions warmed = warm_up_saliency(options_);
  {
    std::lock_guard<std::mutex> hold(lock_);
    resolved_ = warmed;
  }
  // Nothing to upload ahead where no GPU will compute (the CPU, or Auto's pick of it).
  if (warmed.backend == Backend::Cpu || !linked_gpu_backend()) return;
  const GpuBackend& gpu = *linked_gpu_backend();
  for (;;) {
    bool positions = false;
    size_t count = 0;
    const void* data = nullptr;
    {
      std::unique_lock<std::mutex> hold(lock_);
      changed_.wait(hold, [&] { return ended_ || returned_ || positions_ || triangles_; });
      if (ended_) return;
      data = next(positions, count);
      if (!data) return;  // returned, and everything told is uploaded
      uploading_ = true;
    }
    bool failed = false, uploaded = false;
    const Timer took;
    try {
      uploaded = positions ? gpu.prestage_positions(warmed, static_cast<const float*>(data), count)
                           : gpu.prestage_triangles(warmed, static_cast<const uint32_t*>(data), count);
    } catch (...) {
      failed = true;  // the run uploads it, and meets the failure if it is the device's
    }
    std::lock_guard<std::mutex> hold(lock_);
    uploading_ = false;
    uploaded_ = true;  // (a failure may leave one array held: the destructor frees it)
    if (uploaded) uploading_seconds_ += took.seconds();
    changed_.notify_all();
    if (failed) return;
  }
}

}  // namespace meshsal
