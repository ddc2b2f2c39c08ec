#include "tiles/background_write.h"

#include <system_error>
#include <utility>

namespace meshsal {

BackgroundWrite::~BackgroundWrite() {
  if (thread_.joinable()) thread_.join();
}

void BackgroundWrite::submit(std::function<void()> write) {
  finish();
  write_ = std::move(write);  // (held here, not copied into the thread: it owns a tile's data)
  auto run = [this] {
    try {
      write_();
    } catch (...) {
      error_ = std::current_exception();
    }
    write_ = nullptr;  // the tile's data freed as soon as it is written
  };
  try {
    thread_ = std::thread(run);
  } catch (const std::system_error&) {
    run();  // no thread to be had: write now
    finish();
  }
}

void BackgroundWrite::finish() {
  if (thread_.joinable()) thread_.join();
  if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
}

}  // namespace meshsal
