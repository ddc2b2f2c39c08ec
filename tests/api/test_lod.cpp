// Levels of detail: simplify_lod (the saliency computed once and carried down the chain),
// write_lod (one GLB linked by MSFT_lod, or one file per level) and `simplify --lod`.
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "cli/synthetic.h"
#include "cli_run.h"
#include "gltf_util.h"
#include "meshsal/meshsal.h"

using namespace meshsal;
using meshsal_test::quoted;
using meshsal_test::run_cli;
using meshsal_test::scratch_dir;

namespace {

SaliencyOptions cpu() {
  SaliencyOptions o;
  o.backend = Backend::Cpu;
  return o;
}

// The JSON chunk of a GLB.
std::string glb_json(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string b = ss.str();
  REQUIRE(b.size() > 20);
  uint32_t n = 0;
  std::memcpy(&n, b.data() + 12, 4);
  return b.substr(20, n);
}

}  // namespace

TEST_CASE("lod: the chain reaches each target, each level from the one before", "[simplify][lod]") {
  const Mesh m = make_bumpy_sphere(4);  // 5120 faces
  std::vector<SimplifyOptions> levels(3);
  levels[0].ratio = 0.5;
  levels[1].ratio = 0.2;
  levels[2].ratio = 300.0 / 5120;  // all ratios or all counts
  const SaliencyWeightOptions wo = weight_preset(Weighting::Balanced);
  const std::vector<LodLevel> chain = simplify_lod(m, levels, wo, cpu());
  REQUIRE(chain.size() == 3);
  CHECK(chain[0].mesh.triangle_count() == 2560);
  CHECK(chain[1].mesh.triangle_count() == 1024);
  CHECK(chain[2].mesh.triangle_count() == 300);
  for (const LodLevel& l : chain) {
    CHECK(l.report.reached);
    REQUIRE(l.saliency.size() == l.mesh.vertex_count());
    for (double s : l.saliency) CHECK(s >= 0);
    for (const VertexAttribute& a : l.mesh.attributes) CHECK(a.name.find("lod") == std::string::npos);  // the carrier is gone
  }
  // Level 1 was made from level 0: its input count is level 0's faces.
  CHECK(chain[1].report.input_faces == 2560);
  // The saliency carried to level 1 is the input's at the vertices that never moved.
  const SaliencyResult s = compute_saliency(m, cpu());
  size_t same = 0;
  for (size_t v = 0; v < chain[0].mesh.vertex_count(); ++v) {
    const uint32_t from = chain[0].report.vertex_origin[v];
    if (chain[0].mesh.positions[3 * v] == m.positions[3 * from] && chain[0].mesh.positions[3 * v + 1] == m.positions[3 * from + 1] &&
        chain[0].mesh.positions[3 * v + 2] == m.positions[3 * from + 2]) {
      CHECK(chain[0].saliency[v] == Approx(s.saliency[from]).epsilon(1e-6));
      ++same;
    }
  }
  CHECK(same > 100);
  // The first level equals simplify_with_saliency with the same S.
  SimplifyOptions o;
  o.ratio = 0.5;
  const Mesh direct = simplify_with_saliency(m, o, wo, cpu(), s.saliency).mesh;
  CHECK(direct.triangles == chain[0].mesh.triangles);
  // Levels must shrink; target_error is not a level.
  std::vector<SimplifyOptions> bad(2);
  bad[0].ratio = 0.2;
  bad[1].ratio = 0.5;
  CHECK_THROWS_WITH(simplify_lod(m, bad, std::nullopt, cpu()), "lod: level 2 (0.5) is not below level 1 (0.2): list the "
                                                           "levels from the most faces to the fewest");
  bad[1].ratio = 0;
  bad[1].target_faces = 300;
  CHECK_THROWS_WITH(simplify_lod(m, bad, std::nullopt, cpu()), Catch::Contains("not both"));
  CHECK_THROWS_WITH(parse_lod_levels("0.5,x"), Catch::Contains("comma-separated list of ratios in (0, 1) or of face counts"));
  CHECK_THROWS_WITH(parse_lod_levels("1.5"), Catch::Contains("ratios in (0, 1)"));
  const std::vector<SimplifyOptions> parsed = parse_lod_levels("0.5,0.125,1e-2");
  REQUIRE(parsed.size() == 3);
  CHECK(parsed[0].ratio == 0.5);
  CHECK(parsed[1].ratio == 0.125);
  CHECK(parsed[2].ratio == 0.01);
  const std::vector<SimplifyOptions> counts = parse_lod_levels("20000,5000");
  REQUIRE(counts.size() == 2);
  CHECK(counts[0].target_faces == 20000);
  CHECK(counts[1].target_faces == 5000);
}

