// meshsal: writing to a pipe without dying of SIGPIPE, for the writers (atomic_write.cpp,
// append_file.cpp) that may write to a named pipe named by the user.
#pragma once
#include <signal.h>
#include <time.h>

#include <cerrno>

namespace meshsal {

// Blocks SIGPIPE on this thread for the scope, so that writing to a pipe whose reader has
// gone fails with EPIPE instead of killing the process (the signal's disposition is the
// program's, not a library's, to change); a SIGPIPE raised meanwhile is taken off this
// thread before the old mask comes back.
class SigpipeBlocked {
 public:
  SigpipeBlocked() {
    sigemptyset(&pipe_);
    sigaddset(&pipe_, SIGPIPE);
    sigset_t pending;
    sigpending(&pending);
    was_pending_ = sigismember(&pending, SIGPIPE) == 1;
    pthread_sigmask(SIG_BLOCK, &pipe_, &old_);
  }
  ~SigpipeBlocked() {
    if (!was_pending_) {
      sigset_t pending;
      sigpending(&pending);
      if (sigismember(&pending, SIGPIPE) == 1) {
        const timespec zero{0, 0};
        while (sigtimedwait(&pipe_, nullptr, &zero) < 0 && errno == EINTR) {
        }
      }
    }
    pthread_sigmask(SIG_SETMASK, &old_, nullptr);
  }
  SigpipeBlocked(const SigpipeBlocked&) = delete;
  SigpipeBlocked& operator=(const SigpipeBlocked&) = delete;

 private:
  sigset_t pipe_, old_;
  bool was_pending_ = false;
};

}  // namespace meshsal
