#include "saliency/query_groups.h"

#include <algorithm>
#include <numeric>

#include "core/radix_sort.h"
#include "meshsal/meshsal.h"

namespace meshsal {

namespace {

struct Coarse {
  uint64_t f, dx, dy, gx, gy, gz;
  explicit Coarse(const uint64_t dims[3], int factor)
      : f(uint64_t(factor)), dx(dims[0]), dy(dims[1]), gx((dims[0] + f - 1) / f),
        gy((dims[1] + f - 1) / f), gz((dims[2] + f - 1) / f) {}
  uint64_t key(uint64_t k) const {
    const uint64_t x = k % dx, y = k / dx % dy, z = k / dx / dy;
    return ((z / f) * gy + y / f) * gx + x / f;
  }
};

// Runs of equal coarse keys (sorted) as groups.
void close_groups(const std::vector<uint64_t>& coarse, sweep::QueryGroups& gr) {
  for (size_t c = 0; c < coarse.size(); ++c)
    if (c == 0 || coarse[c] != coarse[c - 1]) gr.start.push_back(uint32_t(c));
  gr.start.push_back(uint32_t(coarse.size()));
}

template <class Key>
sweep::QueryGroups group(const std::vector<Key>& keys, const uint64_t dims[3], int factor,
                         unsigned threads) {
  if (factor < 1) throw Error("internal: query groups need a factor of at least 1");
  sweep::QueryGroups gr;
  const size_t m = keys.size();
  gr.cell.resize(m);
  std::iota(gr.cell.begin(), gr.cell.end(), 0u);
  if (factor == 1) {  // every cell its own group, no sort
    gr.start.resize(m + 1);
    std::iota(gr.start.begin(), gr.start.end(), 0u);
    return gr;
  }
  const Coarse co(dims, factor);
  std::vector<uint64_t> coarse(m);
  for (size_t c = 0; c < m; ++c) coarse[c] = co.key(uint64_t(keys[c]));
  radix_sort(coarse, gr.cell, co.gx * co.gy * co.gz, threads);  // stable: cells ascending
  close_groups(coarse, gr);
  return gr;
}

}  // namespace

sweep::QueryGroups group_cells(const std::vector<uint64_t>& keys, const uint64_t dims[3],
                               int factor, unsigned threads) {
  return group(keys, dims, factor, threads);
}

sweep::QueryGroups group_cells(const std::vector<uint32_t>& keys, const uint64_t dims[3],
                               int factor, unsigned threads) {
  return group(keys, dims, factor, threads);
}

sweep::QueryGroups group_cells_reference(const std::vector<uint64_t>& keys, const uint64_t dims[3],
                                         int factor) {
  const Coarse co(dims, factor);
  std::vector<std::pair<uint64_t, uint32_t>> pairs(keys.size());
  for (size_t c = 0; c < keys.size(); ++c) pairs[c] = {co.key(keys[c]), uint32_t(c)};
  std::stable_sort(pairs.begin(), pairs.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  sweep::QueryGroups gr;
  std::vector<uint64_t> coarse;
  for (const auto& p : pairs) gr.cell.push_back(p.second), coarse.push_back(p.first);
  close_groups(coarse, gr);
  return gr;
}

}  // namespace meshsal
