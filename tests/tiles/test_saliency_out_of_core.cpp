// Out of core (saliency_file, meshsal saliency --memory-limit): the same bytes as the
// in-memory run, the peak resident memory under the limit, clear errors.
#include <sys/stat.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <cmath>

#include "cli/synthetic.h"
#include "cli_run.h"
#include "out_of_core_util.h"
#include "json_check.h"
#include "test_util.h"

using namespace meshsal;
using namespace meshsal_test;

namespace {

// The saliency two PLY files hold for the vertices of `mesh` agree to 1e-4 of the maximum.
void check_same_map(const std::filesystem::path& a, const std::filesystem::path& b, const Mesh& mesh) {
  const std::vector<double> x = load_saliency_ply(a.string(), mesh), y = load_saliency_ply(b.string(), mesh);
  CHECK(rel_error(x, y) <= 1e-4);
}

// What the in-memory run writes: S, with `dump` the curvature and raw maps too.
void write_whole(const std::filesystem::path& path, const Mesh& mesh, const SaliencyResult& r, bool dump) {
  std::vector<PlyFloatProperty> extra;
  std::vector<std::string> names;
  if (dump) {
    extra.push_back({"curvature", &r.curvature});
    for (size_t k = 0; k < r.raw.size(); ++k) names.push_back("saliency_raw_" + std::to_string(k));
    for (size_t k = 0; k < r.raw.size(); ++k) extra.push_back({names[k], &r.raw[k]});
  }
  write_saliency_ply(path.string(), mesh, r.saliency, extra, r.is_point);
}

}  // namespace

TEST_CASE("out of core writes the in-memory run's bytes", "[outofcore]") {
  const auto dir = scratch_dir("ooc_bytes");
  const Mesh meshes[] = {make_bumpy_sphere(4), make_plane_with_bump(2.0, 50, 0.3, 0.2), far_sphere()};
  int i = 0;
  for (const Mesh& mesh : meshes) {
    const std::string in = (dir / ("in" + std::to_string(i++) + ".ply")).string();
    write_ply(in, mesh, {});
    const Mesh loaded = load_mesh(in);
    for (Method method : {Method::Exact, Method::Fast})
      for (bool dump : {false, true}) {
        INFO(in << " method " << int(method) << " dump " << dump);
        const SaliencyResult r = compute_saliency(loaded, cpu(method));
        write_whole(dir / "whole.ply", loaded, r, dump);
        SaliencyOptions o = cpu(method);
        o.tiles = 4;
        OutOfCoreOptions ooc;
        ooc.dump_scales = dump;
        ooc.temp_dir = dir.string();
        const OutOfCoreReport rep = saliency_file(in, (dir / "tiled.ply").string(), o, ooc);
        CHECK(rep.tiles >= 16);
        CHECK(rep.vertices == loaded.vertex_count());
        CHECK(rep.triangles == loaded.triangle_count());
        CHECK(rep.eps == r.eps);
        // The summary's statistics: saliency_stats' nearest-rank percentiles, streamed.
        const SaliencyStats st = saliency_stats(r);
        const double tol = method == Method::Exact ? 0 : 1e-6 * st.max;
        CHECK(std::fabs(rep.saliency_p10 - st.p10) <= tol);
        CHECK(std::fabs(rep.saliency_p50 - st.p50) <= tol);
        CHECK(std::fabs(rep.saliency_p90 - st.p90) <= tol);
        CHECK(std::fabs(rep.saliency_p99 - st.p99) <= tol);
        CHECK(rep.saliency_p10 < rep.saliency_p99);
        if (method == Method::Exact) {
          CHECK(file_bytes(dir / "tiled.ply") == file_bytes(dir / "whole.ply"));
        } else {
          // The fast method's sums over cells run in another order in a tile: the same map
          // to rounding, well inside its 1e-4.
          check_same_map(dir / "whole.ply", dir / "tiled.ply", loaded);
        }
      }
  }
  // Its temporary folders are gone.
  for (const auto& e : std::filesystem::directory_iterator(dir))
    CHECK(e.path().filename().string().rfind("meshsal-tiles-", 0) == std::string::npos);
}

