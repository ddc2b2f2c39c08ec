#include "core/cancel.h"

#include "meshsal/meshsal.h"

namespace meshsal {
namespace {

// Per thread and restored by each scope's end: calls on other threads have their own.
thread_local const std::atomic<bool>* current = nullptr;

}  // namespace

CancelScope::CancelScope(const std::atomic<bool>* flag) : saved_(current) {
  if (flag) current = flag;
}

CancelScope::~CancelScope() { current = saved_; }

const std::atomic<bool>* current_cancel_flag() { return current; }

void throw_if_cancelled() {
  if (current && current->load(std::memory_order_relaxed)) throw Cancelled("cancelled");
}

}  // namespace meshsal
