#include "peak_memory.h"

#include <cstdio>
#include <cstring>

namespace meshsal_cli {

uint64_t peak_resident_bytes() {
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

}  // namespace meshsal_cli
