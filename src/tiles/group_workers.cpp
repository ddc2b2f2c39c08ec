#include "tiles/group_workers.h"

#include <algorithm>
#include <atomic>
#include <numeric>

#include "core/parallel.h"
#include "tiles/pass_exchange.h"

namespace meshsal {
namespace detail {

GroupWorkers group_workers(unsigned threads, unsigned concurrent, size_t groups) {
  const unsigned t = resolve_threads(threads);
  GroupWorkers w;
  w.workers = unsigned(std::max<size_t>(1, std::min<size_t>({size_t(t), concurrent ? size_t(concurrent) : t, groups})));
  w.inner = std::max(1u, t / w.workers);
  return w;
}

void for_each_group(const TileExchange* exchange, const std::vector<size_t>& sizes, unsigned workers,
                    const std::function<void(size_t g, unsigned worker)>& body) {
  std::vector<size_t> order;
  for (size_t g = 0; g < sizes.size(); ++g)
    if (runs_group(exchange, g)) order.push_back(g);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return sizes[a] > sizes[b]; });
  std::atomic<size_t> next{0};
  std::atomic<bool> failed{false};
  // One parallel_for item per worker, each taking the next group until none is left (or
  // one failed: parallel_for rethrows it).
  parallel_for(std::max(1u, workers), std::max(1u, workers), 1, [&](size_t w0, size_t w1) {
    for (size_t w = w0; w < w1; ++w)
      for (size_t i; !failed && (i = next.fetch_add(1)) < order.size();) {
        try {
          body(order[i], unsigned(w));
        } catch (...) {
          failed = true;
          throw;
        }
      }
  });
}

}  // namespace detail
}  // namespace meshsal
