#include "progress.h"

#include <cstdio>
#include <unistd.h>

namespace meshsal_cli {

bool stderr_is_terminal() { return isatty(fileno(stderr)) != 0; }

Progress::Progress(bool enabled) : enabled_(enabled) {}

Progress::~Progress() { finish(); }

void Progress::update(const char* stage, double fraction) {
  if (!enabled_) return;
  auto now = std::chrono::steady_clock::now();
  if (stage == last_stage_ && fraction < 1.0 && now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_stage_ = stage;
  last_draw_ = now;
  std::fprintf(stderr, "\r  %-24s %3d%%", stage, int(fraction * 100.0 + 0.5));
  std::fflush(stderr);
  drawn_ = true;
}

void Progress::finish() {
  if (!drawn_) return;
  std::fprintf(stderr, "\r%40s\r", "");
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace meshsal_cli
