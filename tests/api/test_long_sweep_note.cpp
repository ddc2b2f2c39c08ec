// The note an exact run on the CPU gives before a long sweep (api/saliency_backend.cpp,
// long_sweep_note): its cost in time and the way out (--method fast), only when the
// estimated pairs mean more than a minute; compute_saliency gives it to the notice once.
#include <atomic>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "api/resolve_method.h"
#include "cli/synthetic.h"
#include "meshsal/meshsal.h"

using namespace meshsal;

namespace {

// A scale whose neighbourhoods hold the whole sphere (within 4 x 5 x 0.1 = 2 diagonals; its
// widest surround, 2 x 5 x 0.1, the most the options allow): every point sees every point,
// so the exact sweep's pairs are about n^2 (163842 points: ~2.7e10).
SaliencyOptions whole_mesh_neighbourhoods() {
  SaliencyOptions o;
  o.backend = Backend::Cpu;
  o.method = Method::Exact;
  o.eps_frac = 0.1;
  o.scales = {5};
  o.threads = 1;
  return o;
}

}  // namespace

TEST_CASE("long sweep note: an exact sweep of minutes says its cost and names the fast method", "[api][saliency]") {
  const Mesh sphere = make_sphere(1.0, 7);
  REQUIRE(sphere.vertex_count() == 163842);
  SaliencyOptions o = whole_mesh_neighbourhoods();
  const std::string note = long_sweep_note(sphere, o);
  // ~2.7e10 pairs at 1.7e8 pairs/s on one thread: about 2.6 minutes, said as 3.
  CHECK_THAT(note, Catch::StartsWith("note: the exact method will visit ~2.") &&
                       Catch::Contains("e+10 neighbour pairs here: about 3 minutes on 1 CPU thread;") &&
                       Catch::Contains("--method fast (or auto)"));
  // Twice the threads, half the time: 1 minute still passes the line, which is 60 s.
  o.threads = 2;
  CHECK_THAT(long_sweep_note(sphere, o), Catch::Contains("about 1 minute on 2 CPU threads;"));
  // The fast method, and a sweep of seconds, say nothing.
  o.method = Method::Fast;
  CHECK(long_sweep_note(sphere, o).empty());
  o = whole_mesh_neighbourhoods();
  o.scales = {2, 3, 4, 5, 6};
  o.eps_frac = 0.003;
  CHECK(long_sweep_note(sphere, o).empty());
}

TEST_CASE("long sweep note: compute_saliency gives it to the notice before the sweep starts", "[api][saliency]") {
  const Mesh sphere = make_sphere(1.0, 7);
  SaliencyOptions o = whole_mesh_neighbourhoods();
  std::atomic<bool> stop{false};
  std::vector<std::string> notes;
  // Stop at the note: the test needs the order (said before the work), not the minutes.
  o.notice = [&](const std::string& line) {
    notes.push_back(line);
    stop = true;
  };
  o.cancel = &stop;
  CHECK_THROWS_AS(compute_saliency(sphere, o), Cancelled);
  REQUIRE(notes.size() == 1);
  CHECK_THAT(notes[0], Catch::StartsWith("note: the exact method will visit"));
}
