// Issue 21 (5): long calls stop when their cancel flag is set (SaliencyOptions::cancel and
// its twins): meshsal::Cancelled, no result. The CLI's Ctrl-C and Python's KeyboardInterrupt
// go through it.
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <fstream>
#include <filesystem>
#include <sstream>
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

// CPU seconds (user + system) a running process has used so far, from /proc/PID/stat.
double cpu_seconds_so_far(pid_t pid) {
  std::ifstream f("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  const size_t close = text.rfind(')');  // fields 14 and 15 (utime, stime) after "pid (comm)"
  if (close == std::string::npos) return -1;
  std::istringstream rest(text.substr(close + 2));
  std::string field;
  double ticks = 0;
  for (int i = 3; i <= 15 && rest >> field; ++i)
    if (i >= 14) ticks += std::stod(field);
  return ticks / double(::sysconf(_SC_CLK_TCK));
}

double cpu_seconds(const struct rusage& u) {
  return double(u.ru_utime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec) + double(u.ru_stime.tv_sec) +
         1e-6 * double(u.ru_stime.tv_usec);
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
  ViewpointOptions vo;
  vo.optimiser.cancel = &stop;
  const std::vector<double> score(m.vertex_count(), 1.0);
  CHECK(throws_cancelled([&] { best_viewpoint(m, score, vo); }));
  CompareOptions co;
  co.cancel = &stop;
  CHECK(throws_cancelled([&] { compare_surfaces(m, m, {}, co); }));
  // Cancelled is an Error (code that catches Error still stops) and names itself.
  try {
    compare_surfaces(m, m, {}, co);
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
  // The sweep's progress (the fraction of its points done, reported by the calling thread
  // after each of its chunks) measures the work: the flag is set once 2% is done, and the
  // sweep must stop within a few chunks of 256 points per thread, not run on to 100%.
  std::atomic<double> sweep_done{0};
  so.progress = [&](const char* stage, double f) {
    if (std::strcmp(stage, "gaussian sweep") == 0) sweep_done = f;
  };
  double set_at = -1;
  std::thread setter([&] {
    for (int i = 0; i < 120000 && sweep_done < 0.02; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    set_at = sweep_done;
    stop = true;
  });
  const bool cancelled = throws_cancelled([&] { compute_saliency(m, so); });
  setter.join();
  CHECK(cancelled);
  // After the flag, each of T threads ends the chunk it is in (T * 256 points), and the last
  // report before the flag lags the points done by at most one more round of chunks: at most
  // 2 T 256 points in all; twice that is the bound (5% of the sweep on 16 threads).
  const double points = double(m.vertex_count());
  const double threads = std::max(1u, std::thread::hardware_concurrency());
  const double bound = 4.0 * threads * 256.0 / points;
  INFO("flag set at " << set_at << " of the sweep; the last report " << sweep_done << "; bound +" << bound);
  CHECK(set_at >= 0.02);
  CHECK(sweep_done - set_at <= bound);
  CHECK(sweep_done < 1.0);
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
  // The work done after SIGINT, in CPU seconds (not wall time, which a loaded machine
  // stretches): each thread ends its chunk of 256 points (~30k neighbours each: well under
  // 0.1 CPU s), where the whole run takes ~30 CPU s (~15 s on 2 cores).
  const double cpu_before = cpu_seconds_so_far(pid);
  ::kill(pid, SIGINT);
  int status = 0;
  struct rusage usage {};
  ::wait4(pid, &status, 0, &usage);
  const double cpu_after = cpu_seconds(usage) - cpu_before;
  INFO("CPU seconds: " << cpu_before << " before SIGINT, " << cpu_after << " after");
  CHECK(cpu_before > 0);
  CHECK(cpu_after < 2.0);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  CHECK(read_text(dir / "err.txt") == "interrupted\n");
  CHECK_FALSE(fs::exists(out));
  for (const auto& e : fs::directory_iterator(dir)) CHECK(e.path().filename().string().find(".tmp.") == std::string::npos);
}

TEST_CASE("cli: SIGTERM stops an out-of-core run as Ctrl-C does, exit 143, its temporary folder removed",
          "[cli][cancel][outofcore]") {
  using namespace meshsal_test;
  const fs::path dir = scratch_dir("cancel_term");
  fs::create_directories(dir / "tmp");
  const std::string in = (dir / "sphere.ply").string(), out = (dir / "out.ply").string();
  write_ply(in, slow_mesh(), {});
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    const int err = ::open((dir / "err.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(err, 2);
    const std::string cli = meshsal_test::cli_path();
    ::execl(cli.c_str(), cli.c_str(), "simplify", in.c_str(), "-o", out.c_str(), "--ratio", "0.1", "--eps-frac",
            kSlowEpsText, "--backend", "cpu", "--memory-limit", "1G", "--temp-dir", (dir / "tmp").c_str(),
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Once the tiles are on disk (the folder exists), stop it.
  auto folders = [&] {
    size_t n = 0;
    for (const auto& e : fs::directory_iterator(dir / "tmp")) n += e.is_directory();
    return n;
  };
  for (int i = 0; i < 600 && folders() == 0; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  CHECK(folders() == 1);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  ::kill(pid, SIGTERM);
  int status = 0;
  ::waitpid(pid, &status, 0);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 143);
  CHECK(read_text(dir / "err.txt") == "interrupted\n");
  CHECK_FALSE(fs::exists(out));
  CHECK(folders() == 0);
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
