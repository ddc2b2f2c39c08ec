// meshsal batch: BatchProgress (see batch_progress.h).
#include "batch_progress.h"
#include "json_string.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace meshsal::cli {

std::string duration_text(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char buf[48];
  if (s < 60)
    std::snprintf(buf, sizeof buf, "%ld s", s);
  else if (s < 3600)
    std::snprintf(buf, sizeof buf, "%ld min %ld s", s / 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%ld h %ld min", s / 3600, (s % 3600) / 60);
  return buf;
}

BatchProgress::BatchProgress(bool enabled, size_t total) : enabled_(enabled), total_(total) {}

BatchProgress::~BatchProgress() { clear(); }

void BatchProgress::model(size_t done, const std::string& name) {
  done_ = done;
  name_ = name;
  model_start_ = std::chrono::steady_clock::now();
  last_draw_ = {};
  stage("reading", 0);
}

void BatchProgress::computed(double seconds) {
  computed_++;
  computed_seconds_ += seconds;
}

void BatchProgress::stage(const char* stage, double fraction) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  char buf[512];
  std::snprintf(buf, sizeof buf, "[%zu/%zu] %s  %s %3d%%", done_ + 1, total_, printable(name_).c_str(), stage,
                int(fraction * 100.0 + 0.5));
  std::string text = buf;
  if (computed_ > 0) {
    // The current model's own remaining share is guessed from its elapsed time.
    const double mean = computed_seconds_ / double(computed_);
    const double elapsed = std::chrono::duration<double>(now - model_start_).count();
    text += "  ~" + duration_text(double(remaining_) * mean + std::max(0.0, mean - elapsed)) + " left";
  }
  draw(text);
}

void BatchProgress::draw(const std::string& text) {
  std::string line = "\r" + text;
  if (text.size() < drawn_width_) line += std::string(drawn_width_ - text.size(), ' ');
  drawn_width_ = text.size();
  std::fputs(line.c_str(), stderr);
  std::fflush(stderr);
}

void BatchProgress::clear() {
  if (!enabled_ || drawn_width_ == 0) return;
  std::fprintf(stderr, "\r%s\r", std::string(drawn_width_, ' ').c_str());
  std::fflush(stderr);
  drawn_width_ = 0;
}

}  // namespace meshsal::cli
