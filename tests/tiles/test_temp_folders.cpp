// Issue 36 (7): the out-of-core temporary folders meshsal-tiles-XXXXXX. Every signal that
// ends a process and can be caught stops a run as Ctrl-C does, its folder removed; a folder
// is locked for its life, so that one a crash or SIGKILL left (its lock free) is removed by
// the next run in the same parent, while one in use, one without a lock file, a link and
// other people's names are left; where locks cannot be trusted nothing is removed.
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "tiles/scratch_files.h"
#include "tiles/scratch_lock.h"
#include "cli/synthetic.h"
#include "cli_run.h"
#include "meshsal/meshsal.h"

using namespace meshsal;
namespace fs = std::filesystem;

namespace {

// The folders meshsal-tiles-* (not links) in `parent`.
size_t scratch_folders(const fs::path& parent) {
  size_t n = 0;
  for (const auto& e : fs::directory_iterator(parent))
    n += e.is_directory() && !e.is_symlink() && e.path().filename().string().rfind(kScratchPrefix, 0) == 0;
  return n;
}

// `meshsal ARGS...` in a child process, stdout to /dev/null, stderr to `err`; no core file
// (the crash signals below).
pid_t start_cli(const std::vector<std::string>& args, const fs::path& err) {
  const pid_t pid = ::fork();
  if (pid != 0) return pid;
  // A CLI started as a shell starts it: every signal the tests send at its default (one the
  // test process ignores would stay ignored in the CLI, as nohup's SIGHUP does), none blocked.
  for (int sig = 1; sig < NSIG; ++sig)
    if (sig != SIGKILL && sig != SIGSTOP) ::signal(sig, SIG_DFL);
  sigset_t none;
  sigemptyset(&none);
  ::sigprocmask(SIG_SETMASK, &none, nullptr);
  const int null = ::open("/dev/null", O_WRONLY);
  ::dup2(null, 1);
  const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ::dup2(e, 2);
  const struct rlimit no_core {0, 0};
  ::setrlimit(RLIMIT_CORE, &no_core);
  const std::string cli = meshsal_test::cli_path();
  std::vector<char*> argv{const_cast<char*>(cli.c_str())};
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  ::execv(cli.c_str(), argv.data());
  ::_exit(127);
}

// A simplification out of core that runs for well over 10 s (test_cancel.cpp's mesh and
// eps), its tiles in `temp`.
std::vector<std::string> slow_run(const fs::path& dir, const fs::path& temp) {
  const fs::path in = dir / "sphere.ply";
  if (!fs::exists(in)) write_ply(in.string(), make_sphere(1.0, 7), {});
  return {"simplify", in.string(), "-o", (dir / "out.ply").string(), "--ratio", "0.1", "--eps-frac", "0.01",
          "--backend", "cpu", "--memory-limit", "1G", "--temp-dir", temp.string()};
}

// Waits until `temp` holds a folder meshsal-tiles-*, then a moment more (the run is in
// its work); false after 12 s.
bool wait_for_folder(const fs::path& temp) {
  for (int i = 0; i < 600 && scratch_folders(temp) == 0; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  return scratch_folders(temp) == 1;
}

// A quick out-of-core run with its tiles in `temp`: its stderr.
meshsal_test::CliRun quick_run(const fs::path& dir, const fs::path& temp) {
  const fs::path in = dir / "small.ply";
  if (!fs::exists(in)) write_ply(in.string(), make_bumpy_sphere(3), {});
  return meshsal_test::run_cli("saliency " + meshsal_test::quoted(in.string()) + " -o " +
                                   meshsal_test::quoted((dir / "small_s.ply").string()) +
                                   " --backend cpu --memory-limit 100M --temp-dir " + meshsal_test::quoted(temp.string()),
                               dir);
}

}  // namespace

TEST_CASE("cli: every signal that ends a process stops an out-of-core run as Ctrl-C does, its temporary folder removed",
          "[cli][cancel][outofcore]") {
  const fs::path dir = meshsal_test::scratch_dir("signals_tmp");
  std::vector<int> signals{SIGHUP, SIGINT, SIGQUIT, SIGTERM, SIGPIPE, SIGUSR1, SIGUSR2, SIGALRM, SIGXCPU, SIGXFSZ};
#ifdef SIGPWR
  signals.push_back(SIGPWR);
#endif
  for (int sig : signals) {
    INFO("signal " << sig << " (" << strsignal(sig) << ")");
    const fs::path temp = dir / ("tmp" + std::to_string(sig));
    fs::create_directories(temp);
    const pid_t pid = start_cli(slow_run(dir, temp), dir / "err.txt");
    REQUIRE(pid > 0);
    CHECK(wait_for_folder(temp));
    ::kill(pid, sig);
    int status = 0;
    ::waitpid(pid, &status, 0);
    REQUIRE(WIFEXITED(status));  // not ended by the signal: stopped, then exited
    CHECK(WEXITSTATUS(status) == 128 + sig);
    CHECK(meshsal_test::read_file((dir / "err.txt").string()) == "interrupted\n");
    CHECK(scratch_folders(temp) == 0);
    CHECK_FALSE(fs::exists(dir / "out.ply"));
  }
}

TEST_CASE("cli: a run that crashed or was killed leaves its folder, which the next run removes, not one in use",
          "[cli][cancel][outofcore]") {
  const fs::path dir = meshsal_test::scratch_dir("stale_tmp");
  const fs::path temp = dir / "tmp";
  fs::create_directories(temp);
  // A crash (SIGSEGV, abort) and SIGKILL cannot clean up: the folder stays.
  for (int sig : {SIGKILL, SIGSEGV, SIGABRT}) {
    INFO("signal " << sig);
    const pid_t pid = start_cli(slow_run(dir, temp), dir / "err.txt");
    REQUIRE(pid > 0);
    CHECK(wait_for_folder(temp));
    ::kill(pid, sig);
    int status = 0;
    ::waitpid(pid, &status, 0);
    CHECK(WIFSIGNALED(status));
    CHECK(scratch_folders(temp) == 1);
    // The next run in that parent removes it (its lock is free) and says so.
    const meshsal_test::CliRun next = quick_run(dir, temp);
    INFO(next.err);
    CHECK(next.rc == 0);
    CHECK(scratch_folders(temp) == 0);
    CHECK(next.err.find("note: removed 1 temporary folder meshsal-tiles-* in " + temp.string() +
                        " that runs which crashed or were killed left (stale: no run held their lock)\n") == 0);
  }
  // A run in progress holds its lock: a run beside it leaves its folder alone.
  const pid_t pid = start_cli(slow_run(dir, temp), dir / "err.txt");
  REQUIRE(pid > 0);
  CHECK(wait_for_folder(temp));
  const meshsal_test::CliRun beside = quick_run(dir, temp);
  CHECK(beside.rc == 0);
  CHECK(beside.err.empty());
  CHECK(scratch_folders(temp) == 1);
  ::kill(pid, SIGINT);
  int status = 0;
  ::waitpid(pid, &status, 0);
  CHECK(WIFEXITED(status));
  CHECK(scratch_folders(temp) == 0);
}

TEST_CASE("temporary folders: only a folder whose lock is verifiably free is stale", "[outofcore]") {
  const fs::path parent = meshsal_test::scratch_dir("stale_rules");
  const auto make = [&](const std::string& name) {
    fs::create_directories(parent / name);
    std::ofstream(parent / name / "pos.f32") << "tiles";
    return (parent / name).string();
  };
  // Stale: locked by a run that is gone (its descriptor closed).
  const std::string stale = make(std::string(kScratchPrefix) + "stale1");
  const int gone = lock_scratch_dir(stale);
  REQUIRE(gone >= 0);
  CHECK(fs::exists(stale + "/lock"));
  CHECK_FALSE(fs::exists(stale + "/lock.new"));
  ::close(gone);
  // In use: its lock held (by this process, through another open file: flock tells them apart).
  const std::string live = make(std::string(kScratchPrefix) + "live01");
  const int held = lock_scratch_dir(live);
  REQUIRE(held >= 0);
  // No lock file: a run between making its folder and locking it, or one from before locks.
  const std::string lockless = make(std::string(kScratchPrefix) + "nolock");
  // A link named like a folder, to a folder with a free lock file: never followed.
  const std::string elsewhere = make("elsewhere");
  ::close(lock_scratch_dir(elsewhere));
  fs::create_directory_symlink(elsewhere, parent / (std::string(kScratchPrefix) + "link01"));
  // Another name, a free lock: not ours.
  const std::string other = make("other-tiles-stale1");
  ::close(lock_scratch_dir(other));
  // A lock file that is a link: not taken.
  const std::string linked = make(std::string(kScratchPrefix) + "lnlock");
  fs::create_symlink(elsewhere + "/lock", linked + "/lock");

  // Where locks are not trusted (NFS, FUSE...): nothing removed, the others' folders counted.
  const StaleScratch untrusted = remove_stale_scratch_dirs(parent.string(), false);
  CHECK(untrusted.removed == 0);
  CHECK(untrusted.left == 4);  // stale, live, lockless and lnlock; not the link
  CHECK(fs::exists(stale));
  CHECK(stale_scratch_note(parent.string(), untrusted, "nfs") ==
        "note: " + parent.string() + " holds 4 temporary folders meshsal-tiles-* of other runs, left as they are: on "
        "nfs a lock cannot be trusted, so a stale one cannot be told from one in use (remove them by hand when no "
        "meshsal run uses this folder)");

  {
    // A new folder removes the stale one first, then holds its own lock.
    ScratchDir mine(parent.string());
    CHECK(mine.note() == "note: removed 1 temporary folder meshsal-tiles-* in " + parent.string() +
                             " that runs which crashed or were killed left (stale: no run held their lock)");
    CHECK_FALSE(fs::exists(stale));
    for (const std::string& kept : {live, lockless, elsewhere, other, linked}) {
      INFO(kept);
      CHECK(fs::exists(kept + "/pos.f32"));
    }
    CHECK(fs::exists(elsewhere + "/lock"));
    CHECK(fs::is_symlink(parent / (std::string(kScratchPrefix) + "link01")));
    CHECK(fs::path(mine.path()).filename().string().rfind(kScratchPrefix, 0) == 0);
    CHECK(fs::exists(mine.file("lock")));
    std::ofstream(mine.file("tri.u32")) << "x";
    // While it lives, another run's scan leaves it.
    CHECK(remove_stale_scratch_dirs(parent.string(), true).removed == 0);
    CHECK(fs::exists(mine.file("tri.u32")));
    // Its lock is taken: flock through another open file fails.
    const int probe = ::open(mine.file("lock").c_str(), O_RDONLY);
    REQUIRE(probe >= 0);
    CHECK(::flock(probe, LOCK_EX | LOCK_NB) != 0);
    ::close(probe);
    const std::string path = mine.path();
    // Borrowing another folder (MPI ranks) removes its own at once.
    ScratchDir borrower(parent.string());
    const std::string own = borrower.path();
    borrower.borrow(path);
    CHECK_FALSE(fs::exists(own));
    CHECK(fs::exists(path));
  }
  CHECK(scratch_folders(parent) == 3);  // live, lockless, lnlock: this run's own is gone
  // Once the live run ends without cleaning up, it is stale too.
  ::close(held);
  CHECK(remove_stale_scratch_dirs(parent.string(), true).removed == 1);
  CHECK_FALSE(fs::exists(live));
}

TEST_CASE("temporary folders: the file systems whose locks are trusted", "[outofcore]") {
  std::string name;
  // The tests' temporary folder is on a local file system here (ext4, tmpfs, overlay...).
  CHECK(scratch_locks_trusted(fs::temp_directory_path().string(), &name));
  CHECK(name.empty());
  // procfs is no file system a run keeps tiles on, nor in the list: not trusted, named.
  CHECK_FALSE(scratch_locks_trusted("/proc", &name));
  CHECK(name == "type 0x9fa0");
}
