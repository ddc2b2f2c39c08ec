// Issue 21 (3, 4, 6, 7, 9): meshsal batch with hostile inputs. A FIFO among the inputs hung
// the loader; "up to date" compared only times; list files were read without bounds; file
// names went raw into the JSON log and the terminal; a failed log write stopped the run.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_run.h"
#include "cli/synthetic.h"
#include "meshsal/meshsal.h"
#include "test_batch_util.h"

using namespace meshsal_test;
namespace fs = std::filesystem;

namespace {

// Every line of the log (JSON Lines).
std::vector<std::string> lines_of(const fs::path& log) { return log_lines(log); }

const std::string* line_for(const std::vector<std::string>& lines, const std::string& mesh_name) {
  for (auto it = lines.rbegin(); it != lines.rend(); ++it)
    if (it->find(mesh_name) != std::string::npos) return &*it;
  return nullptr;
}

// The file's modification time set back to 2001 (older than any output).
void make_old(const fs::path& p) {
  const timespec times[2] = {{1000000000, 0}, {1000000000, 0}};
  REQUIRE(::utimensat(AT_FDCWD, p.c_str(), times, 0) == 0);
}

// True when `s` is valid UTF-8 (shortest forms, no surrogates).
bool valid_utf8(const std::string& s) {
  for (size_t i = 0; i < s.size();) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    size_t n = c < 0x80 ? 1 : (c >= 0xc2 && c <= 0xdf) ? 2 : (c >= 0xe0 && c <= 0xef) ? 3 : (c >= 0xf0 && c <= 0xf4) ? 4 : 0;
    if (n == 0 || i + n > s.size()) return false;
    for (size_t k = 1; k < n; ++k)
      if ((static_cast<unsigned char>(s[i + k]) & 0xc0) != 0x80) return false;
    if (n == 3 && c == 0xed && static_cast<unsigned char>(s[i + 1]) >= 0xa0) return false;  // surrogate
    i += n;
  }
  return true;
}

}  // namespace

TEST_CASE("batch: a FIFO among the inputs is skipped with its reason, the others run", "[cli][batch]") {
  const fs::path dir = scratch_dir("batch_fifo");
  fs::create_directories(dir / "in");
  meshsal::write_obj((dir / "in" / "a.obj").string(), meshsal::make_sphere(1.0, 1));
  REQUIRE(::mkfifo((dir / "in" / "b.obj").c_str(), 0600) == 0);
  meshsal::write_obj((dir / "in" / "c.obj").string(), meshsal::make_sphere(1.0, 2));
  const CliRun r = run_cli("batch " + quoted((dir / "in").string()) + " -o " + quoted((dir / "out").string()), dir, 120);
  REQUIRE(r.rc == 0);  // it used to block on b.obj forever
  CHECK(r.out.find("3 models: 2 computed, 1 skipped, 0 failed") != std::string::npos);
  CHECK(r.err.find("note: skipped " + (dir / "in" / "b.obj").string() +
                   ": it is a named pipe (FIFO): batch reads regular files only") != std::string::npos);
  const auto lines = lines_of(dir / "out" / "batch.jsonl");
  REQUIRE(lines.size() == 3);
  CHECK(json_text(lines[1], "status") == "skipped");
  CHECK(json_text(lines[1], "reason") == "it is a named pipe (FIFO): batch reads regular files only");
  CHECK(json_text(lines[2], "status") == "done");
  CHECK(fs::exists(dir / "out" / "c_saliency.ply"));
}

