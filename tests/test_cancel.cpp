// Issue 21 (5): long calls stop when their cancel flag is set (SaliencyOptions::cancel and
// its twins): meshsal::Cancelled, no result. The CLI's Ctrl-C and Python's KeyboardInterrupt
// go through it.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <thread>

#include "cli_run.h"
#include "core/cancel.h"
#include "core/parallel.h"
#include "cli/synthetic.h"
#include "meshsal/meshsal.h"
#include "test_batch_util.h"

using namespace meshsal;
namespace fs = std::filesystem;

namespace {

// A mesh and eps whose exact saliency takes ~15 s on 2 cores: 164k vertices, each with
// ~28k neighbours within the cutoff.
Mesh slow_mesh() { return make_sphere(1.0, 7); }
constexpr double kSlowEpsFrac = 0.01;
const char* const kSlowEpsText = "0.01";

SaliencyOptions slow_saliency_options() {
  SaliencyOptions so;
  so.backend = Backend::Cpu;
  so.eps_frac = kSlowEpsFrac;
  return so;
}

template <class F>
bool throws_cancelled(F&& f) {
  try {
    f();
  } catch (const Cancelled&) {
    return true;
  }
  return false;
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

TEST_CASE("cancel: a set flag stops every long call with Cancelled", "[cancel]") {
  const Mesh m = make_bumpy_sphere(3);
  std::atomic<bool> stop{true};
  SaliencyOptions so;
  so.backend = Backend::Cpu;
  so.cancel = &stop;
  CHECK(throws_cancelled([&] { compute_saliency(m, so); }));
  so.method = Method::Fast;
  CHECK(throws_cancelled([&] { compute_saliency(m, so); }));
  so.backend = Backend::Auto;  // a fallback to the CPU must not swallow it
  CHECK(throws_cancelled([&] { compute_saliency(m, so); }));
  CHECK(throws_cancelled([&] { simplification_weights(m, SaliencyWeightOptions{}, so); }));
  SimplifyOptions opt;
  opt.ratio = 0.1;
  opt.cancel = &stop;
  CHECK(throws_cancelled([&] { simplify_mesh(m, opt); }));
  OptimiserOptions oo;
  oo.cancel = &stop;
  const std::vector<double> score(m.vertex_count(), 1.0);
  CHECK(throws_cancelled([&] { best_viewpoint(m, score, oo); }));
  CompareOptions co;
  co.cancel = &stop;
  CHECK(throws_cancelled([&] { compare_surfaces(m, m, nullptr, co); }));
  // Cancelled is an Error (code that catches Error still stops) and names itself.
  try {
    compare_surfaces(m, m, nullptr, co);
  } catch (const Error& e) {
    CHECK(std::string(e.what()) == "cancelled");
  }
  // Not set: the same calls run.
  stop = false;
  so.backend = Backend::Cpu;
  CHECK(compute_saliency(m, so).saliency.size() == m.vertex_count());
}

TEST_CASE("cancel: a flag set from another thread stops saliency within a fraction of its time", "[cancel]") {
  const Mesh m = slow_mesh();
  std::atomic<bool> stop{false};
  SaliencyOptions so = slow_saliency_options();
  so.cancel = &stop;
  std::chrono::steady_clock::time_point set_at;
  std::thread setter([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    set_at = std::chrono::steady_clock::now();
    stop = true;
  });
  const auto t0 = std::chrono::steady_clock::now();
  const bool cancelled = throws_cancelled([&] { compute_saliency(m, so); });
  const double total = seconds_since(t0);
  setter.join();
  CHECK(cancelled);
  // Not a speed target: the whole call takes ~15 s on 2 cores; stopping 300 ms in, it
  // must end long before that (each thread polls before every chunk of 256 points).
  INFO("returned " << total << " s after the start");
  CHECK(total < 5.0);
}

TEST_CASE("cancel: parallel_for polls the flag of the call on every worker", "[cancel]") {
  std::atomic<bool> stop{false};
  std::atomic<size_t> chunks{0};
  const CancelScope scope(&stop);  // what a public call opens with its options' flag
  CHECK(throws_cancelled([&] {
    parallel_for(1000, 4, 10, [&](size_t, size_t) {
      if (++chunks == 5) stop = true;
    });
  }));
  CHECK(chunks < 100);  // stopped soon after, not after all 100 chunks
}

TEST_CASE("cli: Ctrl-C stops a command at once, exit 130, no output or temporary left", "[cli][cancel]") {
  using namespace meshsal_test;
  const fs::path dir = scratch_dir("cancel_cli");
  const std::string in = (dir / "sphere.obj").string(), out = (dir / "out.ply").string();
  write_obj(in, slow_mesh());
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    const int err = ::open((dir / "err.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(err, 2);
    const std::string cli = meshsal_test::cli_path();
    ::execl(cli.c_str(), cli.c_str(), "saliency", in.c_str(), "-o", out.c_str(), "--eps-frac", kSlowEpsText, "--backend",
            "cpu", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));
  const auto t0 = std::chrono::steady_clock::now();
  ::kill(pid, SIGINT);
  int status = 0;
  ::waitpid(pid, &status, 0);
  const double took = seconds_since(t0);
  INFO("ended " << took << " s after SIGINT");
  CHECK(took < 5.0);  // the whole run takes ~15 s
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  CHECK(read_text(dir / "err.txt") == "interrupted\n");
  CHECK_FALSE(fs::exists(out));
  for (const auto& e : fs::directory_iterator(dir)) CHECK(e.path().filename().string().find(".tmp.") == std::string::npos);
}

TEST_CASE("cli: Ctrl-C during batch logs the model it was on and prints the summary", "[cli][cancel][batch]") {
  using namespace meshsal_test;
  const fs::path dir = scratch_dir("cancel_batch");
  fs::create_directories(dir / "in");
  write_obj((dir / "in" / "a_small.obj").string(), make_sphere(1.0, 2));
  write_obj((dir / "in" / "b_slow.obj").string(), slow_mesh());
  const std::string out = (dir / "out").string();
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    const int o = ::open((dir / "out.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(o, 1);
    const int e = ::open((dir / "err.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(e, 2);
    const std::string cli = meshsal_test::cli_path();
    ::execl(cli.c_str(), cli.c_str(), "batch", (dir / "in").c_str(), "-o", out.c_str(), "--eps-frac", kSlowEpsText,
            "--backend", "cpu", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Wait until the small model is logged, then interrupt the slow one.
  for (int i = 0; i < 600 && !fs::exists(dir / "out" / ".meshsal-batch" / "a_small.state"); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  ::kill(pid, SIGINT);
  int status = 0;
  ::waitpid(pid, &status, 0);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  const auto lines = log_lines(dir / "out" / "batch.jsonl");
  REQUIRE(lines.size() == 2);
  CHECK(json_text(lines[0], "status") == "done");
  CHECK(json_text(lines[1], "status") == "interrupted");
  CHECK(read_text(dir / "out.txt").find("batch: 2 models: 1 computed, 0 skipped, 0 failed, then interrupted") == 0);
  CHECK(read_text(dir / "err.txt").find("interrupted (a new run resumes where this one stopped)") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "out" / "b_slow_saliency.ply"));
}