// The output is written a block of vertices at a time, each tile's results read with a
// cursor (TileResultReader): several blocks, with and without the scales kept, exact bytes.
TEST_CASE("out of core: the results of every tile over several output blocks", "[outofcore]") {
  const auto dir = scratch_dir("ooc_blocks");
  const std::string in = (dir / "plane.ply").string();
  write_ply(in, make_plane_with_bump(2.0, 330, 0.3, 0.2), {});  // 109,561 vertices
  const Mesh loaded = load_mesh(in);
  REQUIRE(loaded.vertex_count() > 2 * 65536 - 30000);
  const SaliencyResult r = compute_saliency(loaded, cpu(Method::Exact));
  for (bool dump : {false, true}) {
    INFO("dump " << dump);
    write_whole(dir / "whole.ply", loaded, r, dump);
    SaliencyOptions o = cpu(Method::Exact);
    o.tiles = 3;
    OutOfCoreOptions ooc;
    ooc.dump_scales = dump;
    ooc.temp_dir = dir.string();
    // The writer's blocks are a quarter of the limit (at least 65,536 vertices): two here.
    ooc.memory_limit = uint64_t(40) << 20;
    const OutOfCoreReport rep = saliency_file(in, (dir / "tiled.ply").string(), o, ooc);
    CHECK(rep.tiles >= 9);
    CHECK(file_bytes(dir / "tiled.ply") == file_bytes(dir / "whole.ply"));
  }
}

TEST_CASE("out of core converts other formats once and gives the same bytes", "[outofcore]") {
  const auto dir = scratch_dir("ooc_obj");
  const std::string obj = (dir / "in.obj").string();
  write_obj(obj, make_bumpy_sphere(3));
  const CliRun whole = run_cli("saliency " + quoted(obj) + " -o " + quoted((dir / "a.ply").string()) + " -q --backend cpu", dir);
  REQUIRE(whole.rc == 0);
  const CliRun tiled = run_cli("saliency " + quoted(obj) + " -o " + quoted((dir / "b.ply").string()) +
                                   " -q --backend cpu --memory-limit 1G --tiles 3", dir);
  INFO(tiled.err);
  REQUIRE(tiled.rc == 0);
  CHECK(file_bytes(dir / "a.ply") == file_bytes(dir / "b.ply"));
}

TEST_CASE("out of core: --memory-limit holds the peak resident memory under the limit", "[outofcore][cli]") {
  const auto dir = scratch_dir("ooc_limit");
  const std::string in = (dir / "plane.ply").string();
  write_ply(in, make_plane_with_bump(2.0, 600, 0.3, 0.2), {});  // 361,201 vertices
  const CliRun whole = run_cli("saliency " + quoted(in) + " -o " + quoted((dir / "a.ply").string()) +
                                   " --method fast --backend cpu --json", dir);
  REQUIRE(whole.rc == 0);
  const double peak_whole = json_number(whole.out, "peak_rss");
  REQUIRE(peak_whole > 0);
  // Three quarters of the in-memory peak: tiles it must be. (Half of it was below the
  // smallest workable limit once the in-memory fast path shed its 1-rings, issue 25.)
  const uint64_t limit = uint64_t(peak_whole * 0.75);
  const CliRun tiled = run_cli("saliency " + quoted(in) + " -o " + quoted((dir / "b.ply").string()) +
                                   " --method fast --backend cpu --json --memory-limit " + std::to_string(limit), dir);
  INFO(tiled.err);
  REQUIRE(tiled.rc == 0);
  INFO(tiled.out);
  if (!kAddressSanitizer) {
    CHECK(json_number(tiled.out, "tiles") > 1);
    CHECK(json_number(tiled.out, "peak_rss") < double(limit));
  }
  check_same_map(dir / "a.ply", dir / "b.ply", load_mesh(in));
}

