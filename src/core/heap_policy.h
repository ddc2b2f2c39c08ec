// meshsal: how the command-line program asks the C library to manage its heap.
#pragma once

namespace meshsal {

// A saliency run allocates and frees arrays of tens of MB stage after stage. glibc maps
// each large block afresh and gives it back when freed, so every stage pays the page
// faults again (igea_loop2 --method fast: 310,000 faults, 2.6 s of system time). This
// keeps freed blocks in the heap for the next stage (110,000 faults, 1.0 s; peak memory
// about 4% higher). Process-wide, so it is for programs (the CLI), not for the library.
// Does nothing on other C libraries.
void keep_freed_memory_for_reuse();

}  // namespace meshsal
