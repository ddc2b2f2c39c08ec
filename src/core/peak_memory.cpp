#include "core/peak_memory.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstring>

namespace meshsal {

namespace {

std::atomic<uint64_t> g_before_restart{0};  // the largest mark a restart cleared
std::atomic<bool> g_stage_peaks{false};

}  // namespace

uint64_t stage_peak_resident_bytes() {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return 0;
  char line[256];
  unsigned long long kb = 0;
  while (std::fgets(line, sizeof line, f))
    if (std::strncmp(line, "VmHWM:", 6) == 0) {
      std::sscanf(line + 6, "%llu", &kb);
      break;
    }
  std::fclose(f);
  return uint64_t(kb) * 1024;
}

uint64_t peak_resident_bytes() {
  return std::max(stage_peak_resident_bytes(), g_before_restart.load());
}

bool restart_peak_resident() {
  const uint64_t mark = stage_peak_resident_bytes();
  uint64_t seen = g_before_restart.load();
  while (mark > seen && !g_before_restart.compare_exchange_weak(seen, mark)) {
  }
  std::FILE* f = std::fopen("/proc/self/clear_refs", "w");
  if (!f) return false;
  const bool ok = std::fputs("5", f) >= 0;
  return std::fclose(f) == 0 && ok;
}

void set_stage_peaks(bool on) { g_stage_peaks = on; }
bool stage_peaks() { return g_stage_peaks; }

}  // namespace meshsal
