// meshsal: the process's peak resident memory, as the kernel counts it (VmHWM in
// /proc/self/status): what --memory-limit promises, --json reports and `bench` shows per stage.
#pragma once
#include <cstdint>

namespace meshsal {

// Bytes; 0 where /proc is not there. Never below a mark that restart_peak_resident()
// cleared: the whole process's peak, stage marks or not.
uint64_t peak_resident_bytes();

// The mark since the last restart (the process start if none): the current stage's peak.
uint64_t stage_peak_resident_bytes();

// Starts a new mark from the current resident size (Linux: "5" to /proc/self/clear_refs),
// after folding the old one into peak_resident_bytes(). False where that cannot be done.
bool restart_peak_resident();

// Whether StageClock measures each stage's own peak (restarting the mark as each stage
// begins). Off unless a program asks (meshsal bench): restarting the kernel's mark is a
// change other code in the process could notice.
void set_stage_peaks(bool on);
bool stage_peaks();

}  // namespace meshsal
