// meshsal CLI: Ctrl-C. The first SIGINT sets a flag that every command passes to the
// library as its options' `cancel`: the work stops within a fraction of a second at a point
// where nothing is half-written, the command says "interrupted" and exits with 130 (batch
// first logs the model it was on and prints its summary). A second SIGINT ends the process
// at once, as without the handler.
#pragma once
#include <atomic>

namespace meshsal_cli {

void install_interrupt_handler();

// The flag the first SIGINT sets (never null).
const std::atomic<bool>* interrupt_flag();

constexpr int kInterruptedExit = 130;  // 128 + SIGINT, as a shell reports it

}  // namespace meshsal_cli
