// The CPU rasteriser behind viewpoint and render: the tiled, copy-dropping depth_buffer_cpu
// gives bit for bit the z-buffer of the plain rasteriser (its oracle), on ordinary meshes
// and on hostile ones (stacks of copies of one large triangle, large overlapping triangles
// in every depth order).
#include <cstring>
#include <random>

#include "view/camera.h"
#include "meshsal/meshsal.h"
#include "view/render.h"
#include "cli/synthetic.h"
#include "view/viewpoint.h"
#include "view/visibility.h"
#include "test_util.h"

using namespace meshsal;

namespace {

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// Compares the two rasterisers over several views and resolutions; returns the number of
// views where they differ.
int differing_views(const Mesh& mesh, int views) {
  const ViewFrame frame = frame_mesh(mesh);
  int differ = 0;
  for (const ViewAngles& a : fibonacci_directions(views))
    for (int res : {17, 64, 200}) {
      const ViewRows rows = view_rows(frame, a);
      differ += !same_bits(depth_buffer_cpu(mesh, rows, res), depth_buffer_plain_cpu(mesh, rows, res));
    }
  return differ;
}

// n triangles with corners uniform in the unit cube: large ones, overlapping at all depths.
Mesh random_soup(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  Mesh m;
  for (size_t i = 0; i < 3 * n; ++i) {
    for (int k = 0; k < 3; ++k) m.positions.push_back(u(rng));
    m.triangles.push_back(uint32_t(i));
  }
  return m;
}

}  // namespace

TEST_CASE("raster: the fast z-buffer equals the plain rasteriser's bit for bit", "[view]") {
  CHECK(differing_views(make_sphere(1.0, 4), 12) == 0);
  CHECK(differing_views(make_cube(5), 12) == 0);
  CHECK(differing_views(make_plane_with_bump(2.0, 30, 0.3, 0.4), 12) == 0);
  for (uint32_t seed : {1u, 2u, 3u}) CHECK(differing_views(random_soup(60, seed), 8) == 0);

  // A stack of copies: the same indices again, the same positions under other indices, and
  // copies shifted back and forth along z by small and tiny steps.
  Mesh stack;
  stack.positions = {-1, -1, 0, 1, -1, 0, 0, 1, 0.5f};
  for (int i = 0; i < 50; ++i) stack.triangles.insert(stack.triangles.end(), {0, 1, 2});
  for (int i = 1; i <= 50; ++i) {
    const float dz = (i % 2 ? 1e-7f : -1e-3f) * float(i);
    const uint32_t base = uint32_t(stack.positions.size() / 3);
    for (int k = 0; k < 9; ++k) stack.positions.push_back(stack.positions[k] + (k % 3 == 2 ? dz : 0.0f));
    stack.triangles.insert(stack.triangles.end(), {base, base + 1, base + 2});
  }
  CHECK(differing_views(stack, 10) == 0);

  MESHSAL_REQUIRE_MESH(bunny, "bunny_3k.off");
  CHECK(differing_views(load_mesh(bunny), 6) == 0);
}

TEST_CASE("raster: render_mesh draws the same picture when large triangles come in copies", "[view]") {
  // Large overlapping triangles, each followed by copies at the same positions under other
  // vertex indices with other colours: a copy never wins a pixel (equal depth), so the
  // picture must not change, while dropping the copies keeps its cost that of one.
  Mesh soup = random_soup(40, 9);
  std::mt19937 rng(4);
  std::vector<uint8_t> rgb(3 * soup.vertex_count());
  for (uint8_t& c : rgb) c = uint8_t(rng());
  Mesh copies = soup;
  std::vector<uint8_t> copies_rgb = rgb;
  for (size_t f = 0; f < soup.triangle_count(); ++f)
    for (int k = 0; k < 30; ++k) {
      const uint32_t base = uint32_t(copies.vertex_count());
      for (int i = 0; i < 3; ++i) {
        const uint32_t v = soup.triangles[3 * f + i];
        for (int j = 0; j < 3; ++j) copies.positions.push_back(soup.positions[3 * v + j]);
        for (int j = 0; j < 3; ++j) copies_rgb.push_back(uint8_t(rng()));
        copies.triangles.push_back(base + uint32_t(i));
      }
    }
  const ViewFrame frame = frame_mesh(soup);
  for (bool smooth : {true, false}) {
    RenderStyle style;
    style.size = 160;
    style.smooth = smooth;
    style.edges = !smooth;
    for (const ViewAngles& a : fibonacci_directions(5)) {
      const Image one = render_mesh(soup, &rgb, frame, a, style);
      const Image many = render_mesh(copies, &copies_rgb, frame, a, style);
      CHECK(one.rgb == many.rgb);
    }
  }
}
