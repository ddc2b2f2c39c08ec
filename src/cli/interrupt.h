// meshsal CLI: Ctrl-C. The first SIGINT sets a flag that every command passes to the
// library as its options' `cancel`: the work stops within a fraction of a second at a point
// where nothing is half-written, the command says "interrupted" and exits with 130 (batch
// first logs the model it was on and prints its summary). A second SIGINT ends the process
// at once, as without the handler. SIGTERM (`kill`, a job scheduler's stop) does the same,
// so a stopped out-of-core run removes its temporary folder too; not under mpirun, whose
// ranks must die at once when one aborts.
#pragma once
#include <atomic>

namespace meshsal_cli {

void install_interrupt_handler(bool terminate_too);

// The flag the first signal sets (never null).
const std::atomic<bool>* interrupt_flag();

// 128 + the signal that stopped the work (130 for SIGINT, 143 for SIGTERM), as a shell
// reports it.
int interrupted_exit();

}  // namespace meshsal_cli
