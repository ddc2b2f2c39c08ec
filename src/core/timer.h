// meshsal: wall-clock seconds since a start, for stage timings and reports (one clock for
// the library, the command line and the benchmarks).
#pragma once
#include <chrono>

namespace meshsal {

class Timer {
 public:
  Timer() : t0_(std::chrono::steady_clock::now()) {}
  // Seconds since construction or the last restart().
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
  }
  void restart() { t0_ = std::chrono::steady_clock::now(); }

 private:
  std::chrono::steady_clock::time_point t0_;
};

}  // namespace meshsal
