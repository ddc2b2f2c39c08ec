// Vertices no collapse moved come back with their exact input coordinates (bit for bit),
// not through the simplifier's internal centring and scaling and back.
#include <cstring>
#include <random>
#include <set>

#include "simplify/simplify.h"
#include "cli/synthetic.h"
#include "test_util.h"

using namespace meshsal;

TEST_CASE("simplify: untouched vertices keep their exact input coordinates", "[simplify]") {
  // Spheres at several offsets, with some coordinates exactly 0: a 0 does not always survive
  // (p - center) * scale / scale + center (it came back as -4.4e-16 for some centres).
  for (int shift = 1; shift <= 20; ++shift) {
    Mesh mesh = make_sphere(1.0, 3);
    std::mt19937 rng(shift);
    std::uniform_real_distribution<float> jitter(-1e-3f, 1e-3f);
    for (size_t v = 0; v < mesh.vertex_count(); ++v)
      for (int k = 0; k < 3; ++k) mesh.positions[3 * v + k] += 0.1f * float(shift * (k + 1)) + jitter(rng);
    for (size_t v = 0; v < mesh.vertex_count(); v += 5) mesh.positions[3 * v + v % 3] = 0.0f;

    SimplifyOptions opt;
    opt.target_faces = mesh.triangle_count() - 40;  // 20 collapses: most vertices untouched
    opt.record_collapses = true;
    const Simplified s = simplify_mesh(mesh, opt);
    const Mesh& out = s.mesh;
    const SimplifyReport& rep = s.report;
    REQUIRE(rep.sequence.size() >= 20);

    std::set<uint32_t> kept, removed;
    for (const Collapse& c : rep.sequence) kept.insert(c.kept), removed.insert(c.removed);
    // Output vertices are the surviving input vertices in input order (all are referenced).
    size_t o = 0, untouched = 0, exact = 0;
    for (uint32_t v = 0; v < mesh.vertex_count(); ++v) {
      if (removed.count(v)) continue;
      if (!kept.count(v)) {
        ++untouched;
        exact += o < out.vertex_count() &&
                 std::memcmp(&out.positions[3 * o], &mesh.positions[3 * size_t(v)], 3 * sizeof(float)) == 0;
      }
      ++o;
    }
    INFO("offset step " << shift);
    CHECK(o == out.vertex_count());
    CHECK(untouched > 500);
    CHECK(exact == untouched);
  }
}
