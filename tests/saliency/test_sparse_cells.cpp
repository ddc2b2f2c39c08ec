// The fast method's cell sort (radix, parallel keys) against its std::stable_sort oracle.
#include <random>

#include "core/mesh_points.h"
#include "cli/synthetic.h"
#include "saliency/sparse_cells.h"
#include "test_util.h"

using namespace meshsal;

namespace {

void require_same(const SparseCells& a, const SparseCells& b) {
  for (int k = 0; k < 3; ++k) REQUIRE(a.dims[k] == b.dims[k]);
  REQUIRE(a.order == b.order);
  REQUIRE(a.start == b.start);
  REQUIRE(a.key == b.key);
}

// Random points in a long thin box, some of them duplicated (cells with many points), and
// every seventh vertex left out (not a mesh point).
Mesh random_points(size_t n, std::vector<uint32_t>& points) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> x(-50, 50), yz(-1, 1);
  Mesh m;
  for (size_t v = 0; v < n; ++v) {
    if (v % 5 == 4) {  // a copy of an earlier point: the same cell, a later vertex
      const size_t u = rng() % v;
      m.positions.insert(m.positions.end(), m.positions.begin() + 3 * u, m.positions.begin() + 3 * u + 3);
    } else {
      m.positions.insert(m.positions.end(), {x(rng), yz(rng), yz(rng)});
    }
    if (v % 7 != 3) points.push_back(uint32_t(v));
  }
  return m;
}

}  // namespace

TEST_CASE("sparse cells: the radix sort equals the stable-sort oracle", "[fast]") {
  std::vector<uint32_t> points;
  const Mesh m = random_points(20000, points);
  std::vector<uint8_t> is_point(m.vertex_count(), 0);
  for (uint32_t v : points) is_point[v] = 1;
  const BoundingBox box = mesh_points_bbox(m, is_point);
  REQUIRE(mesh_point_list(is_point) == points);
  // Cells from 40 (keys of a few bits: one pass) down to 1e-5 (keys of about 50 bits: 7 passes).
  for (double cell : {40.0, 0.5, 0.01, 1e-5}) {
    const double used = usable_cell(box, cell);
    const SparseCells want = sort_into_cells_reference(m, points, box, used);
    INFO("cell " << cell << ", " << want.key.size() << " occupied, largest key " << want.key.back());
    if (cell == 1e-5) REQUIRE(want.key.back() > (uint64_t(1) << 48));
    if (cell == 40.0) REQUIRE(want.key.size() < 10);
    for (unsigned threads : {1u, 2u, 5u}) require_same(sort_into_cells(m, points, box, used, threads), want);
    // Keys order the cells by z, then y, then x, and every point lies in its cell.
    for (size_t c = 0; c < want.key.size(); ++c) {
      if (c > 0) REQUIRE(want.key[c] > want.key[c - 1]);
      for (uint32_t i = want.start[c]; i < want.start[c + 1]; ++i)
        REQUIRE(cell_key(box, used, want.dims, &m.positions[3 * want.order[i]]) == want.key[c]);
    }
  }
}

TEST_CASE("sparse cells: a cell's points keep vertex order", "[fast]") {
  // Four points of one cell given out of order stay in the order given; two other cells
  // sort by z first: (1, 0, 0) comes before (0, 0, 1).
  Mesh m;
  m.positions = {0.1f, 0.1f, 0.1f, 0, 0, 1, 0.2f, 0.2f, 0.2f, 1, 0, 0, 0.3f, 0.3f, 0.3f};
  std::vector<uint8_t> is_point(5, 1);
  const BoundingBox box = mesh_points_bbox(m, is_point);
  const SparseCells s = sort_into_cells(m, {4, 0, 1, 2, 3}, box, 0.5);
  CHECK(s.order == std::vector<uint32_t>{4, 0, 2, 3, 1});
  CHECK(s.start == std::vector<uint32_t>{0, 3, 4, 5});
  CHECK(s.key == std::vector<uint64_t>{0, 2, 2 * 1 * 3});  // 3 x 1 x 3 cells: z * 1 * 3 + y * 3 + x
}
