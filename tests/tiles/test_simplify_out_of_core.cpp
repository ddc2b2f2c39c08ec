// Out-of-core simplification (simplify_file, meshsal simplify --memory-limit; issue 23
// item 4): the bytes of the in-memory tiled simplifier, the peak resident memory under the
// limit, clear errors; and the streamed percentile its weights need.
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <sstream>

#include "core/streamed_percentile.h"
#include "cli/synthetic.h"
#include "cli_run.h"
#include "out_of_core_util.h"
#include "json_check.h"
#include "simplify/saliency_weights.h"
#include "test_simplify_util.h"
#include "test_util.h"

using namespace meshsal;
using namespace meshsal_test;

namespace {

SimplifyOptions ratio(double r, unsigned tiles = 0) {
  SimplifyOptions o;
  o.ratio = r;
  o.tiles = tiles;
  return o;
}

// What `meshsal simplify --tiles N` writes, through the library: the mesh as read from
// `path`, weights from its (exact, untiled: the same bits as tiled) saliency with S as
// `quality`, simplify_mesh_tiled (o.tiles), write_ply.
void in_memory(const std::string& path, const std::string& out, const SimplifyOptions& o,
               const std::optional<SaliencyWeightOptions>& weights) {
  Mesh mesh = load_mesh(path);
  std::vector<double> w;
  if (weights) {
    const SimplificationWeights sw = simplification_weights(mesh, *weights, cpu(Method::Exact));
    w = sw.weights;
    set_vertex_attribute(mesh, "quality", sw.saliency);
  }
  write_ply(out, simplify_mesh_tiled(mesh, o, w).mesh, {});
}


}  // namespace

TEST_CASE("streamed percentile is percentile() to the bit", "[outofcore][weights]") {
  std::mt19937_64 rng(7);
  std::vector<double> v(20000);
  std::uniform_real_distribution<double> u(0, 3);
  for (double& x : v) x = std::pow(u(rng), 4);  // skewed, as Sm is
  for (size_t i = 0; i < 3000; ++i) v[i] = 0;     // flat regions: many equal values
  const ValueStream all = [&](const std::function<void(double)>& take) {
    for (double x : v) take(x);
  };
  for (double p : {0.0, 1.0, 30.0, 50.0, 77.7, 99.9, 100.0})
    for (size_t cap : {size_t(16), size_t(1000), size_t(1) << 20}) {  // 16: several narrowing rounds
      INFO("p " << p << ", cap " << cap);
      CHECK(streamed_percentile(all, v.size(), p, cap) == percentile(v, {}, p));
    }
  const std::vector<double> same(5000, 0.25);
  const ValueStream flat = [&](const std::function<void(double)>& take) {
    for (double x : same) take(x);
  };
  CHECK(streamed_percentile(flat, same.size(), 50, 16) == 0.25);
  CHECK_THROWS_AS(streamed_percentile(all, 0, 50), Error);
  CHECK_THROWS_AS(streamed_percentile(all, v.size(), 101), Error);
}

TEST_CASE("out-of-core simplification writes the in-memory tiled bytes", "[outofcore][simplify]") {
  const auto dir = scratch_dir("ooc_simplify");
  const SaliencyWeightOptions balanced = weight_preset(Weighting::Balanced);
  struct Case {
    const char* name;
    Mesh mesh;
    double ratio;
    unsigned tiles;
    bool weighted;
  };
  std::vector<Case> cases;
  cases.push_back({"sphere", make_bumpy_sphere(4), 0.1, 3, true});
  cases.push_back({"plane", make_plane_with_bump(2.0, 60, 0.3, 0.2), 0.1, 3, true});   // open borders
  cases.push_back({"far", far_sphere(), 0.2, 2, true});                                 // survey coordinates
  cases.push_back({"plain", make_bumpy_sphere(4), 0.05, 3, false});                     // weights none
  for (Case& c : cases) {
    INFO(c.name);
    const std::string in = (dir / (std::string(c.name) + ".ply")).string();
    write_ply(in, c.mesh, {});
    const std::string a = (dir / "a.ply").string(), b = (dir / "b.ply").string();
    const std::optional<SaliencyWeightOptions> weights = c.weighted ? std::optional(balanced) : std::nullopt;
    in_memory(in, a, ratio(c.ratio, c.tiles), weights);
    OutOfCoreOptions ooc;
    ooc.temp_dir = dir.string();
    const OutOfCoreSimplifyReport r = simplify_file(in, b, ratio(c.ratio, c.tiles), weights, cpu(Method::Exact), ooc);
    CHECK(r.tiles == c.tiles);
    CHECK(r.simplify.output_faces >= r.simplify.target_faces);
    CHECK(r.simplify.collapses > 0);
    CHECK(file_bytes(a) == file_bytes(b));
    // The temporary folder went with the run.
    for (const auto& e : std::filesystem::directory_iterator(dir))
      CHECK(e.path().filename().string().rfind("meshsal-tiles-", 0) != 0);
    // No crack, no new border, within 1% of the target.
    const simplify_test::Topology ti = simplify_test::topology(c.mesh), to = simplify_test::topology(load_mesh(b));
    if (ti.border_edges == 0) CHECK(to.border_edges == 0);  // closed stays closed: no crack
    CHECK(to.border_edges <= ti.border_edges);
    CHECK(to.nonmanifold_edges == 0);
    CHECK(to.nonmanifold_vertices == 0);
    CHECK(double(r.simplify.output_faces) <= 1.01 * double(r.simplify.target_faces));
  }
}

