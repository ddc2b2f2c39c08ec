// Issue 21 (1, 8): the one rule every writer follows (io/atomic_write.h). A symlink is
// followed and stays a link; a character device or a named pipe is written in place (the
// machine's /dev/null was replaced by a regular file when `batch --log /dev/null` ran as
// root); a folder, a block device or a socket is refused; the temporaries a killed run left
// are removed by the next one, a live writer's are not.
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "cli_run.h"
#include "cli/synthetic.h"
#include "io/append_file.h"
#include "io/atomic_write.h"
#include "test_io_util.h"
#include "test_util.h"

using meshsal_test::error_of;
using meshsal_test::TempDir;
namespace fs = std::filesystem;

namespace {

bool is_char_device(const std::string& p) {
  struct stat st;
  return ::lstat(p.c_str(), &st) == 0 && S_ISCHR(st.st_mode);
}
bool is_fifo(const std::string& p) {
  struct stat st;
  return ::lstat(p.c_str(), &st) == 0 && S_ISFIFO(st.st_mode);
}

void write_text(const std::string& path, const std::string& text) {
  meshsal::write_file_atomically(path, [&](std::FILE* f) { meshsal::write_all(f, text.data(), text.size(), path); });
}

// Opens the FIFO for reading without waiting, so that a writer sees a reader at once.
struct FifoReader {
  int fd;
  explicit FifoReader(const std::string& path) : fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK)) {}
  ~FifoReader() { ::close(fd); }
  std::string drain() {
    ::fcntl(fd, F_SETFL, 0);
    std::string s;
    char buf[4096];
    ssize_t n;
    while ((n = ::read(fd, buf, sizeof buf)) > 0) s.append(buf, size_t(n));
    return s;
  }
};

}  // namespace

TEST_CASE("writers: a symlink is followed, the file it names replaced and the link kept", "[io]") {
  TempDir dir;
  const std::string target = dir.write("real.txt", "old");
  const std::string link = dir.file("link.txt");
  fs::create_symlink("real.txt", link);  // relative, as users make them
  write_text(link, "new");
  CHECK(fs::is_symlink(link));
  CHECK(meshsal_test::read_file(target) == "new");
  // A dangling link: the file it names is created.
  const std::string dangling = dir.file("dangling.ply");
  fs::create_symlink(dir.file("made.ply"), dangling);
  meshsal::write_ply(dangling, meshsal::make_sphere(1.0, 1), {});
  CHECK(fs::is_symlink(dangling));
  CHECK(fs::is_regular_file(dir.file("made.ply")));
  CHECK(meshsal::load_mesh(dangling).vertex_count() == 42);
  // A link to a folder is a folder.
  fs::create_directory(dir.file("sub"));
  fs::create_symlink(dir.file("sub"), dir.file("to_sub"));
  CHECK(error_of([&] { write_text(dir.file("to_sub"), "x"); }) == dir.file("to_sub") + ": cannot write: it is a folder");
  CHECK(dir.entries() == 6);  // no temporary left anywhere
}

