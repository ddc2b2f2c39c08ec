// meshsal: cooperative cancellation. A public call whose options carry a cancel flag
// (SaliencyOptions::cancel, ...) opens a CancelScope on its thread; the long loops poll it:
// parallel_for before every chunk (on every worker), the simplifier every few thousand
// collapses, the GPU paths between submissions, the viewpoint search between batches.
// So a set flag stops the call within a fraction of a second with meshsal::Cancelled,
// without every internal function taking the flag as a parameter.
#pragma once
#include <atomic>

namespace meshsal {

// Makes `flag` the current call's cancel flag on this thread for the scope. A null flag
// keeps the enclosing scope's (a public function calling another).
class CancelScope {
 public:
  explicit CancelScope(const std::atomic<bool>* flag);
  ~CancelScope();
  CancelScope(const CancelScope&) = delete;
  CancelScope& operator=(const CancelScope&) = delete;

 private:
  const std::atomic<bool>* saved_;
};

// This thread's current cancel flag (null outside any scope with one).
const std::atomic<bool>* current_cancel_flag();

// Throws meshsal::Cancelled when the current flag is set.
void throw_if_cancelled();

}  // namespace meshsal
