// meshsal: the wall time of each stage of a call, appended to its report's stages as each
// stage ends (SaliencyResult, OutOfCoreReport, OutOfCoreSimplifyReport).
#pragma once
#include <vector>

#include "core/timer.h"
#include "meshsal/meshsal.h"

namespace meshsal {

class StageClock {
 public:
  explicit StageClock(std::vector<StageTime>& stages) : stages_(stages) {}
  // The stage that ends now: its name and the seconds since the last lap (or the start).
  void lap(const char* name) {
    stages_.push_back({name, timer_.seconds()});
    timer_.restart();
  }

 private:
  std::vector<StageTime>& stages_;
  Timer timer_;
};

}  // namespace meshsal
