// meshsal Python module: Ctrl-C during a library call. Python runs its SIGINT handler (and
// raises KeyboardInterrupt) only when the main thread is back in the interpreter, so a long
// call would hold it off until it returns. An InterruptibleCall, made on the main thread,
// releases the GIL and chains a C handler in front of Python's for the call: a SIGINT sets
// the call's cancel flag (SaliencyOptions::cancel, ...), so the library stops within a
// fraction of a second, and is passed on to Python's handler; the module then raises
// KeyboardInterrupt (translate_cancelled). Calls on other threads only release the GIL:
// Python interrupts the main thread alone.
#pragma once
#include <atomic>

namespace meshsal_py {

class InterruptibleCall {
 public:
  InterruptibleCall();   // with the GIL held: releases it
  ~InterruptibleCall();  // takes it back
  InterruptibleCall(const InterruptibleCall&) = delete;
  InterruptibleCall& operator=(const InterruptibleCall&) = delete;

  // For the call's options' `cancel`: null off the main thread (or with SIGINT ignored).
  const std::atomic<bool>* flag() const { return armed_ ? &flag_ : nullptr; }

 private:
  std::atomic<bool> flag_{false};
  bool armed_ = false;
  void* saved_thread_state_ = nullptr;
};

// With the GIL held, after a call stopped with meshsal::Cancelled: runs Python's pending
// signal handlers (the default one raises KeyboardInterrupt) and makes sure an exception
// is set (KeyboardInterrupt when the handlers raised none).
void translate_cancelled();

}  // namespace meshsal_py