TEST_CASE("out of core: bad limits and inputs are clear errors", "[outofcore][cli]") {
  const auto dir = scratch_dir("ooc_errors");
  const std::string in = (dir / "sphere.ply").string();
  write_ply(in, make_bumpy_sphere(5), {});
  // Too small for one tile: the error names the smallest workable limit, nothing is written.
  const CliRun small = run_cli("saliency " + quoted(in) + " -o " + quoted((dir / "b.ply").string()) +
                                   " --backend cpu --memory-limit 15M", dir);
  CHECK(small.rc == 1);
  CHECK(small.err.find("memory limit 15M is too small") != std::string::npos);
  CHECK(small.err.find("the smallest workable limit is about") != std::string::npos);
  CHECK(!std::filesystem::exists(dir / "b.ply"));
  // The limit it names works.
  const size_t at = small.err.find("about ", small.err.find("smallest workable"));
  const std::string named = small.err.substr(at + 6, small.err.find_first_of(" \n", at + 6) - at - 6);
  const CliRun ok = run_cli("saliency " + quoted(in) + " -o " + quoted((dir / "b.ply").string()) +
                                " --backend cpu --json --memory-limit " + named, dir);
  INFO(small.err << ok.err);
  CHECK(ok.rc == 0);
  if (!kAddressSanitizer) CHECK(json_number(ok.out, "peak_rss") < double(parse_memory_size(named)));

  for (const char* bad : {"0", "-5M", "abc", "12Q", "1e30G"}) CHECK_THROWS_AS(parse_memory_size(bad), Error);
  CHECK(parse_memory_size("700M") == uint64_t(700) << 20);
  CHECK(parse_memory_size("1.5G") == uint64_t(3) << 29);
  CHECK(parse_memory_size("4096K") == 4096 << 10);  // the rest: test_memory_size.cpp
  const CliRun junk = run_cli("saliency " + quoted(in) + " -o " + quoted((dir / "c.ply").string()) + " --memory-limit lots", dir);
  CHECK(junk.rc == 2);
  CHECK(junk.err.find("error: --memory-limit: must be a decimal number") == 0);
  // A FIFO cannot be read twice: refused, not hung.
  const std::string fifo = (dir / "pipe.ply").string();
  REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
  const CliRun pipe = run_cli("saliency " + quoted(fifo) + " -o " + quoted((dir / "d.ply").string()) +
                                  " --memory-limit 1G", dir, 60);
  CHECK(pipe.rc == 1);
  CHECK(pipe.err.find("regular files only") != std::string::npos);
  // The GPU backend is refused.
  const CliRun gpu = run_cli("saliency " + quoted(in) + " -o " + quoted((dir / "e.ply").string()) +
                                 " --backend gpu --memory-limit 1G", dir);
  CHECK(gpu.rc == 1);
  CHECK(gpu.err.find("out of core runs on the CPU") != std::string::npos);
}

TEST_CASE("out of core: a mesh within one tile, and hostile PLY files", "[outofcore]") {
  const auto dir = scratch_dir("ooc_hostile");
  const Mesh mesh = make_bumpy_sphere(3);
  const std::string in = (dir / "in.ply").string();
  write_ply(in, mesh, {});
  // A limit far above the mesh: one tile, the in-memory bytes.
  const Mesh loaded = load_mesh(in);
  const SaliencyResult r = compute_saliency(loaded, cpu(Method::Exact));
  write_saliency_ply((dir / "whole.ply").string(), loaded, r.saliency, {}, r.is_point);
  OutOfCoreOptions ooc;
  ooc.memory_limit = uint64_t(4) << 30;
  ooc.temp_dir = dir.string();
  const OutOfCoreReport one = saliency_file(in, (dir / "one.ply").string(), cpu(Method::Exact), ooc);
  CHECK(one.tiles == 1);
  CHECK(file_bytes(dir / "one.ply") == file_bytes(dir / "whole.ply"));

  // Damaged copies: each an Error naming the problem, no output, no temporary folder left.
  const std::string good = file_bytes(in);
  const size_t body = good.find("end_header\n") + 11;
  struct Case {
    std::string name, bytes, message;
  };
  std::string huge = good;
  huge.replace(huge.find("element vertex "), std::string("element vertex ").size() + std::to_string(loaded.vertex_count()).size(),
               "element vertex 5000000000");
  std::string bad_index = good;
  const uint32_t beyond = uint32_t(loaded.vertex_count() + 7);
  std::memcpy(&bad_index[body + loaded.vertex_count() * 12 + 1], &beyond, 4);  // the first face's first corner
  const Case cases[] = {
      {"truncated.ply", good.substr(0, body + (good.size() - body) / 2), "file ends before"},
      {"huge.ply", huge, "more than 4294967295 vertices"},
      {"index.ply", bad_index, "uses vertex " + std::to_string(beyond)},
      {"ascii.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                    "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
       ""},
      {"noheader.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\n", "ends before end_header"},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    const std::string path = (dir / c.name).string();
    std::ofstream(path, std::ios::binary) << c.bytes;
    const std::string out = (dir / ("out_" + c.name)).string();
    if (c.message.empty()) {  // ASCII PLY: read whole once, converted, computed
      CHECK_NOTHROW(saliency_file(path, out, cpu(Method::Exact), ooc));
      continue;
    }
    try {
      saliency_file(path, out, cpu(Method::Exact), ooc);
      FAIL("no error");
    } catch (const Error& e) {
      INFO(e.what());
      CHECK(std::string(e.what()).find(c.message) != std::string::npos);
    }
    CHECK(!std::filesystem::exists(out));
  }
  for (const auto& e : std::filesystem::directory_iterator(dir))
    CHECK(e.path().filename().string().rfind("meshsal-tiles-", 0) == std::string::npos);
}

