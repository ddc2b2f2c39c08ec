// meshsal: the wall time of each stage of a call, appended to its report's stages as each
// stage ends (SaliencyResult, OutOfCoreReport, OutOfCoreSimplifyReport), and with
// stage_peaks() on (meshsal bench) the peak resident memory of each stage.
#pragma once
#include <vector>

#include "core/peak_memory.h"
#include "core/timer.h"
#include "meshsal/meshsal.h"

namespace meshsal {

class StageClock {
 public:
  explicit StageClock(std::vector<StageTime>& stages) : stages_(stages) {
    if (stage_peaks()) restart_peak_resident();
  }
  // The stage that ends now: its name, the seconds since the last lap (or the start) and
  // its peak memory (0 unless stage_peaks()).
  void lap(const char* name) {
    const double seconds = timer_.seconds();
    uint64_t peak = 0;
    if (stage_peaks()) {
      peak = stage_peak_resident_bytes();
      restart_peak_resident();
    }
    stages_.push_back({name, seconds, peak});
    timer_.restart();
  }
  // The next stage starts now: the time since the last lap was recorded elsewhere (a call
  // that laps its own stages into the same report), so that the stages add up.
  void resume() { timer_.restart(); }

 private:
  std::vector<StageTime>& stages_;
  Timer timer_;
};

}  // namespace meshsal