TEST_CASE("lod: simplify --lod writes one GLB linked by MSFT_lod, or one file per level", "[cli][lod][gltf][validator]") {
  const auto dir = scratch_dir("lod_cli");
  const std::string in = (dir / "m.obj").string();
  write_obj(in, make_bumpy_sphere(4));
  const std::string glb = (dir / "m.glb").string();
  auto r = run_cli("simplify " + quoted(in) + " -o " + quoted(glb) + " --lod 2560,1024,300 --backend cpu --json", dir);
  INFO(r.err);
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("\"output_faces\": 2560") != std::string::npos);
  CHECK(r.out.find("\"output_faces\": 1024") != std::string::npos);
  CHECK(r.out.find("\"output_faces\": 300") != std::string::npos);
  std::string report;
  CHECK(meshsal_test::validate_gltf(glb, &report) == 0);
  INFO(report);
  const std::string json = glb_json(glb);
  CHECK(json.find("\"MSFT_lod\":{\"ids\":[1,2,3]}") != std::string::npos);
  CHECK(json.find("\"extensionsUsed\":[\"MSFT_lod\"]") != std::string::npos);
  CHECK(json.find("\"name\":\"LOD3\"") != std::string::npos);
  // The scene shows LOD0, the input, whole.
  CHECK(load_mesh(glb).triangle_count() == 5120);
  // OBJ: one file per level, the input not written again.
  r = run_cli("simplify " + quoted(in) + " -o " + quoted((dir / "out.obj").string()) + " --lod 2560,300 --backend cpu -q", dir);
  REQUIRE(r.rc == 0);
  CHECK(load_mesh((dir / "out_lod1.obj").string()).triangle_count() == 2560);
  CHECK(load_mesh((dir / "out_lod2.obj").string()).triangle_count() == 300);
  CHECK_FALSE(std::filesystem::exists(dir / "out.obj"));
  // A PLY level carries its saliency as quality.
  r = run_cli("simplify " + quoted(in) + " -o " + quoted((dir / "out.ply").string()) + " --lod 0.5 --backend cpu -q", dir);
  REQUIRE(r.rc == 0);
  const VertexProperties props = read_mesh((dir / "out_lod1.ply").string()).properties;
  CHECK(props.count("quality") == 1);
  // Usage errors.
  r = run_cli("simplify " + quoted(in) + " -o " + quoted(glb) + " --lod 0.5 --ratio 0.1", dir);
  CHECK(r.rc == 2);
  CHECK(r.err.find("--lod names every level") != std::string::npos);
  r = run_cli("simplify " + quoted(in) + " -o " + quoted(glb) + " --lod 0.2,0.5 --backend cpu", dir);
  CHECK(r.rc == 2);
  CHECK(r.err.find("error: --lod: level 2 (0.5) is not below level 1 (0.2)") == 0);
}

TEST_CASE("lod: batch --lod writes the file simplify --lod writes, byte for byte", "[cli][lod][batch]") {
  const auto dir = scratch_dir("lod_batch");
  std::filesystem::create_directories(dir / "in");
  const std::string in = (dir / "in" / "ball.obj").string();
  write_obj(in, make_bumpy_sphere(3));
  auto r = run_cli("batch " + quoted((dir / "in").string()) + " -o " + quoted((dir / "out").string()) +
                       " --lod 0.5,0.1 --backend cpu -q",
                   dir);
  INFO(r.err);
  REQUIRE(r.rc == 0);
  r = run_cli("simplify " + quoted(in) + " -o " + quoted((dir / "one.glb").string()) + " --lod 0.5,0.1 --backend cpu -q", dir);
  REQUIRE(r.rc == 0);
  std::ifstream a(dir / "out" / "ball_lod.glb", std::ios::binary), b(dir / "one.glb", std::ios::binary);
  std::stringstream sa, sb;
  sa << a.rdbuf();
  sb << b.rdbuf();
  CHECK(sa.str().size() > 1000);
  CHECK(sa.str() == sb.str());
  // A rerun in the output folder does not take the GLB for an input.
  r = run_cli("batch " + quoted((dir / "out").string()) + " " + quoted((dir / "in").string()) + " -o " +
                  quoted((dir / "out").string()) + " --lod 0.5,0.1 --backend cpu",
              dir);
  CHECK(r.out.find("1 models: 0 computed, 1 skipped") != std::string::npos);
}