TEST_CASE("out of core: batch --memory-limit writes what batch writes in memory", "[outofcore][cli]") {
  const auto dir = scratch_dir("ooc_batch");
  std::filesystem::create_directories(dir / "in");
  write_ply((dir / "in" / "sphere.ply").string(), make_bumpy_sphere(4), {});
  write_obj((dir / "in" / "plane.obj").string(), make_plane_with_bump(2.0, 40, 0.3, 0.2));
  write_ply((dir / "in" / "cube.ply").string(), make_cube(10), {});
  const std::string in = quoted((dir / "in").string());
  const CliRun whole = run_cli("batch " + in + " -o " + quoted((dir / "a").string()) + " --backend cpu -q", dir);
  REQUIRE(whole.rc == 0);
  const CliRun ooc = run_cli("batch " + in + " -o " + quoted((dir / "b").string()) +
                                 " --backend cpu -q --memory-limit 200M --temp-dir " + quoted(dir.string()), dir);
  INFO(ooc.err);
  REQUIRE(ooc.rc == 0);
  for (const char* name : {"sphere", "plane", "cube"}) {
    INFO(name);
    const std::string file = std::string(name) + "_saliency.ply";
    CHECK(file_bytes(dir / "a" / file) == file_bytes(dir / "b" / file));
  }
  const std::string log = file_bytes(dir / "b" / "batch.jsonl");
  size_t lines = 0;
  for (size_t at = log.find("\"memory_limit\": 209715200"); at != std::string::npos;
       at = log.find("\"memory_limit\": 209715200", at + 1))
    ++lines;
  CHECK(lines == 3);
  // A rerun finds every model up to date.
  const CliRun again = run_cli("batch " + in + " -o " + quoted((dir / "b").string()) + " --backend cpu --memory-limit 200M", dir);
  CHECK(again.rc == 0);
  CHECK(again.out.find("3 skipped") != std::string::npos);
  // What needs the mesh in memory is refused before any work.
  std::filesystem::create_directories(dir / "empty");
  check_usage_error("batch " + in + " -o " + quoted((dir / "empty" / "c").string()) + " --memory-limit 200M --view",
                    "--memory-limit", dir / "empty");
  check_usage_error("batch " + in + " -o " + quoted((dir / "empty" / "c").string()) +
                        " --memory-limit 200M --target-error 1",
                    "--memory-limit", dir / "empty");
}

TEST_CASE("out of core: batch --memory-limit --simplify writes what simplify --memory-limit writes",
          "[outofcore][cli][simplify]") {
  const auto dir = scratch_dir("ooc_batch_simplify");
  std::filesystem::create_directories(dir / "in");
  write_ply((dir / "in" / "sphere.ply").string(), make_bumpy_sphere(4), {});
  write_ply((dir / "in" / "plane.ply").string(), make_plane_with_bump(2.0, 40, 0.3, 0.2), {});
  const std::string in = quoted((dir / "in").string());
  const std::string common = " --backend cpu --method fast --memory-limit 200M --temp-dir " + quoted(dir.string());
  const CliRun batch = run_cli("batch " + in + " -o " + quoted((dir / "b").string()) + " -q --simplify 0.1" + common, dir);
  INFO(batch.err);
  REQUIRE(batch.rc == 0);
  for (const char* name : {"sphere", "plane"}) {
    INFO(name);
    const std::string alone = (dir / (std::string(name) + ".ply")).string();
    const CliRun one = run_cli("simplify " + quoted((dir / "in" / (std::string(name) + ".ply")).string()) + " -o " +
                                   quoted(alone) + " -q --ratio 0.1" + common,
                               dir);
    REQUIRE(one.rc == 0);
    CHECK(file_bytes(alone) == file_bytes(dir / "b" / (std::string(name) + "_simplified.ply")));
    // Its saliency file came from the simplifier's tiles (S once): saliency --memory-limit's bytes.
    const std::string s_alone = (dir / (std::string(name) + "_s.ply")).string();
    const CliRun s = run_cli("saliency " + quoted((dir / "in" / (std::string(name) + ".ply")).string()) + " -o " +
                                 quoted(s_alone) + " -q" + common,
                             dir);
    REQUIRE(s.rc == 0);
    CHECK(file_bytes(s_alone) == file_bytes(dir / "b" / (std::string(name) + "_saliency.ply")));
  }
  // A rerun finds both up to date; the log names the simplified files.
  const CliRun again = run_cli("batch " + in + " -o " + quoted((dir / "b").string()) + " --simplify 0.1" + common, dir);
  CHECK(again.rc == 0);
  CHECK(again.out.find("2 skipped") != std::string::npos);
  CHECK(file_bytes(dir / "b" / "batch.jsonl").find("_simplified.ply") != std::string::npos);
}