TEST_CASE("out-of-core simplification keeps the mesh as read when the target asks for it all", "[outofcore][simplify]") {
  const auto dir = scratch_dir("ooc_simplify_keep");
  Mesh m = make_bumpy_sphere(3);
  m.positions.insert(m.positions.end(), {5, 5, 5});  // an unreferenced vertex stays
  m.triangles.insert(m.triangles.end(), {0, 0, 1});  // and a degenerate triangle
  const std::string in = (dir / "in.ply").string();
  write_ply(in, m, {});
  write_ply((dir / "a.ply").string(), load_mesh(in), {});
  const SaliencyWeightOptions balanced = weight_preset(Weighting::Balanced);
  const OutOfCoreSimplifyReport r =
      simplify_file(in, (dir / "b.ply").string(), ratio(1.0, 2), balanced, cpu(Method::Fast), {});
  CHECK(r.simplify.unchanged);
  CHECK(r.simplify.collapses == 0);
  CHECK(file_bytes(dir / "a.ply") == file_bytes(dir / "b.ply"));
}

TEST_CASE("out-of-core simplification of a shared scan equals the in-memory tiled run", "[outofcore][simplify]") {
  MESHSAL_REQUIRE_MESH(path, "bunny_36k.obj");
  const auto dir = scratch_dir("ooc_simplify_bunny");
  const std::string in = (dir / "bunny.ply").string();
  write_ply(in, load_mesh(path), {});
  const SaliencyWeightOptions balanced = weight_preset(Weighting::Balanced);
  in_memory(in, (dir / "a.ply").string(), ratio(0.1, 4), balanced);
  const OutOfCoreSimplifyReport r =
      simplify_file(in, (dir / "b.ply").string(), ratio(0.1, 4), balanced, cpu(Method::Exact), {});
  CHECK(file_bytes(dir / "a.ply") == file_bytes(dir / "b.ply"));
  CHECK(r.simplify.output_faces <= size_t(1.01 * double(r.simplify.target_faces)));
  CHECK(r.alpha > 0);
}