TEST_CASE("writers: a named pipe is written in place, or refused at once when nothing reads it", "[io]") {
  TempDir dir;
  const std::string fifo = dir.file("out.ply");
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  // No reader: refused now (it used to wait, or replace the pipe by a file).
  CHECK(error_of([&] { write_text(fifo, "data"); }) ==
        fifo + ": cannot write: it is a named pipe (FIFO) and nothing reads from it");
  CHECK(is_fifo(fifo));
  {
    FifoReader reader(fifo);
    write_text(fifo, "hello through the pipe");
    CHECK(reader.drain() == "hello through the pipe");
  }
  CHECK(is_fifo(fifo));
  // A reader that goes away: an Error, and the process lives on (no SIGPIPE).
  {
    std::thread reader([&] {  // reads a little, then goes away
      const int fd = ::open(fifo.c_str(), O_RDONLY);
      char buf[16];
      if (fd >= 0 && ::read(fd, buf, sizeof buf) >= 0) ::close(fd);
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the reader is in open()
    const std::string e = error_of([&] { write_text(fifo, std::string(1 << 22, 'x')); });
    reader.join();
    INFO(e);
    CHECK((e == fifo + ": write failed: Broken pipe" ||
           e == fifo + ": cannot write: it is a named pipe (FIFO) and nothing reads from it"));
  }
  CHECK(is_fifo(fifo));
  CHECK(dir.entries() == 1);
}

TEST_CASE("writers: a character device is written in place, disks and sockets are refused", "[io]") {
  TempDir dir;
  // /dev/full: writes fail there, as on a full disk; it stays a device. Reached through a
  // link of our own, never named directly: a writer that regressed to the rename would
  // replace the link, not the machine's device (as root, the old one replaced the device).
  const std::string full = dir.file("full.txt");
  fs::create_symlink("/dev/full", full);
  CHECK(error_of([&] { write_text(full, std::string(100000, 'x')); }) == full + ": write failed: No space left on device");
  CHECK(is_char_device("/dev/full"));
  CHECK(fs::is_symlink(full));
  // A link to /dev/null is followed to the device, which is written, not replaced.
  fs::create_symlink("/dev/null", dir.file("null.png"));
  meshsal::write_png(dir.file("null.png"), meshsal::Image(4, 4));
  CHECK(fs::is_symlink(dir.file("null.png")));
  CHECK(is_char_device("/dev/null"));
  // Device nodes of our own (root only): a copy of /dev/null written, a disk refused.
  const std::string null_copy = dir.file("null_copy.ply"), disk = dir.file("disk.ply");
  if (::mknod(null_copy.c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0) {
    meshsal::write_ply(null_copy, meshsal::make_sphere(1.0, 1), {});
    CHECK(is_char_device(null_copy));
    REQUIRE(::mknod(disk.c_str(), S_IFBLK | 0600, makedev(7, 0)) == 0);
    CHECK(error_of([&] { write_text(disk, "x"); }).find(disk + ": cannot write: it is a block device") == 0);
    struct stat st;
    REQUIRE(::lstat(disk.c_str(), &st) == 0);
    CHECK(S_ISBLK(st.st_mode));
  } else {
    meshsal_test::skip_case("not root: device nodes of our own are not tested");
  }
  // A socket.
  const std::string sock = dir.file("s.sock");
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::strncpy(addr.sun_path, sock.c_str(), sizeof addr.sun_path - 1);
  if (sock.size() < sizeof addr.sun_path && ::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0)
    CHECK(error_of([&] { write_text(sock, "x"); }) == sock + ": cannot write: it is a socket");
  ::close(fd);
}

TEST_CASE("writers: the temporaries a killed writer left are removed, a live writer's kept", "[io]") {
  TempDir dir;
  const std::string out = dir.file("out.ply");
  // A writer killed with SIGKILL in the middle of writing.
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    meshsal::write_file_atomically(out, [&](std::FILE* f) {
      meshsal::write_all(f, "half a file", 11, out);
      std::fflush(f);
      ::raise(SIGKILL);
    });
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  REQUIRE(WIFSIGNALED(status));
  size_t left = 0;
  for (const auto& e : fs::directory_iterator(dir.path)) left += e.path().filename().string().rfind("out.ply.tmp.", 0) == 0;
  REQUIRE(left == 1);
  // A live writer's temporary (its lock held), another output's, and one that only looks alike.
  const std::string live = dir.write("out.ply.tmp.Live01", "in progress");
  const int live_fd = ::open(live.c_str(), O_RDONLY);
  REQUIRE(::flock(live_fd, LOCK_EX) == 0);
  dir.write("other.ply.tmp.Abc123", "another output's");
  dir.write("out.ply.tmp.toolong1", "not mkstemp's pattern");
  const size_t removed =
      meshsal::remove_stale_temporaries(dir.path.string(), [](const std::string& base) { return base == "out.ply"; });
  CHECK(removed == 1);
  CHECK(fs::exists(live));
  CHECK(fs::exists(dir.file("other.ply.tmp.Abc123")));
  CHECK(fs::exists(dir.file("out.ply.tmp.toolong1")));
  ::close(live_fd);
  // Once its writer is gone, the next run takes that one too.
  CHECK(meshsal::remove_stale_temporaries(dir.path.string(), [](const std::string& b) { return b == "out.ply"; }) == 1);
  CHECK_FALSE(fs::exists(live));
}

TEST_CASE("cli: outputs through links, into devices and pipes, stale temporaries of the run removed", "[cli][io]") {
  using namespace meshsal_test;
  const auto dir = scratch_dir("output_targets");
  const std::string in = (dir / "ball.obj").string();
  meshsal::write_obj(in, meshsal::make_sphere(1.0, 2));
  // saliency -o through a symlink: the linked file gets the PLY.
  fs::create_symlink("real.ply", dir / "link.ply");
  CliRun r = run_cli("saliency " + quoted(in) + " -o " + quoted((dir / "link.ply").string()) + " -q", dir);
  CHECK(r.rc == 0);
  CHECK(fs::is_symlink(dir / "link.ply"));
  CHECK(meshsal::load_mesh((dir / "real.ply").string()).vertex_count() == 162);
  // batch --log onto a device (through a link: /dev/null itself is not put at risk here)
  // and onto a pipe with a reader.
  fs::create_symlink("/dev/null", dir / "null.jsonl");
  r = run_cli("batch " + quoted(in) + " -o " + quoted((dir / "o1").string()) + " --log " +
                  quoted((dir / "null.jsonl").string()) + " -q", dir);
  CHECK(r.rc == 0);
  CHECK(is_char_device("/dev/null"));
  CHECK(fs::is_symlink(dir / "null.jsonl"));
  const std::string fifo = (dir / "log.fifo").string();
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  {
    FifoReader reader(fifo);
    r = run_cli("batch " + quoted(in) + " -o " + quoted((dir / "o2").string()) + " --log " + quoted(fifo) + " -q", dir);
    CHECK(r.rc == 0);
    const std::string log = reader.drain();
    CHECK(log.find("\"status\": \"done\"") != std::string::npos);
  }
  CHECK(is_fifo(fifo));
  // Without a reader the log is refused before any work (nothing else is written).
  r = run_cli("batch " + quoted(in) + " -o " + quoted((dir / "o3").string()) + " --log " + quoted(fifo), dir);
  CHECK(r.rc == 1);
  CHECK(r.err == "error: " + fifo + ": cannot write: it is a named pipe (FIFO) and nothing reads from it\n");
  CHECK_FALSE(fs::exists(dir / "o3" / "ball_saliency.ply"));
  // What a run killed mid-write left: the next run in that folder removes it.
  fs::create_directories(dir / "o4");
  std::ofstream(dir / "o4" / "ball_saliency.ply.tmp.Xy12Zw") << "half a PLY";
  std::ofstream(dir / "out.ply.tmp.Ab34Cd") << "half a PLY";
  r = run_cli("batch " + quoted(in) + " -o " + quoted((dir / "o4").string()) + " -q", dir);
  CHECK(r.rc == 0);
  CHECK_FALSE(fs::exists(dir / "o4" / "ball_saliency.ply.tmp.Xy12Zw"));
  r = run_cli("saliency " + quoted(in) + " -o " + quoted((dir / "out.ply").string()) + " -q", dir);
  CHECK(r.rc == 0);
  CHECK_FALSE(fs::exists(dir / "out.ply.tmp.Ab34Cd"));
}

TEST_CASE("AppendFile: lines go to the end, earlier ones stay, a cut last line is ended first", "[io]") {
  TempDir dir;
  const std::string p = dir.write("log.jsonl", "{\"a\": 1}\n{\"cut");
  {
    meshsal::AppendFile f(p);
    f.append("{\"b\": 2}");
    f.sync();
  }
  CHECK(meshsal_test::read_file(p) == "{\"a\": 1}\n{\"cut\n{\"b\": 2}\n");
  const std::string link = dir.file("full.jsonl");  // a link, never /dev/full itself (above)
  fs::create_symlink("/dev/full", link);
  meshsal::AppendFile full(link);
  CHECK_THROWS_WITH(full.append("x"), link + ": write failed: No space left on device");
  CHECK(is_char_device("/dev/full"));
}
