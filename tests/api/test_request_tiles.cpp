// run_request's implied options: tiled simplification weighs by the paper's S computed in the
// same tiles whatever the front end (the CLI's simplify --tiles, Python's simplify_file(tiles=)),
// unless the request names the saliency's tiles; the other models are had whole.
#include <catch2/catch.hpp>

#include <string>

#include "cli/synthetic.h"
#include "meshsal/meshsal.h"
#include "test_io_util.h"

using namespace meshsal;

TEST_CASE("run_request: tiled simplification takes S in the same tiles from every front end", "[tiles]") {
  meshsal_test::TempDir dir;
  const std::string in = dir.file("in.ply");
  write_ply(in, make_bumpy_sphere(4), {});
  Request r;
  r.input = in;
  r.simplify.ratio = 0.3;
  r.simplify.tiles = 3;
  r.saliency.backend = Backend::Cpu;
  r.saliency.method = Method::Fast;
  auto simplified = [&](unsigned saliency_tiles, const std::string& name) {
    r.saliency.tiles = saliency_tiles;
    r.simplified_output = dir.file(name);
    run_request(r);
    return meshsal_test::read_file(r.simplified_output);
  };
  const std::string implied = simplified(0, "implied.ply");
  // The same bytes as S asked for in 3 tiles. (S whole, saliency tiles 1, differs from it in
  // the last bits only: on this mesh its simplification is the same, so it proves nothing.)
  CHECK(implied == simplified(3, "tiled.ply"));
  // Another model is had whole (tiles it cannot take are not implied; named, refused).
  r.saliency.model = Model::Height;
  CHECK_NOTHROW(simplified(0, "height.ply"));
  CHECK_THROWS_WITH(simplified(2, "refused.ply"), Catch::Contains("in memory, in one piece"));
}

TEST_CASE("run_request out of core: the saliency and the simplified mesh from one S", "[outofcore]") {
  meshsal_test::TempDir dir;
  const std::string in = dir.file("in.ply");
  write_ply(in, make_bumpy_sphere(4), {});
  Request r;
  r.input = in;
  r.simplify.ratio = 0.2;
  r.saliency.backend = Backend::Cpu;
  r.saliency.method = Method::Fast;
  r.out_of_core.memory_limit = uint64_t(1) << 30;
  r.out_of_core.temp_dir = dir.path.string();
  r.saliency_output = dir.file("s.ply");
  r.simplified_output = dir.file("m.ply");
  const RequestResult both = run_request(r);
  // One step computed S and wrote both files; the saliency report is the simplifier's.
  REQUIRE(both.steps.size() == 1);
  CHECK(both.steps[0].name == "simplify");
  CHECK(both.out_of_core.saliency_max == both.simplify_out_of_core.saliency.saliency_max);
  CHECK(both.out_of_core.saliency_max > 0);
  CHECK(both.outputs == std::vector<std::string>{r.saliency_output, r.simplified_output});
  // Each file alone is what the request with both wrote.
  Request s_only = r, m_only = r;
  s_only.simplified_output.clear();
  s_only.saliency_output = dir.file("s_only.ply");
  m_only.saliency_output.clear();
  m_only.simplified_output = dir.file("m_only.ply");
  run_request(s_only);
  run_request(m_only);
  CHECK(meshsal_test::read_file(dir.file("s.ply")) == meshsal_test::read_file(dir.file("s_only.ply")));
  CHECK(meshsal_test::read_file(dir.file("m.ply")) == meshsal_test::read_file(dir.file("m_only.ply")));
}
