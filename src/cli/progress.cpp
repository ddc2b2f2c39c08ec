#include "progress.h"

#include <cstdio>
#include <unistd.h>

namespace meshsal::cli {

bool stderr_is_terminal() { return isatty(fileno(stderr)) != 0; }

Progress::Progress(bool enabled) : enabled_(enabled) {}

Progress::~Progress() { finish(); }

void Progress::update(const char* stage, double fraction) {
  if (!enabled_) return;
  auto now = std::chrono::steady_clock::now();
  if (stage == last_stage_ && fraction < 1.0 && now - last_draw_ < std::chrono::milliseconds(100)) return;
  if (stage != last_stage_) stage_start_ = now;
  last_stage_ = stage;
  last_draw_ = now;
  // Time left in this stage, from its pace so far (once there is a pace to go by: the
  // tiles of an out-of-core run take minutes).
  const double spent = std::chrono::duration<double>(now - stage_start_).count();
  char left[32] = "";
  if (fraction > 0.02 && fraction < 1.0 && spent > 2.0)
    std::snprintf(left, sizeof left, ", %.0f s left", spent / fraction * (1.0 - fraction));
  std::fprintf(stderr, "\r  %-24s %3d%%%-16s", stage, int(fraction * 100.0 + 0.5), left);
  std::fflush(stderr);
  drawn_ = true;
}

void Progress::finish() {
  if (!drawn_) return;
  std::fprintf(stderr, "\r%56s\r", "");
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace meshsal::cli