TEST_CASE("simplify --memory-limit holds the limit and gives --tiles N's bytes", "[outofcore][simplify][cli]") {
  const auto dir = scratch_dir("ooc_simplify_cli");
  const std::string in = (dir / "plane.ply").string();
  write_ply(in, make_plane_with_bump(2.0, 400, 0.3, 0.2), {});  // 160,801 vertices
  const std::string common = "simplify " + quoted(in) + " --ratio 0.05 --backend cpu --json";
  const CliRun limited =
      run_cli(common + " -o " + quoted((dir / "b.ply").string()) + " --method fast --memory-limit 60M", dir);
  INFO(limited.err << limited.out);
  REQUIRE(limited.rc == 0);
  const double tiles = json_number(limited.out, "tiles");
  CHECK(tiles > 1);
  if (!kAddressSanitizer) CHECK(json_number(limited.out, "peak_rss") < 60.0 * (1 << 20));
  CHECK(json_number(limited.out, "output_faces") <= 1.01 * json_number(limited.out, "target_faces"));
  // With the exact method the tiled saliency is the untiled one: the same bytes as --tiles
  // in memory (a smaller mesh: the exact method is slow).
  const std::string small = (dir / "small.ply").string();
  write_ply(small, make_plane_with_bump(2.0, 100, 0.3, 0.2), {});
  const std::string exact = "simplify " + quoted(small) + " --ratio 0.1 --backend cpu --method exact --tiles 3 -o ";
  const CliRun mem = run_cli(exact + quoted((dir / "d.ply").string()), dir);
  const CliRun ooc = run_cli(exact + quoted((dir / "e.ply").string()) + " --memory-limit 1G", dir);
  REQUIRE(mem.rc == 0);
  REQUIRE(ooc.rc == 0);
  CHECK(file_bytes(dir / "d.ply") == file_bytes(dir / "e.ply"));
  // --lock-border reaches the out-of-core run too: the same bytes as in memory, and not
  // those without it (the plane's border gives up vertices then).
  const CliRun mem_locked = run_cli(exact + quoted((dir / "f.ply").string()) + " --lock-border", dir);
  const CliRun ooc_locked = run_cli(exact + quoted((dir / "g.ply").string()) + " --lock-border --memory-limit 1G --json", dir);
  REQUIRE(mem_locked.rc == 0);
  REQUIRE(ooc_locked.rc == 0);
  CHECK(file_bytes(dir / "f.ply") == file_bytes(dir / "g.ply"));
  CHECK(file_bytes(dir / "f.ply") != file_bytes(dir / "e.ply"));
  CHECK(ooc_locked.out.find("\"lock_border\": true") != std::string::npos);
}

TEST_CASE("simplify --memory-limit: what it does not take is a clear error", "[outofcore][simplify][cli]") {
  const auto dir = scratch_dir("ooc_simplify_errors");
  const std::string in = (dir / "sphere.ply").string();
  write_ply(in, make_bumpy_sphere(5), {});
  const std::string base = "simplify " + quoted(in) + " --ratio 0.1 --backend cpu ";
  const CliRun small = run_cli(base + "-o " + quoted((dir / "b.ply").string()) + " --memory-limit 20M", dir);
  CHECK(small.rc == 1);
  CHECK(small.err.find("the smallest workable limit is about") != std::string::npos);
  CHECK(!std::filesystem::exists(dir / "b.ply"));
  const CliRun plain_small =
      run_cli(base + "-o " + quoted((dir / "b.ply").string()) + " --weights none --memory-limit 20M", dir);
  CHECK(plain_small.rc == 1);
  CHECK(plain_small.err.find("too small to simplify") != std::string::npos);
  const CliRun obj = run_cli(base + "-o " + quoted((dir / "b.obj").string()) + " --memory-limit 1G", dir);
  CHECK(obj.rc != 0);
  CHECK(obj.err.find("writes a binary PLY") != std::string::npos);
  const CliRun error = run_cli("simplify " + quoted(in) + " --target-error 1 -o " + quoted((dir / "b.ply").string()) +
                                   " --memory-limit 1G",
                               dir);
  CHECK(error.rc != 0);
  CHECK(error.err.find("not --target-error") != std::string::npos);
  const CliRun from = run_cli(base + "-o " + quoted((dir / "b.ply").string()) + " --saliency-from " + quoted(in) +
                                  " --memory-limit 1G",
                              dir);
  CHECK(from.rc != 0);
  CHECK(from.err.find("--saliency-from") != std::string::npos);
  const std::string fifo = (dir / "pipe.ply").string();
  REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
  const CliRun pipe = run_cli("simplify " + quoted(fifo) + " --ratio 0.1 -o " + quoted((dir / "d.ply").string()) +
                                  " --memory-limit 1G",
                              dir, 60);
  CHECK(pipe.rc == 1);
  CHECK(pipe.err.find("regular files only") != std::string::npos);
  SaliencyWeightOptions rank;
  rank.curve = WeightCurve::Rank;
  CHECK_THROWS_WITH(simplify_file(in, (dir / "r.ply").string(), ratio(0.1, 2), rank, cpu(Method::Fast), {}),
                    Catch::Contains("rank curve"));
  SimplifyOptions bound;
  bound.target_error = 0.01;
  bound.tiles = 2;
  CHECK_THROWS_WITH(simplify_file(in, (dir / "r.ply").string(), bound, std::nullopt, cpu(Method::Fast), {}),
                    Catch::Contains("not target_error"));
}
