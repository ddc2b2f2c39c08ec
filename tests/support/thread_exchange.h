// Tests: N processes in threads exchanging through memory (meshsal::TileExchange): what
// MPI ranks do, without MPI; the library's own ranks in threads (tiles/thread_ranks.h).
#pragma once
#include <functional>

#include "meshsal/meshsal.h"
#include "tiles/thread_ranks.h"

namespace meshsal_test {

using ThreadExchange = meshsal::TileExchange;

// body(exchange) once per rank, each in its own thread, all joined; then the first
// exception a rank threw, if any (the others' next collective throws instead of waiting).
inline void run_ranks(int ranks, const std::function<void(ThreadExchange&)>& body) {
  meshsal::run_thread_ranks(ranks, body);
}

}  // namespace meshsal_test
