// Issue 36 (4): the check of output files is the library's (meshsal::check_outputs), so
// every front end that writes makes it, and the library's own file-to-file calls
// (saliency_file, simplify_file) check their output against their input themselves: never
// the input (through a symbolic or hard link, read-only or not), never PLY bytes under a
// .obj or .glb name.
#include <sys/stat.h>

#include <filesystem>
#include <string>

#include "cli/synthetic.h"
#include "out_of_core_util.h"
#include "test_io_util.h"

using meshsal_test::error_of;
using meshsal_test::file_bytes;
using meshsal_test::read_file;
using meshsal_test::TempDir;
namespace fs = std::filesystem;

namespace {

bool has(const std::string& message, const std::string& part) { return message.find(part) != std::string::npos; }

// A small mesh as a binary PLY in `dir`, read-only (its bytes must survive every call).
std::string read_only_input(const TempDir& dir) {
  const std::string in = dir.file("in.ply");
  meshsal::write_ply(in, meshsal::make_bumpy_sphere(2), {});
  REQUIRE(::chmod(in.c_str(), 0444) == 0);
  return in;
}

meshsal::SaliencyOptions cpu_options() {
  meshsal::SaliencyOptions o;
  o.backend = meshsal::Backend::Cpu;
  return o;
}

// The two out-of-core calls, each writing `output` from `input`.
void run_saliency_file(const std::string& input, const std::string& output) {
  meshsal::saliency_file(input, output, cpu_options(), {});
}
void run_simplify_file(const std::string& input, const std::string& output) {
  meshsal::SimplifyOptions o;
  o.ratio = 0.5;
  meshsal::simplify_file(input, output, o, std::nullopt, cpu_options(), {});
}

}  // namespace

TEST_CASE("check_outputs refuses an input reached through a symbolic or a hard link", "[io]") {
  TempDir dir;
  const std::string in = dir.write("in.ply", "ply\n");
  const std::string link = dir.file("link.ply"), hard = dir.file("hard.ply");
  fs::create_symlink(in, link);
  fs::create_hard_link(in, hard);
  for (const std::string& out : {in, link, hard}) {
    INFO(out);
    const std::string e = error_of([&] { meshsal::check_outputs({{out, "-o", {".ply"}}}, {in}); });
    CHECK(e == out + ": -o is the input file '" + in + "' (an output never replaces an input)");
  }
  // Another file, an input that does not exist (loading it says so later) and "" pass.
  CHECK(error_of([&] { meshsal::check_outputs({{dir.file("new.ply"), "-o", {".ply"}}}, {in, dir.file("none"), ""}); })
            .empty());
  CHECK(read_file(in) == "ply\n");
}

TEST_CASE("check_outputs refuses a name without its extensions and one file given twice", "[io]") {
  TempDir dir;
  const std::string obj = dir.file("out.obj");
  CHECK(error_of([&] { meshsal::check_outputs({{obj, "path", {".ply", ".glb"}}}, {}); }) ==
        obj + ": path must be a .ply or .glb file");
  CHECK(error_of([&] { meshsal::check_outputs({{dir.file("OUT.PLY"), "-o", {".ply"}}}, {}); }).empty());
  const std::string png = dir.file("a.png");
  CHECK(error_of([&] { meshsal::check_outputs({{png, "-o", {".png"}}, {png, "--map", {".png"}}}, {}); }) ==
        png + ": given for both -o and --map");
  CHECK(has(error_of([&] { meshsal::check_outputs({{dir.file("no/such/x.png"), "-o", {}}}, {}); }), "cannot write"));
  CHECK(has(error_of([&] { meshsal::check_outputs({{dir.path.string(), "-o", {}}}, {}); }), "cannot write"));
}

TEST_CASE("check_outputs removes the temporaries a killed writer left beside its output", "[io]") {
  TempDir dir;
  const std::string stale = dir.write("out.ply.tmp.AbC123", "half");
  const std::string other = dir.write("other.ply.tmp.AbC123", "someone else's");
  meshsal::check_outputs({{dir.file("out.ply"), "-o", {".ply"}}}, {});
  CHECK(!fs::exists(stale));
  CHECK(fs::exists(other));
}

TEST_CASE("saliency_file and simplify_file never write over their input, through a link either", "[outofcore]") {
  for (const char* name : {"saliency_file", "simplify_file"}) {
    INFO(name);
    const auto call = std::string(name) == "saliency_file" ? run_saliency_file : run_simplify_file;
    TempDir dir;
    const std::string in = read_only_input(dir);
    const std::string before = file_bytes(in);
    const std::string link = dir.file("link.ply"), hard = dir.file("hard.ply");
    fs::create_symlink(in, link);
    fs::create_hard_link(in, hard);
    for (const std::string& out : {in, link, hard}) {
      INFO(out);
      const std::string e = error_of([&] { call(in, out); });
      CHECK(e == out + ": the output is the input file '" + in + "' (an output never replaces an input)");
    }
    CHECK(file_bytes(in) == before);
    CHECK(fs::is_symlink(link));
    CHECK(dir.entries() == 3);  // no temporary left behind
    // The check is the library's own: a fresh name beside it works.
    call(in, dir.file("out.ply"));
    CHECK(fs::exists(dir.file("out.ply")));
    CHECK(file_bytes(in) == before);
  }
}

TEST_CASE("saliency_file and simplify_file refuse a name that is not a PLY's, before any work", "[outofcore]") {
  TempDir dir;
  const std::string in = read_only_input(dir);
  for (const char* name : {"saliency_file", "simplify_file"}) {
    const auto call = std::string(name) == "saliency_file" ? run_saliency_file : run_simplify_file;
    for (const char* ext : {".obj", ".glb", ".gltf", ".ply.gz", ""}) {
      const std::string out = dir.file(std::string("out") + ext);
      INFO(out);
      CHECK(error_of([&] { call(in, out); }) ==
            out + ": " + name + " writes a binary PLY: give an output name ending in .ply");
      CHECK(!fs::exists(out));
      // Before the input is read: a missing input still gets the output's message.
      CHECK(has(error_of([&] { call(dir.file("missing.ply"), out); }), name + std::string(" writes a binary PLY")));
    }
  }
  CHECK(dir.entries() == 1);
}