TEST_CASE("batch: up to date means the same input and options, not newer times", "[cli][batch]") {
  const fs::path dir = scratch_dir("batch_resume");
  fs::create_directories(dir / "in");
  const fs::path in = dir / "in" / "m.obj", out = dir / "out";
  meshsal::write_obj(in.string(), meshsal::make_sphere(1.0, 2));  // 162 vertices
  const std::string args = "batch " + quoted(in.string()) + " -o " + quoted(out.string());
  CliRun r = run_cli(args + " --simplify 0.5", dir);
  REQUIRE(r.rc == 0);
  // The same input and options: skipped, and its line keeps the numbers.
  r = run_cli(args + " --simplify 0.5", dir);
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("0 computed, 1 skipped") != std::string::npos);
  auto lines = lines_of(out / "batch.jsonl");
  REQUIRE(lines.size() == 2);  // appended: the first run's line stays
  CHECK(json_text(lines[0], "status") == "done");
  CHECK(json_text(lines[1], "status") == "skipped");
  CHECK(lines[1].find("\"vertices\": 162") != std::string::npos);
  CHECK(lines[1].find("\"simplify\": {") != std::string::npos);
  // Other options: computed again (it kept the old 0.5 outputs before).
  r = run_cli(args + " --simplify 0.1", dir);
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("1 computed, 0 skipped") != std::string::npos);
  CHECK(meshsal::load_mesh((out / "m_simplified.obj").string()).triangle_count() == 32);
  // A different mesh under the same name with an older time: computed again.
  meshsal::write_obj(in.string(), meshsal::make_sphere(1.0, 1));  // 42 vertices
  make_old(in);
  r = run_cli(args + " --simplify 0.1", dir);
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("1 computed, 0 skipped") != std::string::npos);
  CHECK(meshsal::load_mesh((out / "m_saliency.ply").string()).vertex_count() == 42);
  // The same size and time but other bytes (a touched-back copy): the content hash tells.
  std::string text = read_text(in);
  const size_t at = text.find("v 0");
  REQUIRE(at != std::string::npos);
  text[at + 2] = '1';  // one coordinate's digit
  std::ofstream(in, std::ios::binary) << text;
  make_old(in);
  r = run_cli(args + " --simplify 0.1", dir);
  CHECK(r.out.find("1 computed, 0 skipped") != std::string::npos);
  // An output removed: computed again.
  r = run_cli(args + " --simplify 0.1", dir);
  CHECK(r.out.find("0 computed, 1 skipped") != std::string::npos);
  fs::remove(out / "m_simplified.obj");
  r = run_cli(args + " --simplify 0.1", dir);
  CHECK(r.out.find("1 computed, 0 skipped") != std::string::npos);
}

TEST_CASE("batch: list files are bounded: regular files or -, no endless or binary lists", "[cli][batch]") {
  const fs::path dir = scratch_dir("batch_lists");
  const fs::path out = dir / "out";
  meshsal::write_obj((dir / "a.obj").string(), meshsal::make_sphere(1.0, 1));
  // /dev/zero used to be read until memory ran out.
  CliRun r = run_cli("batch --list /dev/zero -o " + quoted(out.string()), dir, 60);
  CHECK(r.rc == 1);
  CHECK(r.err == "error: /dev/zero: a list file must be a regular file, or - for standard input\n");
  // @/dev/urandom printed raw bytes as the message.
  r = run_cli("batch @/dev/urandom -o " + quoted(out.string()), dir, 60);
  CHECK(r.rc == 1);
  CHECK(r.err == "error: /dev/urandom: a list file must be a regular file, or - for standard input\n");
  // Binary data in a regular file.
  {
    std::ofstream f(dir / "nul.txt", std::ios::binary);
    f.write("a.obj\nx\0y\n", 10);
  }
  r = run_cli("batch --list " + quoted((dir / "nul.txt").string()) + " -o " + quoted(out.string()), dir, 60);
  CHECK(r.rc == 1);
  CHECK(r.err == "error: " + (dir / "nul.txt").string() +
                     ":2: not a line of text (a NUL byte): a list file holds one path per line\n");
  // A line longer than a path can be.
  std::ofstream(dir / "long.txt") << "a.obj\n" << std::string(5000, 'x') << "\n";
  r = run_cli("batch --list " + quoted((dir / "long.txt").string()) + " -o " + quoted(out.string()), dir, 60);
  CHECK(r.rc == 1);
  CHECK(r.err.find(":2: a line longer than 4096 bytes") != std::string::npos);
  // A huge file (sparse: costs no disk).
  {
    std::ofstream f(dir / "huge.txt");
    f << "a.obj\n";
  }
  fs::resize_file(dir / "huge.txt", (uint64_t(65) << 20));
  r = run_cli("batch --list " + quoted((dir / "huge.txt").string()) + " -o " + quoted(out.string()), dir, 60);
  CHECK(r.rc == 1);
  CHECK(r.err.find("a list file larger than 64 MiB") != std::string::npos);
  CHECK_FALSE(fs::exists(out / "a_saliency.ply"));
  // Standard input with -, relative items taken from the working folder.
  std::ofstream(dir / "list.txt") << "# one model\n" << (dir / "a.obj").string() << "\n";
  r = run_cli("batch --list - -o " + quoted(out.string()) + " -q", dir, 60, (dir / "list.txt").string());
  CHECK(r.rc == 0);
  CHECK(fs::exists(out / "a_saliency.ply"));
}

