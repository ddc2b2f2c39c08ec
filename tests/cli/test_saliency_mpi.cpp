// `mpirun -np N meshsal saliency` (README, "Beyond one machine"): the ranks share the tiles
// and rank 0 writes the single-process run's bytes, in memory and with --memory-limit; a
// failing rank ends the run. Each run is under `timeout`, so a hang fails the test. Without
// MPI in the program, or without mpirun: "SKIPPED: no MPI".
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include "cli/synthetic.h"
#include "cli_run.h"
#include "json_check.h"
#include "mpi_run.h"
#include "test_util.h"

using namespace meshsal_test;
namespace fs = std::filesystem;

namespace {

std::string file_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

TEST_CASE("mpirun saliency: 2 and 3 ranks write the single-process bytes", "[mpi][tiles]") {
  if (skip_without_mpi()) return;
  const auto dir = scratch_dir("mpi_saliency");
  const std::string in = (dir / "in.ply").string();
  meshsal::write_ply(in, meshsal::make_bumpy_sphere(4), {});
  for (const char* method : {"exact", "fast"}) {
    const std::string common = quoted(in) + " --backend cpu --threads 1 --method " + method;
    // One process, untiled: the reference the exact method must equal bit for bit.
    const CliRun one = run_cli("saliency " + common + " -q -o " + quoted((dir / "one.ply").string()), dir);
    REQUIRE(one.rc == 0);
    const CliRun tiled = run_cli("saliency " + common + " -q --tiles 3 -o " + quoted((dir / "tiled.ply").string()), dir);
    REQUIRE(tiled.rc == 0);
    if (std::string(method) == "exact") CHECK(file_bytes(dir / "one.ply") == file_bytes(dir / "tiled.ply"));
    for (int ranks : {2, 3}) {
      for (const std::string mode : {"", " --memory-limit 1G"}) {
        INFO(method << " ranks " << ranks << mode);
        const fs::path out = dir / ("np" + std::to_string(ranks) + ".ply");
        std::filesystem::remove(out);
        const CliRun r = run_mpi(np(ranks, "saliency " + common + " --tiles 3 --json" + mode + " -o " + quoted(out.string())), dir);
        INFO(r.err);
        REQUIRE(r.rc == 0);
        // Rank 0 alone reports (one JSON object) and writes.
        CHECK(json_valid(r.out.substr(0, r.out.find_last_not_of("\n") + 1)));
        CHECK(json_number(r.out, "ranks") == ranks);
        CHECK(json_number(r.out, "tiles") == 27);
        CHECK(file_bytes(out) == file_bytes(dir / "tiled.ply"));
      }
    }
  }
}

TEST_CASE("mpirun saliency: ranks on one machine share its cores unless --threads says", "[mpi]") {
  if (skip_without_mpi()) return;
  const auto dir = scratch_dir("mpi_threads");
  const std::string in = (dir / "in.ply").string();
  meshsal::write_ply(in, meshsal::make_bumpy_sphere(3), {});
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  for (int ranks : {1, 2, 3}) {
    for (const std::string mode : {"", " --memory-limit 1G"}) {
      INFO("ranks " << ranks << mode);
      const fs::path out = dir / "np.ply";
      const CliRun r = run_mpi(np(ranks, "saliency " + quoted(in) + " --backend cpu --json" + mode + " -o " +
                                             quoted(out.string())), dir);
      INFO(r.err);
      REQUIRE(r.rc == 0);
      CHECK(json_number(r.out, "threads_per_rank") == std::max(1u, cores / unsigned(ranks)));
      const CliRun given = run_mpi(np(ranks, "saliency " + quoted(in) + " --backend cpu --threads 3 --json" + mode +
                                                 " -o " + quoted(out.string())), dir);
      REQUIRE(given.rc == 0);
      CHECK(json_number(given.out, "threads_per_rank") == 3);
    }
  }
  // One process: every core, as --threads 0 says.
  const CliRun one = run_cli("saliency " + quoted(in) + " --backend cpu --json -o " + quoted((dir / "one.ply").string()), dir);
  REQUIRE(one.rc == 0);
  CHECK(json_number(one.out, "threads_per_rank") == cores);
}

TEST_CASE("mpirun saliency: a failing rank ends the run with its message", "[mpi]") {
  if (skip_without_mpi()) return;
  const auto dir = scratch_dir("mpi_saliency_fail");
  const std::string in = (dir / "in.ply").string();
  meshsal::write_ply(in, meshsal::make_bumpy_sphere(3), {});
  // Rank 1 is given a file that does not exist: it fails while rank 0 waits in a collective.
  const std::string good = "saliency " + quoted(in) + " --backend cpu -o " + quoted((dir / "o.ply").string());
  const std::string bad = "saliency " + quoted((dir / "missing.ply").string()) + " --backend cpu -o " +
                          quoted((dir / "o.ply").string());
  // (MPI_Abort ends rank 0 where it stands: its temporary folder stays, in the test's own.)
  for (const std::string& mode : {std::string(), " --memory-limit 1G --temp-dir " + quoted(dir.string())}) {
    INFO(mode);
    const CliRun r = run_mpi(np(1, good + mode) + " : " + np(1, bad + mode), dir);
    CHECK(r.rc == 1);
    CHECK(r.err.find("missing.ply") != std::string::npos);
    CHECK(!fs::exists(dir / "o.ply"));
  }
}
