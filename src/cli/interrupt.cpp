#include "interrupt.h"

#include <signal.h>

namespace meshsal::cli {
namespace {

std::atomic<bool> interrupted{false};
std::atomic<int> first_signal{SIGINT};
static_assert(std::atomic<bool>::is_always_lock_free, "set from a signal handler");
static_assert(std::atomic<int>::is_always_lock_free, "set from a signal handler");

void on_signal(int sig) {
  if (!interrupted.exchange(true)) first_signal.store(sig);
  // The next one stops the process at once; not SIGPIPE, which every later write to the
  // pipe raises again while the command winds down (they fail with EPIPE instead).
  if (sig != SIGPIPE) signal(sig, SIG_DFL);
}

void install(int sig) {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  // A shell runs background jobs with SIGINT ignored, nohup with SIGHUP: keep that.
  struct sigaction old {};
  if (sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) return;
  sigaction(sig, &sa, nullptr);
}

}  // namespace

void install_interrupt_handler(bool all_signals) {
  install(SIGINT);
  if (!all_signals) return;
  static const int others[] = {SIGTERM, SIGHUP, SIGQUIT, SIGPIPE, SIGUSR1, SIGUSR2, SIGALRM, SIGXCPU, SIGXFSZ,
#ifdef SIGPWR
                               SIGPWR,
#endif
  };
  for (int sig : others) install(sig);
}

int interrupted_exit() { return 128 + first_signal.load(); }

const std::atomic<bool>* interrupt_flag() { return &interrupted; }

}  // namespace meshsal::cli
