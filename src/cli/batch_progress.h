// meshsal batch: the progress line on a terminal (stderr):
//   [3/10] bunny_36k.obj  gaussian sweep 42%  ~1 min 20 s left
// Time left: the mean time of the models computed so far times those still to compute
// (skipped models cost nothing); "" until one model is done.
#pragma once
#include <chrono>
#include <string>

namespace meshsal::cli {

// "45 s", "3 min 20 s", "2 h 5 min".
std::string duration_text(double seconds);

class BatchProgress {
 public:
  BatchProgress(bool enabled, size_t total);
  ~BatchProgress();
  // A model starts (done: models finished before it, skipped and failed included).
  void model(size_t done, const std::string& name);
  // Stage progress inside the current model; redrawn at most every 100 ms.
  void stage(const char* stage, double fraction);
  // A computed model took `seconds` (feeds the estimate).
  void computed(double seconds);
  // Models still to compute after the current one.
  void remaining(size_t models) { remaining_ = models; }
  void clear();  // erases the line (before other messages, and at the end)

 private:
  void draw(const std::string& text);
  bool enabled_;
  size_t total_, done_ = 0, remaining_ = 0, computed_ = 0;
  double computed_seconds_ = 0;
  std::string name_;
  size_t drawn_width_ = 0;
  std::chrono::steady_clock::time_point last_draw_{};
  std::chrono::steady_clock::time_point model_start_{};
};

}  // namespace meshsal::cli
