#include "core/id_ranks.h"

#include "core/radix_sort.h"

namespace meshsal {

void rank_ids(const uint32_t* ids, size_t n, uint32_t max_id, std::vector<uint32_t>& distinct,
              std::vector<uint32_t>& rank, unsigned threads) {
  std::vector<uint32_t> key(ids, ids + n), at(n);
  for (size_t i = 0; i < n; ++i) at[i] = uint32_t(i);
  radix_sort(key, at, max_id, threads);
  distinct.clear();
  rank.resize(n);
  for (size_t j = 0; j < n; ++j) {
    if (j == 0 || key[j] != key[j - 1]) distinct.push_back(key[j]);
    rank[at[j]] = uint32_t(distinct.size() - 1);
  }
}

}  // namespace meshsal
