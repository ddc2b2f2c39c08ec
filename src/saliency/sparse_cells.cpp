#include "saliency/sparse_cells.h"

#include <algorithm>
#include <utility>

#include "core/parallel.h"
#include "core/parallel_select.h"
#include "core/radix_sort.h"

namespace meshsal {

namespace {

constexpr int kAxisBits = 21;

// Slots and keys of the occupied cells from the sorted keys.
template <class Key>
void mark_cells(const std::vector<Key>& keys, SparseCells& s) {
  for (size_t i = 0; i < keys.size(); ++i) {
    if (i == 0 || keys[i] != keys[i - 1]) {
      s.start.push_back(uint32_t(i));
      s.key.push_back(keys[i]);
    }
  }
  s.start.push_back(uint32_t(keys.size()));
}

// Keys of Key bits (32 where the grid has fewer than 2^32 cells: half the memory and
// traffic of the sort on a 10M-vertex scan).
template <class Key>
void sort_keys(const Mesh& mesh, std::vector<uint32_t>&& points, const BoundingBox& box, double cell,
               unsigned threads, SparseCells& s) {
  std::vector<Key> keys(points.size());
  parallel_for(points.size(), threads, 1 << 15, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i)
      keys[i] = Key(cell_key(box, cell, s.dims, &mesh.positions[3 * size_t(points[i])]));
  });
  s.order = std::move(points);
  radix_sort(keys, s.order, s.dims[0] * s.dims[1] * s.dims[2] - 1, threads);
  mark_cells(keys, s);
}

}  // namespace

double usable_cell(const BoundingBox& box, double cell) {
  for (int a = 0; a < 3; ++a)
    while ((box.max[a] - box.min[a]) / cell >= double((1 << kAxisBits) - 2)) cell *= 2;
  return cell;
}

void cell_dims(const BoundingBox& box, double cell, uint64_t dims[3]) {
  for (int a = 0; a < 3; ++a) dims[a] = uint64_t((box.max[a] - box.min[a]) / cell) + 1;
}

uint64_t cell_key(const BoundingBox& box, double cell, const uint64_t dims[3], const float* p) {
  uint64_t c[3];
  for (int a = 0; a < 3; ++a) c[a] = uint64_t((double(p[a]) - box.min[a]) / cell);
  return (c[2] * dims[1] + c[1]) * dims[0] + c[0];
}

SparseCells sort_into_cells(const Mesh& mesh, std::vector<uint32_t>&& points, const BoundingBox& box,
                            double cell, unsigned threads) {
  SparseCells s;
  cell_dims(box, cell, s.dims);
  if (s.dims[0] * s.dims[1] * s.dims[2] <= (uint64_t(1) << 32))
    sort_keys<uint32_t>(mesh, std::move(points), box, cell, threads, s);
  else
    sort_keys<uint64_t>(mesh, std::move(points), box, cell, threads, s);
  return s;
}

SparseCells sort_into_cells(const Mesh& mesh, const std::vector<uint32_t>& points,
                            const BoundingBox& box, double cell, unsigned threads) {
  return sort_into_cells(mesh, std::vector<uint32_t>(points), box, cell, threads);
}

std::vector<uint32_t> mesh_point_list(const std::vector<uint8_t>& is_point) {
  std::vector<uint32_t> points;
  parallel_select(
      is_point.size(), 0, [&](size_t v) { return is_point[v] != 0; }, [](size_t v) { return uint32_t(v); }, points);
  return points;
}

SparseCells sort_into_cells_reference(const Mesh& mesh, const std::vector<uint32_t>& points,
                                      const BoundingBox& box, double cell) {
  SparseCells s;
  cell_dims(box, cell, s.dims);
  std::vector<std::pair<uint64_t, uint32_t>> kv;
  for (uint32_t v : points) kv.push_back({cell_key(box, cell, s.dims, &mesh.positions[3 * size_t(v)]), v});
  std::stable_sort(kv.begin(), kv.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<uint64_t> keys;
  for (const auto& [k, v] : kv) {
    keys.push_back(k);
    s.order.push_back(v);
  }
  mark_cells(keys, s);
  return s;
}

}  // namespace meshsal
