// meshsal CLI: the process's peak resident memory, as the kernel counts it (VmHWM in
// /proc/self/status): what --memory-limit promises and --json reports.
#pragma once
#include <cstdint>

namespace meshsal_cli {

// Bytes; 0 where /proc is not there.
uint64_t peak_resident_bytes();

}  // namespace meshsal_cli
