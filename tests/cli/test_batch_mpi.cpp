// `mpirun -np N meshsal batch` (README, "Across machines: MPI"): the models shared over the
// ranks, each computed once, the outputs and the log of a single-process run, resuming, and
// a failing rank ending the whole run. Each run is under `timeout`, so a hang fails the test
// instead of hanging it. Without MPI in the program, or without mpirun: "SKIPPED: no MPI".
#include <catch2/catch.hpp>

#include <iostream>
#include <string>
#include <thread>
#include <vector>

#include "cli/synthetic.h"
#include "json_check.h"
#include "mpi_run.h"
#include "test_batch_util.h"

using namespace meshsal_test;

namespace {

// mpirun ... SPEC, where SPEC is "-np N meshsal ARGS" (or MPMD parts joined by " : "), as
// root too, more ranks than cores allowed; ended after 120 s (rc 124) should it hang.
BatchRun run_batch_mpi(const std::string& spec, const fs::path& dir) {
  const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  const std::string cmd = mpirun_command() + spec + " > " + out.string() + " 2> " + err.string() + " < /dev/null";
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_text(out), read_text(err)};
}

// make_batch_inputs' four (one broken) and two more: six models, so that 2 and 3 ranks
// take several rounds.
fs::path six_models(const fs::path& dir) {
  const fs::path in = make_batch_inputs(dir);
  meshsal::write_obj((in / "a_small.obj").string(), meshsal::make_sphere(1.0, 1));
  meshsal::write_ply((in / "z_bumpy.ply").string(), meshsal::make_bumpy_sphere(1), {});
  return in;
}

const std::vector<std::string> kModels = {"a_small", "ball", "broken", "bumpy", "cube", "z_bumpy"};

size_t count_of(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// The log lines of a run as a single process would write them, but for the timings and
// the output folder: mesh, status, name, output file name, error, counts, saliency maximum.
std::string comparable(const std::string& line) {
  std::string s = json_text(line, "mesh") + " | " + json_text(line, "status") + " | " + json_text(line, "name") +
                  " | " + fs::path(json_text(line, "output")).filename().string() + " | " + json_text(line, "error");
  if (json_text(line, "status") == "done" || json_text(line, "status") == "skipped")
    s += " | " + std::to_string(json_number(line, "vertices")) + " " + std::to_string(json_number(line, "faces")) +
         " " + std::to_string(json_number(line, "max"));
  return s;
}

}  // namespace

TEST_CASE("batch mpi: 2 and 3 ranks compute each model once, outputs and log as one process makes them", "[batch][mpi]") {
  if (skip_without_mpi()) return;
  const fs::path dir = batch_scratch("mpi_same");
  const fs::path in = six_models(dir);
  const std::string common = " --backend cpu --threads 1";
  const BatchRun one = run_meshsal("batch " + in.string() + " -o " + (dir / "one").string() + common, dir);
  INFO("one process: " << one.err);
  REQUIRE(one.exit_code == 1);  // broken.obj fails; the others go on
  const std::vector<std::string> one_log = log_lines(dir / "one" / "batch.jsonl");
  REQUIRE(one_log.size() == 6);

  struct Case {
    int ranks;
    const char* shared;  // done models per rank: model k of those to compute goes to rank k % N
  };
  for (const Case c : {Case{2, "on 2 ranks (computed: 2, 3)"}, Case{3, "on 3 ranks (computed: 2, 2, 1)"}}) {
    const fs::path out = dir / ("np" + std::to_string(c.ranks));
    const BatchRun r = run_batch_mpi(np(c.ranks, "batch " + in.string() + " -o " + out.string() + common), dir);
    INFO(c.ranks << " ranks\nstdout: " << r.out << "\nstderr: " << r.err);
    CHECK(r.exit_code == 1);
    // One summary, from rank 0, counting every model once.
    CHECK(count_of(r.out, "batch: 6 models: 5 computed, 0 skipped, 1 failed") == 1);
    CHECK(r.out.find(c.shared) != std::string::npos);
    // The broken model's error once, as one process prints it.
    CHECK(count_of(r.err, "error: " + (in / "broken.obj").string() + ": line 3: face index 7") == 1);
    // One log, in model order, with the lines one process writes.
    const std::vector<std::string> log = log_lines(out / "batch.jsonl");
    REQUIRE(log.size() == one_log.size());
    for (size_t i = 0; i < log.size(); ++i) {
      CHECK(json_valid(log[i]));
      CHECK(comparable(log[i]) == comparable(one_log[i]));
    }
    // The same files, byte for byte.
    for (const std::string& m : kModels) {
      INFO(m);
      const fs::path ply = out / (m + "_saliency.ply");
      if (m == "broken") {
        CHECK_FALSE(fs::exists(ply));
        continue;
      }
      CHECK(read_text(ply) == read_text(dir / "one" / (m + "_saliency.ply")));
      CHECK(fs::exists(out / ".meshsal-batch" / (m + ".state")));
    }
  }
}

