// `mpirun -np N meshsal simplify` (README, "Across machines: MPI"; issue 41): the ranks share
// the saliency's tiles and the passes' groups, and rank 0 writes the bytes one process
// writes with the same tiles, in memory and with --memory-limit; JSON and the summary name
// the ranks. Each run is under `timeout`, so a hang fails the test. Without MPI in the
// program, or without mpirun: "SKIPPED: no MPI".
#include <filesystem>
#include <string>

#include "cli/synthetic.h"
#include "cli_run.h"
#include "json_check.h"
#include "mpi_run.h"
#include "out_of_core_util.h"
#include "test_util.h"

using namespace meshsal_test;
namespace fs = std::filesystem;

TEST_CASE("mpirun simplify: 2 and 3 ranks write the single-process bytes", "[mpi][simplify]") {
  if (skip_without_mpi()) return;
  const auto dir = scratch_dir("mpi_simplify");
  const std::string in = (dir / "in.ply").string();
  // 20480 faces: the first rounds keep 3 tiles (round_tiles), so the ranks share groups.
  meshsal::write_ply(in, meshsal::make_bumpy_sphere(5), {});
  for (const std::string weights : {"balanced", "none"}) {
    for (const std::string& mode : {std::string(), " --memory-limit 1G --temp-dir " + quoted(dir.string())}) {
      const std::string common = quoted(in) + " --backend cpu --threads 1 --method fast --ratio 0.1 --tiles 3 --weights " +
                                 weights + mode;
      const CliRun one = run_cli("simplify " + common + " -q -o " + quoted((dir / "one.ply").string()), dir);
      REQUIRE(one.rc == 0);
      for (int ranks : {2, 3}) {
        INFO("weights " << weights << ", ranks " << ranks << mode);
        const fs::path out = dir / ("np" + std::to_string(ranks) + ".ply");
        fs::remove(out);
        const CliRun r = run_mpi(np(ranks, "simplify " + common + " --json -o " + quoted(out.string())), dir);
        INFO(r.err);
        REQUIRE(r.rc == 0);
        // Rank 0 alone reports (one JSON object) and writes.
        CHECK(json_valid(r.out.substr(0, r.out.find_last_not_of("\n") + 1)));
        CHECK(json_number(r.out, "ranks") == ranks);
        CHECK(json_number(r.out, "threads_per_rank") == 1);
        CHECK(json_number(r.out, "collapses") > 0);
        CHECK(file_bytes(out) == file_bytes(dir / "one.ply"));
      }
    }
  }
  // The human summary names the tiles and the ranks that shared them.
  const CliRun human = run_mpi(np(2, "simplify " + quoted(in) + " --backend cpu --ratio 0.1 --tiles 3 -o " +
                                         quoted((dir / "h.ply").string())), dir);
  REQUIRE(human.rc == 0);
  CHECK(human.out.find("tiles      3, shared by 2 ranks") != std::string::npos);
  // Without --tiles the ranks take default_mpi_tiles (2 for 2 ranks): the bytes of --tiles 2.
  const CliRun plain = run_cli("simplify " + quoted(in) + " --backend cpu --ratio 0.1 --tiles 2 -q -o " +
                                   quoted((dir / "t2.ply").string()), dir);
  REQUIRE(plain.rc == 0);
  const CliRun dflt = run_mpi(np(2, "simplify " + quoted(in) + " --backend cpu --ratio 0.1 -q -o " +
                                        quoted((dir / "d.ply").string())), dir);
  REQUIRE(dflt.rc == 0);
  CHECK(file_bytes(dir / "d.ply") == file_bytes(dir / "t2.ply"));
}

TEST_CASE("mpirun simplify: what shared simplification does not take is said once", "[mpi][simplify]") {
  if (skip_without_mpi()) return;
  const auto dir = scratch_dir("mpi_simplify_refused");
  const std::string in = (dir / "in.ply").string();
  meshsal::write_ply(in, meshsal::make_bumpy_sphere(3), {});
  const std::string out = " -o " + quoted((dir / "o.ply").string());
  struct Case {
    std::string args, says;
  };
  const Case cases[] = {
      {"--lod 0.5,0.2", "--lod runs in one process"},
      {"--target-error 1", "not --target-error"},
      {"--ratio 0.1 --tiles 1", "give --tiles N"},
  };
  for (const Case& c : cases) {
    INFO(c.args);
    const CliRun r = run_mpi(np(2, "simplify " + quoted(in) + " --backend cpu " + c.args + out), dir);
    CHECK(r.rc == 2);
    CHECK(r.err.find(c.says) != std::string::npos);
    // Said once, by rank 0, not once per rank.
    CHECK(r.err.find(c.says) == r.err.rfind(c.says));
    CHECK(!fs::exists(dir / "o.ply"));
  }
}
