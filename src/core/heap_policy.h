// meshsal: how a program may ask the C library to manage its heap. The library never calls
// this itself: it is process-wide, so it is the application's choice (the meshsal command
// makes it at start-up; Python programs call meshsal.keep_freed_memory()).
#pragma once

namespace meshsal {

// A saliency run allocates and frees arrays of tens of MB stage after stage. glibc maps
// each large block afresh and gives it back when freed, so every stage pays the page
// faults again (igea_loop2 --method fast: 310,000 faults, 2.6 s of system time). on = true
// keeps freed blocks in the heap for the next stage (110,000 faults, 1.0 s; peak memory
// about 4% higher): large blocks come from the heap (M_MMAP_MAX 0) and its free top is not
// given back (M_TRIM_THRESHOLD INT_MAX). on = false sets glibc's documented default values
// back (M_MMAP_MAX 65536, M_TRIM_THRESHOLD 128 KiB; glibc's dynamic mmap threshold stays
// off once either was set). Returns false, changing nothing, on other C libraries.
bool keep_freed_memory_for_reuse(bool on = true);

}  // namespace meshsal
