// batch_ranks.h: a round's results as bytes and back (what ranks send rank 0), and the
// one-process answers of the MPI wrapper (no mpirun: nothing is sent).
#include <catch2/catch.hpp>

#include <stdexcept>

#include "cli/batch_ranks.h"
#include "cli/mpi_world.h"

using meshsal::cli::ModelResult;

TEST_CASE("batch ranks: results survive the trip as bytes, cut bytes are refused", "[batch]") {
  ModelResult a;
  a.index = 7;
  a.status = "done";
  a.line = "{\"mesh\": \"x\\u0000y.obj\"}";
  a.notes = {"note: one", std::string("two\0with a NUL", 14)};
  a.has_view = true;
  a.seconds = 0.1 + 0.2;
  a.rank = 3;
  ModelResult b;
  b.index = 8;
  b.status = "failed";
  b.error = "b.obj: line 3: bad";
  const std::vector<uint8_t> bytes = meshsal::cli::pack_results({a, b});
  const std::vector<ModelResult> back = meshsal::cli::unpack_results(bytes);
  REQUIRE(back.size() == 2);
  CHECK(back[0].index == 7);
  CHECK(back[0].status == "done");
  CHECK(back[0].line == a.line);
  CHECK(back[0].notes == a.notes);
  CHECK(back[0].has_view);
  CHECK(back[0].seconds == a.seconds);
  CHECK(back[0].rank == 3);
  CHECK(back[1].status == "failed");
  CHECK(back[1].error == b.error);
  CHECK_FALSE(back[1].has_view);
  CHECK(meshsal::cli::unpack_results(meshsal::cli::pack_results({})).empty());
  for (size_t cut : {size_t(1), size_t(9), bytes.size() / 2, bytes.size() - 1}) {
    INFO(cut);
    const std::vector<uint8_t> part(bytes.begin(), bytes.begin() + long(cut));
    CHECK_THROWS_AS(meshsal::cli::unpack_results(part), std::runtime_error);
  }
}

TEST_CASE("batch ranks: without mpirun one inactive rank, and the collectives give back what is given",
          "[batch]") {
  using namespace meshsal::cli;
  // The tests are not started by mpirun and the test binary has no MPI: mpi_start is a no-op.
  int argc = 1;
  char arg0[] = "meshsal_tests";
  char* args[] = {arg0, nullptr};
  char** argv = args;
  mpi_start(&argc, &argv);
  CHECK_FALSE(mpi_world().active);
  CHECK(mpi_world().rank == 0);
  CHECK(mpi_world().size == 1);
  const std::vector<uint8_t> mine = {1, 2, 3};
  CHECK(mpi_all_gather(mine) == std::vector<std::vector<uint8_t>>{mine});
  mpi_barrier();
  ModelResult r;
  r.index = 4;
  r.status = "done";
  const std::vector<ModelResult> all = meshsal::cli::gather_results({r});
  REQUIRE(all.size() == 1);
  CHECK(all[0].index == 4);
  mpi_stop();
  CHECK_FALSE(mpi_world().active);
}
