// Issue 36 (10): `mpirun -np N meshsal COMMAND`. A command that does not share its work over
// the ranks (all but saliency and batch) runs on rank 0 alone, as one process: the other
// ranks end at once with 0, silently, so the output is written once and an error said
// once. A command that does, stopped before its work by an error every rank finds alike (a
// usage error, a missing input), says it once and ends every rank quietly: no MPI_Abort and
// its banner. Each run is under `timeout`; without MPI: "SKIPPED: no MPI".
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "cli/synthetic.h"
#include "cli_run.h"
#include "mpi_run.h"
#include "test_util.h"

using namespace meshsal_test;
namespace fs = std::filesystem;

namespace {

CliRun run_mpi(int ranks, const std::string& args, const fs::path& dir) {
  const fs::path out = dir / "mpi_stdout.txt", err = dir / "mpi_stderr.txt";
  const std::string cmd = mpirun_command() + "-np " + std::to_string(ranks) + " " + cli_path() + " " + args + " > " +
                          quoted(out.string()) + " 2> " + quoted(err.string()) + " < /dev/null";
  CliRun r;
  r.rc = exit_status(std::system(cmd.c_str()));
  r.out = read_file(out.string());
  r.err = read_file(err.string());
  return r;
}

size_t count_of(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// What Open MPI prints when a rank calls MPI_Abort or a rank dies or leaves without
// MPI_Finalize.
void check_no_abort_noise(const std::string& err) {
  CHECK(err.find("MPI_ABORT") == std::string::npos);
  CHECK(err.find("help message") == std::string::npos);
  CHECK(err.find("without calling \"finalize\"") == std::string::npos);
  CHECK(err.find("PMIX ERROR") == std::string::npos);
  CHECK(err.find("meshsal (rank") == std::string::npos);
}

}  // namespace

TEST_CASE("mpirun: a command that does not use the ranks runs on rank 0 alone", "[mpi]") {
  if (skip_without_mpi()) return;
  const auto dir = scratch_dir("mpi_one_rank");
  const std::string in = (dir / "in.ply").string();
  meshsal::write_ply(in, meshsal::make_bumpy_sphere(3), {});
  // One simplification, one report, one file.
  const CliRun simplify = run_mpi(3, "simplify " + quoted(in) + " -o " + quoted((dir / "s.obj").string()) +
                                         " --ratio 0.5 --backend cpu --threads 1", dir);
  INFO(simplify.out << simplify.err);
  CHECK(simplify.rc == 0);
  CHECK(count_of(simplify.out, "wrote") == 1);
  CHECK(simplify.err.empty());
  CHECK(meshsal::load_mesh((dir / "s.obj").string()).triangle_count() == 640);
  // render and view: the same.
  const CliRun render = run_mpi(2, "render " + quoted(in) + " -o " + quoted((dir / "r.png").string()) +
                                       " --backend cpu --threads 1", dir);
  INFO(render.err);
  CHECK(render.rc == 0);
  CHECK(count_of(render.out, "wrote") == 1);
  // An error: said once, the status of one process, no Open MPI abort.
  const CliRun missing = run_mpi(3, "view " + quoted((dir / "missing.ply").string()) + " -o " +
                                        quoted((dir / "v.html").string()), dir);
  INFO(missing.err);
  CHECK(missing.rc == 1);
  CHECK(count_of(missing.err, "error: ") == 1);
  CHECK(missing.err.find("error: " + (dir / "missing.ply").string() + ": cannot open") == 0);
  check_no_abort_noise(missing.err);
  const CliRun usage = run_mpi(2, "simplify " + quoted(in) + " -o " + quoted((dir / "u.obj").string()) +
                                      " --lod 0.2,0.5", dir);
  CHECK(usage.rc == 2);
  CHECK(count_of(usage.err, "error: --lod") == 1);
  check_no_abort_noise(usage.err);
  CHECK_FALSE(fs::exists(dir / "u_lod1.obj"));
}

TEST_CASE("mpirun saliency and batch: an error every rank finds before the work is said once, without MPI_Abort",
          "[mpi]") {
  if (skip_without_mpi()) return;
  const auto dir = scratch_dir("mpi_said_once");
  const std::string in = (dir / "in.ply").string();
  meshsal::write_ply(in, meshsal::make_bumpy_sphere(3), {});
  const std::string out = quoted((dir / "o.ply").string());
  struct Case {
    std::string args, said;
    int rc;
  };
  for (const Case& c : std::vector<Case>{
           {"saliency " + quoted(in) + " -o " + out + " --memory-limit abc", "error: --memory-limit: ", 2},
           {"saliency " + quoted(in) + " -o " + out + " --memory-limit 0.5", "error: --memory-limit: ", 2},
           {"saliency " + quoted((dir / "missing.ply").string()) + " -o " + out + " --backend cpu",
            "error: " + (dir / "missing.ply").string() + ": cannot open", 1},
           {"saliency " + quoted(in) + " -o " + quoted((dir / "no" / "o.ply").string()),
            "error: " + (dir / "no" / "o.ply").string() + ": cannot write", 1},
           {"batch " + quoted(in) + " -o " + quoted((dir / "b").string()) + " --lod 0.5,0.5", "error: --lod: ", 2}}) {
    const CliRun r = run_mpi(2, c.args, dir);
    INFO(c.args << "\nstderr: " << r.err);
    CHECK(r.rc == c.rc);
    CHECK(count_of(r.err, "error: ") == 1);
    CHECK(r.err.find(c.said) == 0);
    check_no_abort_noise(r.err);
    CHECK_FALSE(fs::exists(dir / "o.ply"));
  }
  // --help once.
  const CliRun help = run_mpi(2, "saliency --help", dir);
  CHECK(help.rc == 0);
  CHECK(count_of(help.out, "Usage:") == 1);
}
