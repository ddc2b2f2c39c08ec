#include "interrupt.h"

#include <signal.h>

namespace meshsal_cli {
namespace {

std::atomic<bool> interrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free, "set from a signal handler");

void on_sigint(int) {
  interrupted.store(true);
  signal(SIGINT, SIG_DFL);  // the next Ctrl-C stops the process at once
}

}  // namespace

void install_interrupt_handler() {
  struct sigaction sa {};
  sa.sa_handler = on_sigint;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  // A shell runs background jobs with SIGINT ignored: keep that.
  struct sigaction old {};
  if (sigaction(SIGINT, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) return;
  sigaction(SIGINT, &sa, nullptr);
}

const std::atomic<bool>* interrupt_flag() { return &interrupted; }

}  // namespace meshsal_cli
