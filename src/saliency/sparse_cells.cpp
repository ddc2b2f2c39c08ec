#include "saliency/sparse_cells.h"

#include <algorithm>
#include <cmath>
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

std::vector<uint64_t> distinct_cell_keys(const float* xyz, size_t n, const BoundingBox& box, double cell,
                                         const BoundingBox& within, double bitmap_bytes_per_point, unsigned threads) {
  uint64_t dims[3];
  cell_dims(box, cell, dims);
  if (n == 0) return {};
  // The cells of `within` along each axis, a cell wider each way than rounding can move a
  // point's (cell_key's division), clamped to the grid.
  uint64_t lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    const double l = std::floor((within.min[a] - box.min[a]) / cell) - 1, h = std::floor((within.max[a] - box.min[a]) / cell) + 1;
    lo[a] = l > 0 ? uint64_t(l) : 0;
    hi[a] = uint64_t(std::clamp(h, double(lo[a]), double(dims[a] - 1)));
  }
  const uint64_t span[3] = {hi[0] - lo[0] + 1, hi[1] - lo[1] + 1, hi[2] - lo[2] + 1};
  const double bits = double(span[0]) * double(span[1]) * double(span[2]);
  if (!(bits / 8 <= bitmap_bytes_per_point * double(n))) {
    Mesh points;
    points.positions.assign(xyz, xyz + 3 * n);
    std::vector<uint32_t> list(n);
    for (size_t i = 0; i < n; ++i) list[i] = uint32_t(i);
    return sort_into_cells(points, std::move(list), box, cell, threads).key;
  }
  // Bit (z * span[1] + y) * span[0] + x of the cells' range: its order is the keys' order.
  std::vector<uint64_t> words((uint64_t(bits) + 63) / 64, 0);
  for (size_t i = 0; i < n; ++i) {
    uint64_t c[3];
    for (int a = 0; a < 3; ++a) c[a] = uint64_t((double(xyz[3 * i + a]) - box.min[a]) / cell) - lo[a];
    if (c[0] >= span[0] || c[1] >= span[1] || c[2] >= span[2])
      throw Error("internal: a point outside the box its cells were counted in");
    const uint64_t b = (c[2] * span[1] + c[1]) * span[0] + c[0];
    words[b >> 6] |= uint64_t(1) << (b & 63);
  }
  std::vector<uint64_t> keys;
  for (size_t w = 0; w < words.size(); ++w)
    for (uint64_t m = words[w]; m; m &= m - 1) {
      const uint64_t b = 64 * w + uint64_t(__builtin_ctzll(m));
      const uint64_t x = b % span[0] + lo[0], y = b / span[0] % span[1] + lo[1], z = b / (span[0] * span[1]) + lo[2];
      keys.push_back((z * dims[1] + y) * dims[0] + x);
    }
  return keys;
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
