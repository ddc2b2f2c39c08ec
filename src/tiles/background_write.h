// meshsal: a tile's files written on a thread of their own while the next tile is computed
// (out of core, most of a tile's phase C and a tenth of its phase 1 were its writes, with a
// core idle meanwhile). One write at a time: submit() first waits for the last one, so a
// tile's outputs are held at most until the next tile's are ready.
#pragma once
#include <exception>
#include <functional>
#include <thread>

namespace meshsal {

class BackgroundWrite {
 public:
  BackgroundWrite() = default;
  BackgroundWrite(const BackgroundWrite&) = delete;
  BackgroundWrite& operator=(const BackgroundWrite&) = delete;
  // Waits for the last write (its error, if any, lost: call finish() to hear it).
  ~BackgroundWrite();
  // Waits for the last write (rethrowing its error), then starts `write` (on this thread
  // where no thread can be started).
  void submit(std::function<void()> write);
  // Waits for the last write; rethrows its error.
  void finish();

 private:
  std::function<void()> write_;  // the write under way
  std::thread thread_;
  std::exception_ptr error_;
};

}  // namespace meshsal
