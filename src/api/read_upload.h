// meshsal (internal to api/): what a front end's run does on a second thread while it
// reads its input, for S computed on a GPU: the device opened, the pipelines compiled and
// the probes run (warm_up_saliency), then the mesh's float positions and triangles
// uploaded as the reader tells of them (io/read_observer.h, gpu/gpu_prestage.h), so that
// the upload overlaps the rest of the read and the computation starts with the mesh on
// the device. Either part only saves time: a failure is left for the run to meet.
#pragma once
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <thread>

#include "io/read_observer.h"
#include "meshsal/meshsal.h"

namespace meshsal {

class ReadUpload final : public ReadObserver {
 public:
  // Starts the thread (none where the process may start no more: the run then opens the
  // device itself). `options`: the run's, as warm_up_saliency takes them.
  explicit ReadUpload(const SaliencyOptions& options);
  // Joins the thread, and frees what was uploaded and no run took.
  ~ReadUpload();
  ReadUpload(const ReadUpload&) = delete;
  ReadUpload& operator=(const ReadUpload&) = delete;

  void positions_read(const float* positions, size_t vertex_count) override;
  void triangles_read(const uint32_t* triangles, size_t triangle_count) override;
  // `returned`: the arrays told of are uploaded still (join waits for them); otherwise
  // waits for an upload under way, and no other starts.
  void read_ended(bool returned) noexcept override;

  // After the read, before the mesh read changes or goes: waits for the thread, the
  // warm-up and the uploads of what the reader told of (the seconds it waited go to
  // `waited`, those it spent uploading to `uploading`), and gives the options
  // warm_up_saliency resolved (Auto's device). False where no thread ran.
  bool join(SaliencyOptions& resolved, double& waited, double& uploading);

 private:
  void run();
  // The next array to upload (null: none now), taken under the lock.
  const void* next(bool& positions, size_t& count);

  std::mutex lock_;
  std::condition_variable changed_;
  const float* positions_ = nullptr;
  const uint32_t* triangles_ = nullptr;
  size_t vertex_count_ = 0, triangle_count_ = 0;
  bool ended_ = false;      // read_ended(false), or the destructor: no upload starts
  bool returned_ = false;   // read_ended(true): what was told is uploaded, then the thread ends
  bool uploading_ = false;  // an upload reads the reader's arrays
  bool uploaded_ = false;   // something went to the device (freed unless a run took it)
  double uploading_seconds_ = 0;
  SaliencyOptions options_, resolved_;
  std::thread thread_;
};

}  // namespace meshsal