// Issue 36 (9): a bad --lod list is a usage error found before the input is read (the
// order, a level twice, ratios mixed with counts), in simplify and batch alike.
TEST_CASE("lod: a bad list is a usage error before the input is read, in simplify and batch", "[cli][lod][batch]") {
  const auto dir = scratch_dir("lod_usage");
  const std::string in = quoted((dir / "missing.obj").string());  // never read
  std::string seventeen;
  for (int n = 17; n >= 1; --n) seventeen += std::to_string(n * 100) + (n > 1 ? "," : "");
  for (const std::string& list : std::vector<std::string>{"0.2,0.5", "0.5,0.5", "500,500", "300,2000", "0.5,300", "300,0.5", "0.5,", ",0.5",
                                 "0.5,,0.2", "0x10", "0.5,inf", "nan", "1.5", "0", "-5", "+5", " 5", "0.5 ", "1e", seventeen}) {
    for (const std::string command : {"simplify " + in + " -o " + quoted((dir / "o.glb").string()),
                                      "batch " + in + " -o " + quoted((dir / "out").string())}) {
      INFO(command << " --lod='" << list << "'");
      meshsal_test::check_usage_error(command + " --lod='" + list + "'", "--lod: ", dir);
    }
  }
  const auto said = [&](const std::string& list) {
    return run_cli("simplify " + in + " -o " + quoted((dir / "o.glb").string()) + " --lod " + list, dir).err;
  };
  CHECK(said("0.2,0.5") == "error: --lod: level 2 (0.5) is not below level 1 (0.2): list the levels from the most "
                           "faces to the fewest (see --help)\n");
  CHECK(said("500,500") == "error: --lod: level 2 repeats level 1 (500): each level has fewer faces than the one "
                           "before (see --help)\n");
  CHECK(said("0.5,300") == "error: --lod: give ratios (e.g. 0.5,0.2) or face counts (e.g. 20000,5000), not both: "
                           "level 1 is 0.5, level 2 300 (see --help)\n");
  CHECK(said(seventeen) == "error: --lod: at most 16 levels, got 17 (see --help)\n");
}

// A level at or above the faces of the mesh it starts from is that mesh unchanged, as plain
// `simplify --target-faces N` writes a mesh of N faces or fewer unchanged.
TEST_CASE("lod: a level above the face count keeps the mesh, as plain simplify does", "[simplify][lod][cli][batch]") {
  const Mesh m = make_bumpy_sphere(4);  // 5120 faces
  std::vector<SimplifyOptions> levels(3);
  levels[0].target_faces = 9000;
  levels[1].target_faces = 5120;
  levels[2].target_faces = 2000;
  const SaliencyWeightOptions wo = weight_preset(Weighting::Balanced);
  const std::vector<LodLevel> chain = simplify_lod(m, levels, wo, cpu());
  REQUIRE(chain.size() == 3);
  for (int i : {0, 1}) {
    INFO("level " << i + 1);
    CHECK(chain[size_t(i)].report.unchanged);
    CHECK(chain[size_t(i)].mesh.triangles == m.triangles);
    CHECK(chain[size_t(i)].mesh.positions == m.positions);
    CHECK(chain[size_t(i)].saliency.size() == m.vertex_count());
  }
  CHECK(chain[0].saliency == compute_saliency(m, cpu()).saliency);
  CHECK(chain[2].mesh.triangle_count() == 2000);
  CHECK_FALSE(chain[2].report.unchanged);

  const auto dir = scratch_dir("lod_above");
  const std::string in = (dir / "m.obj").string();
  write_obj(in, m);
  auto r = run_cli("simplify " + quoted(in) + " -o " + quoted((dir / "plain.obj").string()) +
                       " --target-faces 9000 --backend cpu", dir);
  REQUIRE(r.rc == 0);
  r = run_cli("simplify " + quoted(in) + " -o " + quoted((dir / "out.obj").string()) + " --lod 9000,300 --backend cpu", dir);
  INFO(r.err);
  REQUIRE(r.rc == 0);
  CHECK(r.err.find("note: LOD1: the target is at or above the mesh's 5120 faces") != std::string::npos);
  const Mesh level1 = load_mesh((dir / "out_lod1.obj").string());
  CHECK(level1.triangles == load_mesh((dir / "plain.obj").string()).triangles);
  CHECK(level1.triangle_count() == 5120);
  CHECK(load_mesh((dir / "out_lod2.obj").string()).triangle_count() == 300);
  std::filesystem::create_directories(dir / "in");
  write_obj((dir / "in" / "m.obj").string(), m);
  r = run_cli("batch " + quoted((dir / "in").string()) + " -o " + quoted((dir / "out").string()) +
                  " --lod 9000,300 --backend cpu -q", dir);
  INFO(r.err);
  CHECK(r.rc == 0);
  CHECK(std::filesystem::exists(dir / "out" / "m_lod.glb"));
}
