// meshsal CLI: progress on a terminal for long stages (silent when stderr is not a tty).
#pragma once
#include <chrono>
#include <string>

namespace meshsal::cli {

class Progress {
 public:
  explicit Progress(bool enabled);
  ~Progress();
  // Shows "stage  42%, 12 s left"; redraws at most every 100 ms.
  void update(const char* stage, double fraction);
  void finish();  // clears the line

 private:
  bool enabled_;
  bool drawn_ = false;
  std::string last_stage_;
  std::chrono::steady_clock::time_point last_draw_{};
  std::chrono::steady_clock::time_point stage_start_{};
};

// True when stderr is a terminal (progress is only drawn there).
bool stderr_is_terminal();

}  // namespace meshsal::cli