TEST_CASE("batch mpi: a rerun under mpirun skips what is done, as one process does", "[batch][mpi]") {
  if (skip_without_mpi()) return;
  const fs::path dir = batch_scratch("mpi_resume");
  const fs::path in = six_models(dir), out = dir / "out";
  const std::string common = " -o " + out.string() + " --backend cpu --threads 1";
  // A partial run: two of the six models, on 3 ranks (one rank has none).
  BatchRun r = run_batch_mpi(np(3, "batch " + (in / "ball.obj").string() + " " + (in / "cube.off").string() + common), dir);
  INFO("stdout: " << r.out << "\nstderr: " << r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("batch: 2 models: 2 computed, 0 skipped, 0 failed") != std::string::npos);
  const long long ball_time = mtime_ns(out / "ball_saliency.ply"), cube_time = mtime_ns(out / "cube_saliency.ply");
  REQUIRE(ball_time > 0);

  // All six on 2 ranks: the two done are skipped, the rest computed.
  r = run_batch_mpi(np(2, "batch " + in.string() + common), dir);
  INFO("stdout: " << r.out << "\nstderr: " << r.err);
  CHECK(r.exit_code == 1);
  CHECK(r.out.find("batch: 6 models: 3 computed, 2 skipped, 1 failed") != std::string::npos);
  CHECK(mtime_ns(out / "ball_saliency.ply") == ball_time);
  CHECK(mtime_ns(out / "cube_saliency.ply") == cube_time);
  std::vector<std::string> log = log_lines(out / "batch.jsonl");
  REQUIRE(log.size() == 2 + 6);  // the earlier run's lines stay, the new ones follow in order
  const std::vector<std::string> statuses = {"done", "skipped", "failed", "done", "skipped", "done"};
  for (size_t i = 0; i < 6; ++i) {
    INFO(log[2 + i]);
    CHECK(json_text(log[2 + i], "name") == kModels[i]);
    CHECK(json_text(log[2 + i], "status") == statuses[i]);
  }

  // Again on 3 ranks: nothing left but the broken model, which fails again.
  r = run_batch_mpi(np(3, "batch " + in.string() + common), dir);
  INFO("stdout: " << r.out << "\nstderr: " << r.err);
  CHECK(r.exit_code == 1);
  CHECK(r.out.find("batch: 6 models: 0 computed, 5 skipped, 1 failed") != std::string::npos);
  CHECK(log_lines(out / "batch.jsonl").size() == 2 + 6 + 6);
  CHECK(mtime_ns(out / "ball_saliency.ply") == ball_time);
}

TEST_CASE("batch mpi: a rank that fails ends every rank with its message and status", "[batch][mpi]") {
  if (skip_without_mpi()) return;
  const fs::path dir = batch_scratch("mpi_fail");
  const fs::path in = six_models(dir), out = dir / "out";
  const std::string good = "batch " + in.string() + " -o " + out.string() + " --backend cpu --threads 1";
  // Rank 1's output folder goes through a regular file: it cannot be made there, while
  // rank 0 goes on to the first collective. (mpirun A : B gives rank 1 its own command.)
  std::ofstream(dir / "a_file") << "not a folder\n";
  BatchRun r = run_batch_mpi(np(1, good) + " : " +
                           np(1, "batch " + in.string() + " -o " + (dir / "a_file" / "out").string()), dir);
  INFO("stdout: " << r.out << "\nstderr: " << r.err);
  CHECK(r.exit_code == 1);  // the status of rank 1's error, not timeout's 124
  CHECK(r.err.find("meshsal (rank 1): error: " + (dir / "a_file" / "out").string()) != std::string::npos);
  CHECK_FALSE(fs::exists(out / "batch.jsonl"));  // nothing computed or logged

  // A usage error on rank 1 only: status 2.
  r = run_batch_mpi(np(1, good) + " : " + np(1, "batch " + in.string() + " -o " + out.string() + " --scales x"), dir);
  INFO("stdout: " << r.out << "\nstderr: " << r.err);
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("meshsal (rank 1): error: --scales") != std::string::npos);

  // Ranks given other inputs would share out other models: every rank stops.
  r = run_batch_mpi(np(1, good) + " : " + np(1, "batch " + (in / "ball.obj").string() + " -o " + out.string()), dir);
  INFO("stdout: " << r.out << "\nstderr: " << r.err);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("error: batch: rank 1 has other models to compute than rank 0") != std::string::npos);
  CHECK_FALSE(fs::exists(out / "batch.jsonl"));
}

TEST_CASE("batch mpi: ranks on one machine share its cores and the summary says how many each", "[batch][mpi]") {
  if (skip_without_mpi()) return;
  const fs::path dir = batch_scratch("mpi_threads");
  const fs::path in = six_models(dir);
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const BatchRun r = run_batch_mpi(np(2, "batch " + (in / "ball.obj").string() + " -o " + (dir / "out").string() +
                                       " --backend cpu --json"), dir);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(json_number(r.out, "ranks") == 2);
  CHECK(json_number(r.out, "threads_per_rank") == std::max(1u, cores / 2));
}