TEST_CASE("batch: names that are not UTF-8 or hold control characters stay valid JSON and one line", "[cli][batch]") {
  const fs::path dir = scratch_dir("batch_names");
  fs::create_directories(dir / "in");
  const std::string latin1 = "caf\xe9.obj";                  // ISO 8859-1, not UTF-8
  const std::string esc = "evil\x1b]0;title\x07\x1b[2J.obj";  // OSC title, clear screen
  const std::string nl = "two\nlines.obj";
  meshsal::write_obj((dir / "in" / latin1).string(), meshsal::make_sphere(1.0, 1));
  std::ofstream(dir / "in" / esc) << "v 0 0 0\nf 1 2 3\n";  // broken: fails with its name
  std::ofstream(dir / "in" / nl) << "junk\n";
  const CliRun r = run_cli("batch " + quoted((dir / "in").string()) + " -o " + quoted((dir / "out").string()), dir, 120);
  CHECK(r.rc == 1);
  const std::string log = read_text(dir / "out" / "batch.jsonl");
  CHECK(valid_utf8(log));
  CHECK(log.find("caf\\udce9.obj") != std::string::npos);
  CHECK(log.find('\x1b') == std::string::npos);
  CHECK(log.find("evil\\u001b]0;title\\u0007\\u001b[2J.obj") != std::string::npos);
  CHECK(log.find("two\\nlines.obj") == std::string::npos);  // \n escaped as \u000a
  CHECK(log.find("two\\u000alines.obj") != std::string::npos);
  CHECK(std::count(log.begin(), log.end(), '\n') == 3);
  // The terminal gets no escape sequences, and each error stays on one line.
  CHECK(r.err.find('\x1b') == std::string::npos);
  CHECK(r.err.find('\x07') == std::string::npos);
  CHECK(r.err.find("evil\\x1b]0;title\\x07\\x1b[2J.obj") != std::string::npos);
  CHECK(r.err.find("two\\x0alines.obj") != std::string::npos);
  size_t error_lines = 0;
  std::istringstream ss(r.err);
  for (std::string line; std::getline(ss, line);) error_lines += line.rfind("error: ", 0) == 0;
  CHECK(error_lines == 2);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 2);
}

TEST_CASE("batch: a log that cannot be written is reported, the models still run, the end says so", "[cli][batch]") {
  const fs::path dir = scratch_dir("batch_log_full");
  const fs::path in = make_batch_inputs(dir);
  fs::remove(in / "broken.obj");
  // /dev/full: every write fails with ENOSPC, as on a full disk. Through a link of our own:
  // a batch that regressed to replacing its log would replace the link, not the device.
  const fs::path full = dir / "full.jsonl";
  fs::create_symlink("/dev/full", full);
  const CliRun r = run_cli("batch " + quoted(in.string()) + " -o " + quoted((dir / "out").string()) + " --log " +
                               quoted(full.string()), dir, 120);
  CHECK(r.rc == 1);
  CHECK(fs::exists(dir / "out" / "ball_saliency.ply"));
  CHECK(fs::exists(dir / "out" / "bumpy_saliency.ply"));
  CHECK(fs::exists(dir / "out" / "cube_saliency.ply"));
  CHECK(r.out.find("batch: 3 models: 3 computed, 0 skipped, 0 failed") != std::string::npos);
  CHECK(r.err.find("error: " + full.string() + ": write failed: No space left on device: the log misses this "
                   "model's line; the run goes on\n") != std::string::npos);
  CHECK(r.err.find("error: the log " + full.string() + " misses 3 lines (the write error is above)\n") !=
        std::string::npos);
  struct stat st;
  CHECK((::stat("/dev/full", &st) == 0 && S_ISCHR(st.st_mode)));
}
