// Issue 36 (6): batch reads its resume records (DIR/.meshsal-batch/NAME.state) back, and
// used to copy a record's last line into the log as it found it: a torn or edited state
// file put a line that is not JSON (or not UTF-8) into the log, a FIFO in its place hung the
// run, a huge one was read whole. A state file is now read within bounds and validated in
// full; anything else than what batch writes means the model is computed again.
#include <sys/stat.h>

#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "cli_run.h"
#include "core/utf8.h"
#include "json_check.h"
#include "meshsal/meshsal.h"
#include "test_batch_util.h"

using namespace meshsal_test;
namespace fs = std::filesystem;

namespace {

// Every line of the log is one JSON value on one line of valid UTF-8 (JSON Lines).
void check_json_lines(const fs::path& log) {
  const std::string text = read_text(log);
  REQUIRE(!text.empty());
  CHECK(text.back() == '\n');
  CHECK(meshsal::valid_utf8(text));
  for (const std::string& line : log_lines(log)) {
    INFO(line.substr(0, 300));
    CHECK(json_valid(line));
    CHECK(line.find('\r') == std::string::npos);
    CHECK(line.size() < 64 * 1024);
  }
}

struct Rig {
  fs::path dir, state, log;
  std::string args;
};

Rig make_rig(const std::string& name) {
  Rig g;
  g.dir = scratch_dir(name);
  fs::create_directories(g.dir / "in");
  meshsal::write_obj((g.dir / "in" / "m.obj").string(), meshsal::make_sphere(1.0, 1));
  g.args = "batch " + quoted((g.dir / "in" / "m.obj").string()) + " -o " + quoted((g.dir / "out").string()) +
           " --backend cpu";
  g.state = g.dir / "out" / ".meshsal-batch" / "m.state";
  g.log = g.dir / "out" / "batch.jsonl";
  const CliRun r = run_cli(g.args, g.dir, 300);
  REQUIRE(r.rc == 0);
  return g;
}

// The state's lines (without their newlines).
std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  for (size_t at = 0; at < text.size();) {
    size_t nl = text.find('\n', at);
    if (nl == std::string::npos) nl = text.size();
    lines.push_back(text.substr(at, nl - at));
    at = nl + 1;
  }
  return lines;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const std::string& l : lines) s += l + "\n";
  return s;
}

}  // namespace

TEST_CASE("batch: a state file not as batch writes it means recompute, and none of it reaches the log",
          "[cli][batch]") {
  Rig g = make_rig("batch_state_bad");
  const std::string good = read_text(g.state);
  const std::vector<std::string> lines = lines_of(good);
  REQUIRE(lines.size() >= 4);
  REQUIRE(lines.back().rfind("record {", 0) == 0);
  // The good state is read back: skipped, its record in the log.
  CliRun r = run_cli(g.args, g.dir, 300);
  REQUIRE(r.out.find("0 computed, 1 skipped") != std::string::npos);

  const auto with_record = [&](const std::string& record) {
    std::vector<std::string> l = lines;
    l.back() = "record " + record;
    return joined(l);
  };
  const auto with_line = [&](size_t i, const std::string& suffix) {
    std::vector<std::string> l = lines;
    l[i] += suffix;
    return joined(l);
  };
  const std::string record = lines.back().substr(7);
  std::string nested = "{\"status\": \"done\", \"a\": ";
  for (int k = 0; k < 70; ++k) nested += "[";
  for (int k = 0; k < 70; ++k) nested += "]";
  nested += "}";
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"a torn record", with_record(record.substr(0, record.size() / 2))},
      {"an empty object", with_record("{}")},
      {"two values", with_record("{\"status\": \"done\"} {\"status\": \"done\"}")},
      {"not UTF-8", with_record("{\"status\": \"done\", \"name\": \"caf\xe9\"}")},
      {"an escape character", with_record("{\"status\": \"done\",\x1b[2J \"a\": 1}")},
      {"a carriage return", with_record("{\"status\": \"done\",\r\"a\": 1}")},
      {"nesting deeper than 64", with_record(nested)},
      {"a record without status done", with_record("{\"mesh\": \"m.obj\", \"status\": \"failed\"}")},
      {"a huge record (2 MiB)", with_record("{\"status\": \"done\", \"pad\": \"" + std::string(2 << 20, 'a') + "\"}")},
      {"no last newline", good.substr(0, good.size() - 1)},
      {"junk after the input numbers", with_line(1, " junk")},
      {"junk after an output size", with_line(3, "x")},
      {"a line after the record", good + "extra\n"},
      {"the record twice", good + lines.back() + "\n"},
  };
  for (const auto& [what, text] : bad) {
    INFO(what);
    {
      std::ofstream f(g.state, std::ios::binary | std::ios::trunc);
      f << text;
    }
    r = run_cli(g.args, g.dir, 300);
    CHECK(r.rc == 0);
    CHECK(r.out.find("1 computed, 0 skipped") != std::string::npos);
    check_json_lines(g.log);
    CHECK(json_text(log_lines(g.log).back(), "status") == "done");
    // The model's new state is one batch wrote: the next run skips it.
    CHECK(read_text(g.state).size() < 64 * 1024);
    r = run_cli(g.args, g.dir, 300);
    CHECK(r.out.find("0 computed, 1 skipped") != std::string::npos);
  }
  check_json_lines(g.log);
}

TEST_CASE("batch: a FIFO or a link in place of a state file is not read: the model is recomputed", "[cli][batch]") {
  Rig g = make_rig("batch_state_fifo");
  // A FIFO: opening it to read used to wait for a writer forever.
  fs::remove(g.state);
  REQUIRE(::mkfifo(g.state.c_str(), 0600) == 0);
  CliRun r = run_cli(g.args, g.dir, 120);
  INFO(r.err);
  CHECK(r.rc == 0);
  CHECK(r.out.find("1 computed, 0 skipped") != std::string::npos);
  check_json_lines(g.log);
  struct stat st;
  REQUIRE(::lstat(g.state.c_str(), &st) == 0);
  REQUIRE(S_ISREG(st.st_mode));  // replaced by a state file, not written through (and not read here if not)
  // A link to a state file elsewhere is none of batch's: recomputed, replaced by a file.
  std::ofstream(g.dir / "elsewhere.state", std::ios::binary) << read_text(g.state);
  fs::remove(g.state);
  fs::create_symlink(g.dir / "elsewhere.state", g.state);
  r = run_cli(g.args, g.dir, 120);
  CHECK(r.out.find("1 computed, 0 skipped") != std::string::npos);
  REQUIRE(::lstat(g.state.c_str(), &st) == 0);
  CHECK(S_ISREG(st.st_mode));
  r = run_cli(g.args, g.dir, 120);
  CHECK(r.out.find("0 computed, 1 skipped") != std::string::npos);
}
