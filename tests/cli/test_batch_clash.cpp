// Issue 36 (6): a batch whose --log, --contact-sheet or gallery is one of its models' files
// (or another of them) replaced that file and ended with status 0; --html with
// --memory-limit linked pages it never wrote. Both are usage errors now, found before any
// work: exit status 2, and every file already there keeps its bytes.
#include <unistd.h>

#include <catch2/catch.hpp>

#include <filesystem>
#include <map>
#include <string>

#include "cli_run.h"
#include "meshsal/meshsal.h"
#include "test_batch_util.h"

using namespace meshsal_test;
namespace fs = std::filesystem;

namespace {

// Every regular file under `dir` (recursively) with its bytes.
std::map<std::string, std::string> files_under(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = read_text(e.path());
  return files;
}

}  // namespace

TEST_CASE("batch: --log, --contact-sheet or the gallery on a model's file, or on each other, is a usage error",
          "[cli][batch]") {
  const fs::path dir = scratch_dir("batch_clash");
  fs::create_directories(dir / "in");
  const std::string in = (dir / "in" / "ball.obj").string(), out = (dir / "out").string();
  meshsal::write_obj(in, meshsal::make_sphere(1.0, 1));
  const std::string args = "batch " + quoted(in) + " -o " + quoted(out) + " --view --backend cpu";
  CliRun r = run_cli(args, dir, 300);
  REQUIRE(r.rc == 0);
  const auto before = files_under(out);
  REQUIRE(before.count("ball_saliency.ply"));
  REQUIRE(before.count("ball_view.png"));
  REQUIRE(before.count(".meshsal-batch/ball.state"));
  // Another name for a model's file: a link to it, and a hard link.
  fs::create_symlink(fs::path(out) / "ball_view.png", dir / "link.jsonl");
  fs::create_hard_link(fs::path(out) / "ball_saliency.ply", dir / "hard.jsonl");

  struct Case {
    std::string extra, message;
  };
  const std::string o = out + "/";
  const std::string of = " (every file a batch writes is a file of its own)";
  const Case cases[] = {
      {"--log " + quoted(o + "ball_saliency.ply"),
       o + "ball_saliency.ply: given for both --log and the saliency output of " + in + of},
      {"--log " + quoted(o + "ball_view.png"), o + "ball_view.png: given for both --log and the best-view picture of " + in},
      {"--contact-sheet " + quoted(o + "ball_view.png"),
       o + "ball_view.png: given for both --contact-sheet and the best-view picture of " + in},
      {"--log " + quoted(out + "/../out/ball_saliency.ply"), "given for both --log and the saliency output of " + in},
      {"--log " + quoted((dir / "link.jsonl").string()), "given for both --log and the best-view picture of " + in},
      {"--log " + quoted((dir / "hard.jsonl").string()), "given for both --log and the saliency output of " + in},
      {"--log " + quoted(o + ".meshsal-batch/ball.state"), "given for both --log and the resume record of " + in},
      {"--log " + quoted(o + ".meshsal-batch"), "given for both --log and the folder of the resume records"},
      {"--simplify 0.5 --log " + quoted(o + "ball_simplified.obj"),
       "given for both --log and the simplified mesh of " + in},
      {"--html --log " + quoted(o + "ball_view.html"), "given for both --log and the page of " + in},
      {"--html --log " + quoted(o + "index.html"), "index.html: given for both --log and --html's gallery"},
      {"--lod 0.5 --contact-sheet " + quoted(o + "ball_lod.glb"),
       "given for both --contact-sheet and the levels of detail of " + in},
      {"--log " + quoted(o + "sheet.png") + " --contact-sheet " + quoted(o + "sheet.png"),
       "sheet.png: given for both --log and --contact-sheet"},
  };
  for (const Case& c : cases) {
    r = run_cli(args + " " + c.extra, dir, 300);
    INFO(c.extra << "\nstderr: " << r.err);
    CHECK(r.rc == 2);
    CHECK(r.err.find("error: ") == 0);
    CHECK(r.err.find(c.message) != std::string::npos);
    CHECK(r.out.empty());
    CHECK(files_under(out) == before);  // not one byte written, nothing added
  }
  // The same run with its own names still works (the files were left as they were).
  r = run_cli(args, dir, 300);
  CHECK(r.rc == 0);
  CHECK(r.out.find("0 computed, 1 skipped") != std::string::npos);
}

TEST_CASE("batch: --html with --memory-limit is refused instead of linking pages it never writes", "[cli][batch]") {
  const fs::path dir = scratch_dir("batch_html_ooc");
  fs::create_directories(dir / "in");
  const std::string in = (dir / "in" / "ball.ply").string(), out = (dir / "out").string();
  meshsal::write_ply(in, meshsal::make_sphere(1.0, 1), {});
  const CliRun r = run_cli("batch " + quoted(in) + " -o " + quoted(out) + " --html --memory-limit 200M", dir, 300);
  INFO(r.err);
  CHECK(r.rc == 2);
  CHECK(r.err == "error: --memory-limit computes each model out of core: it takes no --view, --html, "
                 "--contact-sheet (they need the mesh in memory) or --target-error (give --simplify RATIO|FACES) "
                 "(see --help)\n");
  CHECK_FALSE(fs::exists(out));  // refused before the output folder is made
}

TEST_CASE("batch: --log on the list file of the inputs is refused: the list is an input", "[cli][batch]") {
  const fs::path dir = scratch_dir("batch_log_list");
  meshsal::write_obj((dir / "a.obj").string(), meshsal::make_sphere(1.0, 1));
  const fs::path list = dir / "list.txt";
  std::ofstream(list) << "a.obj\n";
  const std::string text = read_text(list);
  for (const std::string& given : {"--list " + quoted(list.string()), "@" + quoted(list.string())}) {
    const CliRun r = run_cli("batch " + given + " -o " + quoted((dir / "out").string()) + " --log " + quoted(list.string()), dir, 300);
    INFO(given << "\nstderr: " << r.err);
    CHECK(r.rc == 1);
    CHECK(r.err.find(list.string() + ": --log is the input file") != std::string::npos);
    CHECK(read_text(list) == text);
    CHECK_FALSE(fs::exists(dir / "out" / "a_saliency.ply"));
  }
}
