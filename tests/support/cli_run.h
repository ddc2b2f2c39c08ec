// Runs the meshsal executable as a user would (stdin closed) and keeps what it printed:
// the one way the CLI tests start the tool.
#pragma once
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "test_io_util.h"

namespace meshsal_test {

struct CliRun {
  int rc = -1;          // the exit status; -1 when a signal ended the tool
  std::string out, err;  // stdout and stderr (run_cli_merged: both in `out`, in order)
};

inline std::string quoted(const std::string& s) { return "'" + s + "'"; }

// The meshsal executable the tests run: this build's, or MESHSAL_TEST_CLI when set (to run
// the CLI tests against another build, e.g. to see which fail on an older one).
inline std::string cli_path() {
  const char* other = std::getenv("MESHSAL_TEST_CLI");
  return other && *other ? other : MESHSAL_CLI;
}

// An empty folder meshsal_NAME_PID under the temporary directory (emptied if it exists), for
// a test's inputs and outputs, removed when the test process exits.
inline std::filesystem::path scratch_dir(const std::string& name) {
  const std::filesystem::path d = std::filesystem::temp_directory_path() /
                                  ("meshsal_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  remove_at_exit(d);
  return d;
}

inline int exit_status(int system_status) {
  return WIFEXITED(system_status) ? WEXITSTATUS(system_status) : -1;
}

// `meshsal ARGS`, stdout and stderr apart, through stdout.txt and stderr.txt in `dir`.
// `timeout_s` > 0: a run that hangs is killed after that many seconds (rc 124 or -1), so a
// test of a hang fails instead of waiting forever. `stdin_path`: what it reads (default
// /dev/null).
inline CliRun run_cli(const std::string& args, const std::filesystem::path& dir, int timeout_s = 0,
                      const std::string& stdin_path = "/dev/null") {
  const std::string out = (dir / "stdout.txt").string(), err = (dir / "stderr.txt").string();
  const std::string cmd = (timeout_s > 0 ? "timeout -s KILL " + std::to_string(timeout_s) + " " : std::string()) +
                          quoted(cli_path()) + " " + args + " > " + quoted(out) + " 2> " + quoted(err) + " < " +
                          quoted(stdin_path);
  CliRun r;
  r.rc = exit_status(std::system(cmd.c_str()));
  r.out = read_file(out);
  r.err = read_file(err);
  return r;
}
inline CliRun run_cli(const std::string& args, const TempDir& dir) { return run_cli(args, dir.path); }
inline CliRun run_cli(const std::string& args) { return run_cli(args, TempDir()); }

// `meshsal ARGS` with stderr merged into stdout, as a terminal shows them.
inline CliRun run_cli_merged(const std::string& args) {
  const std::string cmd = quoted(cli_path()) + " " + args + " 2>&1 < /dev/null";
  CliRun r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  r.rc = exit_status(pclose(p));
  return r;
}

// `meshsal ARGS`, run in DIR, must be a usage error: exit status 2, stderr naming `option`,
// and nothing written into DIR (beside run_cli's stdout.txt and stderr.txt).
inline void check_usage_error(const std::string& args, const std::string& option, const std::filesystem::path& dir) {
  const CliRun r = run_cli(args, dir);
  INFO("meshsal " << args << "\nstderr: " << r.err);
  CHECK(r.rc == 2);
  CHECK(r.err.find("error: " + option) != std::string::npos);
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    INFO("written: " << name);
    CHECK((name == "stdout.txt" || name == "stderr.txt"));
  }
}

}  // namespace meshsal_test
