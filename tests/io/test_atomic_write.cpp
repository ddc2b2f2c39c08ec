// Every output goes through write_file_atomically: a fresh temporary name (a symlink planted
// at the old fixed OUT.png.tmp is not followed), sensible permissions, and errors that name
// the file, a full disk included (simulated with RLIMIT_FSIZE, which needs no privileges).
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <filesystem>

#include "io/atomic_write.h"
#include "io/png_image.h"
#include "cli/synthetic.h"
#include "test_io_util.h"

using meshsal_test::error_of;
using meshsal_test::TempDir;
namespace fs = std::filesystem;

namespace {

std::string read_all(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

size_t files_in(const fs::path& dir) {
  size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += bool(e.path().filename().string().size());
  return n;
}

// Lowers this process's file size limit to `bytes` (writes past it fail with EFBIG instead
// of raising SIGXFSZ) for the scope.
struct FileSizeLimit {
  rlimit old{};
  void (*old_handler)(int);
  explicit FileSizeLimit(rlim_t bytes) {
    ::getrlimit(RLIMIT_FSIZE, &old);
    old_handler = ::signal(SIGXFSZ, SIG_IGN);
    rlimit r = old;
    r.rlim_cur = bytes;
    REQUIRE(::setrlimit(RLIMIT_FSIZE, &r) == 0);
  }
  ~FileSizeLimit() {
    ::setrlimit(RLIMIT_FSIZE, &old);
    ::signal(SIGXFSZ, old_handler);
  }
};

}  // namespace

TEST_CASE("write_png does not follow a symlink planted at OUT.png.tmp", "[io]") {
  TempDir dir;
  const std::string victim = dir.write("victim.txt", "keep me");
  const std::string out = dir.file("out.png");
  fs::create_symlink(victim, out + ".tmp");
  meshsal::write_png(out, meshsal::Image(4, 3, 10, 20, 30));
  CHECK(read_all(victim) == "keep me");
  CHECK(fs::is_symlink(out + ".tmp"));
  const std::string png = read_all(out);
  REQUIRE(png.size() > 8);
  CHECK(png.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0);
  CHECK(files_in(dir.path) == 3);  // victim, the planted link, out.png: no temporary left
}

TEST_CASE("written files get 0666 minus the umask, a replaced file keeps its mode", "[io]") {
  TempDir dir;
  const mode_t old_mask = ::umask(022);
  const std::string png = dir.file("a.png"), ply = dir.file("a.ply");
  meshsal::write_png(png, meshsal::Image(2, 2));
  meshsal::write_ply(ply, meshsal::make_sphere(1.0, 1), {});
  struct stat st;
  REQUIRE(::stat(png.c_str(), &st) == 0);
  CHECK((st.st_mode & 07777) == 0644);
  REQUIRE(::stat(ply.c_str(), &st) == 0);
  CHECK((st.st_mode & 07777) == 0644);
  REQUIRE(::chmod(ply.c_str(), 0600) == 0);
  meshsal::write_obj(ply.substr(0, ply.size() - 4) + ".obj", meshsal::make_sphere(1.0, 1));
  meshsal::write_ply(ply, meshsal::make_sphere(1.0, 2), {});
  REQUIRE(::stat(ply.c_str(), &st) == 0);
  CHECK((st.st_mode & 07777) == 0600);
  ::umask(old_mask);
}

TEST_CASE("a failed write names the file and leaves the old one and no temporary", "[io]") {
  TempDir dir;
  const meshsal::Mesh big = meshsal::make_sphere(1.0, 5);  // ~0.5 MB as PLY or OBJ
  const std::string ply = dir.write("out.ply", "previous ply");
  const std::string obj = dir.write("out.obj", "previous obj");
  const std::string png = dir.write("out.png", "previous png");
  std::string ply_error, obj_error, png_error;
  {
    FileSizeLimit limit(4096);
    ply_error = error_of([&] { meshsal::write_ply(ply, big, {}); });
    obj_error = error_of([&] { meshsal::write_obj(obj, big); });
    png_error = error_of([&] { meshsal::write_png(png, meshsal::Image(512, 512, 1, 2, 3)); });
  }
  CHECK(ply_error == ply + ": write failed: File too large");
  CHECK(obj_error == obj + ": write failed: File too large");
  CHECK(png_error.rfind(png + ": write failed: ", 0) == 0);
  CHECK(read_all(ply) == "previous ply");
  CHECK(read_all(obj) == "previous obj");
  CHECK(read_all(png) == "previous png");
  CHECK(files_in(dir.path) == 3);
}

TEST_CASE("write_file_atomically: an error in the body removes the temporary", "[io]") {
  TempDir dir;
  const std::string out = dir.file("x.bin");
  const std::string e = error_of([&] {
    meshsal::write_file_atomically(out, [&](std::FILE* f) {
      meshsal::write_all(f, "abc", 3, out);
      throw meshsal::Error(out + ": stopped");
    });
  });
  CHECK(e == out + ": stopped");
  CHECK(files_in(dir.path) == 0);
  CHECK(error_of([&] { meshsal::write_file_atomically(dir.path.string(), [](std::FILE*) {}); }) ==
        dir.path.string() + ": cannot write: it is a folder");
}
