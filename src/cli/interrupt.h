// meshsal CLI: signals. The first SIGINT (Ctrl-C) sets a flag that every command passes to
// the library as its options' `cancel`: the work stops within a fraction of a second at a
// point where nothing is half-written, the command says "interrupted" and exits with 128 +
// the signal (130 for SIGINT; batch first logs the model it was on and prints its summary).
// A second one ends the process at once, as without the handler. Every other signal whose
// default is to end the process and that a person or a system sends (SIGTERM from `kill`
// or a job scheduler, SIGHUP from a closed terminal, SIGQUIT, SIGPIPE from a reader gone,
// SIGUSR1/2, SIGALRM, SIGXCPU, SIGXFSZ, SIGPWR) does the same, so an out-of-core run removes
// its temporary folder whatever stops it; a crash (SIGSEGV, abort) cannot, and SIGKILL
// neither: a later run removes what they leave (tiles/scratch_lock.h). Under mpirun only
// SIGINT: the ranks must die at once when one aborts (mpirun sends them SIGTERM), and a
// rank waiting in a collective would never see the flag.
#pragma once
#include <atomic>

namespace meshsal::cli {

// SIGINT, and with `all_signals` the others above. A signal a shell set to be ignored
// (SIGINT in a background job, SIGHUP under nohup) stays ignored.
void install_interrupt_handler(bool all_signals);

// The flag the first signal sets (never null).
const std::atomic<bool>* interrupt_flag();

// 128 + the signal that stopped the work (130 for SIGINT, 143 for SIGTERM), as a shell
// reports it.
int interrupted_exit();

}  // namespace meshsal::cli
