// meshsal: ranks in threads of one process, exchanging through memory (a TileExchange): the
// tile store's passes, written for ranks, run on the cores of one process (each thread
// reads its share of the input as an MPI rank would). The tests run their ranks so too.
#pragma once
#include <functional>

#include "meshsal/meshsal.h"

namespace meshsal {

// body(exchange) once per rank, each on a thread of its own, all joined; then the first
// exception a rank threw, if any. A rank that ends by an exception breaks the exchange:
// the others' next all_gather throws instead of waiting for it.
void run_thread_ranks(int ranks, const std::function<void(TileExchange&)>& body);

}  // namespace meshsal
