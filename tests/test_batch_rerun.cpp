// Issue 22 (item 3): meshsal batch run again over its own results: a log a killed run left
// with a torn last line.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli_run.h"
#include "core/synthetic.h"
#include "json_check.h"
#include "meshsal/meshsal.h"
#include "test_batch_util.h"

using namespace meshsal_test;
namespace fs = std::filesystem;

TEST_CASE("batch: a torn last line in the log is noted, and the new lines start on a line of their own",
          "[cli][batch]") {
  const fs::path dir = scratch_dir("batch_torn");
  fs::create_directories(dir / "in");
  meshsal::write_obj((dir / "in" / "a.obj").string(), meshsal::make_sphere(1.0, 1));
  const fs::path out = dir / "out", log = out / "batch.jsonl";
  const std::string args = "batch " + quoted((dir / "in").string()) + " -o " + quoted(out.string()) + " --backend cpu";
  CliRun r = run_cli(args, dir, 120);
  REQUIRE(r.rc == 0);
  CHECK(r.err.find("torn") == std::string::npos);
  REQUIRE(log_lines(log).size() == 1);

  // A run killed part way through its line: no newline at the end.
  const std::string torn = "{\"mesh\": \"" + (dir / "in" / "a.obj").string() + "\", \"status\": \"do";
  std::ofstream(log, std::ios::app | std::ios::binary) << torn;
  r = run_cli(args + " --force", dir, 120);
  CHECK(r.rc == 0);
  CHECK(r.err == "note: " + log.string() + ": ignored a torn last line (" + std::to_string(torn.size()) +
                     " bytes) from an interrupted run\n");
  std::vector<std::string> lines = log_lines(log);
  REQUIRE(lines.size() == 3);
  CHECK(json_valid(lines[0]));
  CHECK(lines[1] == torn);  // left as it was: the log is only ever appended to
  CHECK(json_valid(lines[2]));
  CHECK(json_text(lines[2], "status") == "done");

  // A last line that is not JSON although it ends with a newline; blank lines after it.
  const std::string junk = "\"status\": \"done\", \"na";
  std::ofstream(log, std::ios::app | std::ios::binary) << junk << "\n\n";
  r = run_cli(args, dir, 120);
  CHECK(r.rc == 0);
  CHECK(r.err.find("ignored a torn last line (" + std::to_string(junk.size()) + " bytes)") != std::string::npos);
  lines = log_lines(log);
  REQUIRE(lines.size() == 6);
  CHECK(lines[3] == junk);
  CHECK(json_text(lines[5], "status") == "skipped");
  CHECK(json_valid(lines[5]));

  // A whole last line missing only its newline is a record, not torn: completed silently.
  std::string text = read_text(log);
  text.pop_back();
  std::ofstream(log, std::ios::trunc | std::ios::binary) << text;
  r = run_cli(args, dir, 120);
  CHECK(r.rc == 0);
  CHECK(r.err.find("torn") == std::string::npos);
  lines = log_lines(log);
  REQUIRE(lines.size() == 7);
  for (size_t i : {5, 6}) CHECK(json_valid(lines[i]));
}
