// [io] hostile input (issue 10): header/body boundaries, byte-order marks, CR-only line
// ends, comments in a PLY body, devices and pipes, gzip bombs. Each case names the file
// in a one-line Error, or loads exactly the mesh the file means.
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <zlib.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <thread>

#include "meshsal/meshsal.h"
#include "test_io_util.h"

using meshsal::LoadOptions;
using meshsal::Mesh;
using meshsal_test::put_bin;
using meshsal_test::TempDir;

namespace {

void expect_error(const std::string& path, const std::string& problem, const LoadOptions& options = {}) {
  INFO("file: " << path);
  std::string msg;
  try {
    meshsal::load_mesh(path, options);
  } catch (const meshsal::Error& e) {
    msg = e.what();
  }
  INFO("message: " << msg);
  REQUIRE(!msg.empty());
  CHECK(msg.find('\n') == std::string::npos);
  CHECK(msg.rfind(path + ": ", 0) == 0);
  CHECK(msg.find(problem) != std::string::npos);
}

void expect_same(const Mesh& a, const Mesh& b) {
  CHECK(a.positions == b.positions);
  CHECK(a.triangles == b.triangles);
}

const std::string kBom = "\xEF\xBB\xBF";
const std::string kObj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n";
const std::string kOff = "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";
const std::string kPlyAscii =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";

std::string binary_header(uint64_t nv, uint64_t nf) {
  return "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(nv) +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(nf) +
         "\nproperty list uchar int vertex_indices\nend_header\n";
}

std::string binary_body() {
  std::string s;
  for (float f : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) put_bin(s, f);
  put_bin<uint8_t>(s, 3);
  for (int32_t i : {0, 1, 2}) put_bin(s, i);
  return s;
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
    s.replace(at, from.size(), to);
  return s;
}

// gzip-compresses `head` followed by `zeros` zero bytes, streaming (the zeros never exist
// in memory at once); level 1, the fastest, still packs 256 MiB of zeros into ~1.1 MB.
std::string gzip_with_zeros(const std::string& head, size_t zeros) {
  z_stream zs{};
  REQUIRE(deflateInit2(&zs, 1, Z_DEFLATED, 15 + 16, 9, Z_DEFAULT_STRATEGY) == Z_OK);
  std::string out;
  std::vector<char> buf(1 << 16);
  auto pump = [&](const char* data, size_t n, int flush) {
    zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data));
    zs.avail_in = static_cast<uInt>(n);
    do {
      zs.next_out = reinterpret_cast<Bytef*>(buf.data());
      zs.avail_out = static_cast<uInt>(buf.size());
      deflate(&zs, flush);
      out.append(buf.data(), buf.size() - zs.avail_out);
    } while (zs.avail_out == 0 || (flush == Z_FINISH && zs.avail_in > 0));
  };
  pump(head.data(), head.size(), Z_NO_FLUSH);
  const std::vector<char> block(1 << 20, 0);
  for (size_t left = zeros; left > 0;) {
    const size_t n = std::min(left, block.size());
    pump(block.data(), n, Z_NO_FLUSH);
    left -= n;
  }
  pump(nullptr, 0, Z_FINISH);
  deflateEnd(&zs);
  return out;
}

// Sets an environment variable for one scope (ctest runs each case in its own process).
struct ScopedEnv {
  std::string name;
  ScopedEnv(const std::string& n, const std::string& value) : name(n) { ::setenv(n.c_str(), value.c_str(), 1); }
  ~ScopedEnv() { ::unsetenv(name.c_str()); }
};

}  // namespace

TEST_CASE("hostile PLY: the 175-byte file whose end_header has no newline", "[io]") {
  TempDir dir;
  // The header alone, cut before its last newline: the body offset used to point one byte
  // past the buffer, the size check underflowed and the reader ran off the allocation.
  std::string bytes = binary_header(30000, 1000);
  bytes.pop_back();
  REQUIRE(bytes.size() == 175);
  expect_error(dir.write("no_newline.ply", bytes), "header line 9: end_header is not followed by a newline");
}

TEST_CASE("hostile PLY: every header/body boundary case is refused", "[io]") {
  TempDir dir;
  const std::string header = binary_header(3, 1), body = binary_body();
  REQUIRE(meshsal_test::load_error(dir.write("ok.ply", header + body)).empty());
  std::string no_nl = header;
  no_nl.pop_back();
  expect_error(dir.write("small_counts.ply", binary_header(3, 1).substr(0, header.size() - 1)),
               "end_header is not followed by a newline");
  // ascii: the same, and with an empty body after it.
  std::string ascii = kPlyAscii.substr(0, kPlyAscii.find("end_header") + 10);
  expect_error(dir.write("ascii_no_nl.ply", ascii), "end_header is not followed by a newline");
  expect_error(dir.write("empty_body.ply", header), "header element counts need at least 37 bytes but the body has 0");
  // Text after end_header on its line would shift where the body starts.
  expect_error(dir.write("junk.ply", replace_all(header, "end_header\n", "end_header \x01\x02\n") + body),
               "header line 9: more text after end_header on its line");
  // CR-only line ends in a binary header: "\r" then a body starting with '\n' is ambiguous.
  expect_error(dir.write("cr_binary.ply", replace_all(header, "\n", "\r") + body), "CR-only line ends");
  // Header and body run together (no newline, body bytes right after end_header).
  expect_error(dir.write("glued.ply", no_nl + body), "end_header");
  // The header cut anywhere: never read past the data.
  for (size_t cut = 0; cut < header.size() + body.size(); ++cut) {
    INFO("cut at " << cut);
    CHECK(!meshsal_test::load_error(dir.write("cut.ply", (header + body).substr(0, cut))).empty());
  }
}

TEST_CASE("hostile input: a UTF-8 byte-order mark is skipped in OBJ, OFF and ascii PLY", "[io]") {
  TempDir dir;
  // OBJ used to drop the first v line ("\xEF\xBB\xBFv" is no key) and shift every index.
  const Mesh obj = meshsal::load_mesh(dir.write("plain.obj", kObj));
  REQUIRE(obj.vertex_count() == 4);
  expect_same(meshsal::load_mesh(dir.write("bom.obj", kBom + kObj)), obj);
  expect_same(meshsal::load_mesh(dir.write_gz("bom.obj.gz", kBom + kObj)), obj);
  expect_same(meshsal::load_mesh(dir.write("bom.off", kBom + kOff)), obj);
  expect_same(meshsal::load_mesh(dir.write("bom.ply", kBom + kPlyAscii)), obj);
}

TEST_CASE("hostile input: byte-order marks in odd places get messages that say so", "[io]") {
  TempDir dir;
  expect_error(dir.write("bom_binary.ply", kBom + binary_header(3, 1) + binary_body()),
               "a UTF-8 byte-order mark in front of a binary PLY header");
  expect_error(dir.write("joined.obj", kObj + kBom + kObj), "line 7: a UTF-8 byte-order mark inside the file");
  expect_error(dir.write("joined.off", replace_all(kOff, "1 1 0\n", kBom + "1 1 0\n")),
               "line 5: a UTF-8 byte-order mark inside the file");
  expect_error(dir.write("utf16.obj", std::string("\xFF\xFEv\0 \0", 6)), "UTF-16 text");
}

TEST_CASE("hostile input: CR-only line ends are read as line ends", "[io]") {
  TempDir dir;
  const Mesh obj = meshsal::load_mesh(dir.write("plain.obj", kObj));
  // Before, "v 0 0 0\rv 1 0 0\r..." was one line: one vertex, the rest extra columns.
  expect_same(meshsal::load_mesh(dir.write("cr.obj", replace_all(kObj, "\n", "\r"))), obj);
  expect_same(meshsal::load_mesh(dir.write("mixed.obj", "v 0 0 0\rv 1 0 0\r\nv 1 1 0\nv 0 1 0\rf 1 2 3\nf 1 3 4")),
              obj);
  expect_same(meshsal::load_mesh(dir.write("cr.off", replace_all(kOff, "\n", "\r"))), obj);
  expect_same(meshsal::load_mesh(dir.write("cr.ply", replace_all(kPlyAscii, "\n", "\r"))), obj);
  // Line numbers count CR-only lines.
  expect_error(dir.write("bad_cr.obj", "v 0 0 0\rv 1 0 0\rv 1 x 0\r"), "line 3: bad vertex coordinate 'x'");
}

TEST_CASE("hostile PLY: a comment line in an ascii body says what it is", "[io]") {
  TempDir dir;
  expect_error(dir.write("comment_after.ply", kPlyAscii + "comment written by a broken exporter\n"),
               "a 'comment' line after the last element (PLY allows comments only in the header)");
  expect_error(dir.write("comment_inside.ply", replace_all(kPlyAscii, "3 0 1 2\n", "comment here\n3 0 1 2\n")),
               "line 14: a 'comment' line inside the body");
}

TEST_CASE("hostile input: devices are refused before reading", "[io]") {
  TempDir dir;
  const std::string zero = dir.file("zero.ply");
  REQUIRE(::symlink("/dev/zero", zero.c_str()) == 0);
  // Before, /dev/zero was read until memory ran out.
  expect_error(zero, "is a character device, not a mesh file");
  const std::string null_obj = dir.file("null.obj");
  REQUIRE(::symlink("/dev/null", null_obj.c_str()) == 0);
  expect_error(null_obj, "is a character device");
}

namespace {

// Writes `data` into the FIFO at `path` from a thread, ignoring a reader that hangs up.
struct FifoWriter {
  std::thread thread;
  FifoWriter(const std::string& path, std::string data) {
    thread = std::thread([path, data] {
      const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
      int fd = -1;
      while (fd < 0 && std::chrono::steady_clock::now() < deadline) {
        fd = ::open(path.c_str(), O_WRONLY | O_NONBLOCK);  // ENXIO until the reader opens
        if (fd < 0) std::this_thread::sleep_for(std::chrono::milliseconds(2));
      }
      if (fd < 0) return;
      ::fcntl(fd, F_SETFL, 0);
      for (size_t at = 0; at < data.size();) {
        const ssize_t n = ::write(fd, data.data() + at, data.size() - at);
        if (n <= 0) break;
        at += static_cast<size_t>(n);
      }
      ::close(fd);
    });
  }
  ~FifoWriter() { thread.join(); }
};

}  // namespace

TEST_CASE("hostile input: a FIFO is read, up to a limit", "[io]") {
  TempDir dir;
  // The writer may outlive a reader that gave up; the old disposition comes back at the end
  // (a SIGPIPE left ignored is inherited by the CLIs later tests start, which keep it so).
  struct IgnoreSigpipe {
    void (*old)(int) = ::signal(SIGPIPE, SIG_IGN);
    ~IgnoreSigpipe() { ::signal(SIGPIPE, old); }
  } ignore_sigpipe;
  const std::string fifo = dir.file("pipe.obj");
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  {
    FifoWriter writer(fifo, kObj);
    const Mesh m = meshsal::load_mesh(fifo);
    CHECK(m.vertex_count() == 4);
    CHECK(m.triangle_count() == 2);
  }
  {
    std::string big = kObj;
    while (big.size() < 300000) big += "# padding padding padding padding padding\n";
    FifoWriter writer(fifo, big);
    LoadOptions small;
    small.max_input_bytes = 100000;
    expect_error(fifo, "more than 100000 bytes came from a pipe", small);
  }
}

TEST_CASE("hostile gzip: a bomb is refused after inflating what its header allows", "[io]") {
  TempDir dir;
  // A valid header for 3 vertices and 1 face followed by 256 MiB of zeros (~1.1 MB gzipped).
  const std::string gz = gzip_with_zeros(binary_header(3, 1) + binary_body(), size_t(256) << 20);
  CHECK(gz.size() < (size_t(3) << 19));
  const std::string path = dir.write("bomb.ply.gz", gz);
  // Limit: header + 64 MiB + 64 x (12 x 3 + 13 x 1) bytes.
  const uint64_t limit = binary_header(3, 1).size() + (uint64_t(64) << 20) + 64 * (36 + 13);
  expect_error(path, "gzip data inflates to more than " + std::to_string(limit) + " bytes");
  // A garbled header is refused from the first inflated MiB, whatever the counts allow.
  expect_error(dir.write("garbage.ply.gz", gzip_with_zeros("ply\nformat ascii 1.0\nelephant\nend_header\n", size_t(16) << 20)),
               "unexpected header line 'elephant'");
  // ... before the rest is inflated: damage after the first MiB is never reached.
  std::string damaged = gzip_with_zeros("ply\nformat ascii 1.0\nelephant\nend_header\n", size_t(16) << 20);
  for (size_t i = damaged.size() / 2; i < damaged.size() - 8; ++i) damaged[i] = static_cast<char>(0xA5 ^ i);
  expect_error(dir.write("damaged.ply.gz", damaged), "unexpected header line 'elephant'");
  // OFF: the counts' rule too.
  expect_error(dir.write("bomb.off.gz", gzip_with_zeros(kOff, size_t(80) << 20)), "gzip data inflates to more than");
}

TEST_CASE("hostile gzip: the inflate limit is an option (the library reads no MESHSAL_MAX_INPUT)", "[io]") {
  TempDir dir;
  std::string obj = kObj;
  while (obj.size() < (size_t(3) << 20)) obj += "# a long comment line that compresses very well indeed\n";
  const std::string path = dir.write_gz("long.obj.gz", obj);
  // Crossing the first MiB (where the head is checked) inflates fine by default.
  CHECK(meshsal::load_mesh(path).vertex_count() == 4);
  LoadOptions two_mib;
  two_mib.max_input_bytes = 2 << 20;
  expect_error(path, "gzip data inflates to more than 2 MiB", two_mib);
  {
    // The environment is the meshsal command's (load_options in src/cli), not the library's.
    ScopedEnv env("MESHSAL_MAX_INPUT", "2M");
    CHECK(meshsal::load_mesh(path).vertex_count() == 4);
    ScopedEnv junk("MESHSAL_MAX_INPUT", "lots");
    CHECK(meshsal::load_mesh(path).vertex_count() == 4);
  }
  {
    // Raising it lets a padded PLY beyond the counts' rule through to the parser.
    const std::string bomb = dir.write("pad.ply.gz", gzip_with_zeros(kPlyAscii, size_t(80) << 20));
    expect_error(bomb, "gzip data inflates to more than");
    LoadOptions one_gib;
    one_gib.max_input_bytes = uint64_t(1) << 30;
    expect_error(bomb, "83886080 bytes of data after the last element", one_gib);
  }
}

TEST_CASE("load_mesh_bytes: the in-memory entry names the input in errors", "[io]") {
  CHECK(meshsal::load_mesh_bytes(kObj, "mem.obj").vertex_count() == 4);
  CHECK_THROWS_WITH(meshsal::load_mesh_bytes("v 0 0 0\n", "mem.obj"), "mem.obj: mesh has no faces");
  CHECK_THROWS_WITH(meshsal::load_mesh_bytes(kObj, "mem.xyz"), Catch::StartsWith("mem.xyz: unknown mesh format"));
}

TEST_CASE("hostile input: messages hold only printable text, whatever the file holds", "[io]") {
  TempDir dir;
  // A long token used to be quoted raw (control bytes and all) once it passed 40 characters.
  const std::string junk = "1" + std::string(20, '\x1b') + "[2J" + std::string(30, '\x07');
  const std::string obj_path = dir.write("junk.obj", "v 0 0 " + junk + "\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string msg = meshsal_test::load_error(obj_path);
  CHECK(msg.find("bad vertex coordinate '1????") != std::string::npos);
  for (char c : msg.substr(obj_path.size())) CHECK((static_cast<unsigned char>(c) >= 32 && c != 127));
  expect_error(dir.write("name.ply", "ply\nformat ascii 1.0\nelement ve\x01rtex 3\nend_header\n"),
               "bad element line 'element ve?rtex 3'");
  expect_error(dir.write("prop.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float \x1b[x\nend_header\n"),
               "property name '?[x' has unprintable characters");
}

namespace {

// Runs the meshsal CLI with `env` in front; returns the exit status, stderr in `err`.
int run_cli(const std::string& env, const std::string& args, const TempDir& dir, std::string& err) {
  const std::string err_path = dir.file("stderr.txt");
  const std::string cmd = env + " " + MESHSAL_CLI + " " + args + " > /dev/null 2> " + err_path + " < /dev/null";
  const int status = std::system(cmd.c_str());
  err = meshsal_test::read_file(err_path);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

TEST_CASE("hostile input: every command honours MESHSAL_MAX_INPUT and --help says so", "[io]") {
  TempDir dir;
  std::string obj = kObj;
  while (obj.size() < 4096) obj += "# padding so that the file inflates past one KiB\n";
  const std::string gz = dir.write_gz("pad.obj.gz", obj);
  std::string err;
  CHECK(run_cli("", "saliency " + gz + " -o " + dir.file("ok.ply") + " -q", dir, err) == 0);
  for (const std::string& args : {"saliency " + gz + " -o " + dir.file("s.ply"), "compare " + gz + " " + gz,
                                  "render " + gz + " -o " + dir.file("r.png")}) {
    INFO(args);
    CHECK(run_cli("MESHSAL_MAX_INPUT=1K", args, dir, err) == 1);
    CHECK(err == "error: " + gz + ": gzip data inflates to more than 1024 bytes, the limit for this file "
                                  "(a gzip bomb?); MESHSAL_MAX_INPUT=BYTES raises it\n");
  }
  CHECK(run_cli("MESHSAL_MAX_INPUT=lots", "saliency " + gz + " -o " + dir.file("s.ply"), dir, err) == 1);
  CHECK(err.find("MESHSAL_MAX_INPUT: 'lots' is not a byte count") != std::string::npos);
  CHECK(run_cli("MESHSAL_MAX_INPUT=1M", "saliency " + gz + " -o " + dir.file("s.ply") + " -q", dir, err) == 0);
  std::string help;
  {
    const std::string out_path = dir.file("help.txt");
    REQUIRE(std::system((std::string(MESHSAL_CLI) + " --help > " + out_path).c_str()) == 0);
    help = meshsal_test::read_file(out_path);
  }
  CHECK(help.find("MESHSAL_MAX_INPUT=BYTES") != std::string::npos);
}

// Issue 21 (10): one face line with 25M corners became 26M fan triangles (2.7 GB, 31 s): a
// polygon's corner count is bounded in every format.
TEST_CASE("loaders: a polygon with more than 65536 corners is refused, the largest allowed is read", "[io]") {
  TempDir dir;
  const auto face = [](size_t corners, const char* prefix) {
    std::string s = prefix;
    for (size_t i = 1; i <= corners; ++i) s += " " + std::to_string(i);
    return s + "\n";
  };
  const auto vertices = [](size_t n, const char* v) {
    std::string s;
    for (size_t i = 0; i < n; ++i) {
      const double a = 6.283185307179586 * double(i) / double(n);
      s += std::string(v) + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
    }
    return s;
  };
  const size_t big = 70000;
  const std::string obj = dir.write("big.obj", vertices(big, "v ") + face(big, "f"));
  CHECK(meshsal_test::load_error(obj) == obj + ": line " + std::to_string(big + 1) +
                               ": face with more than 65536 vertices (65536 is the most a polygon may have)");
  const std::string obj_attr = obj;
  meshsal::LoadOptions with_attributes;
  with_attributes.attributes = true;
  CHECK_THROWS_WITH(meshsal::load_mesh(obj_attr, with_attributes),
                    Catch::Contains("face with more than 65536 vertices"));
  const std::string off = dir.write("big.off", "OFF\n" + std::to_string(big) + " 1 0\n" + vertices(big, "") +
                                                   std::to_string(big) + face(big, "").substr(0));
  CHECK(meshsal_test::load_error(off).find("face with more than 65536 vertices") != std::string::npos);
  // Binary PLY with an int list count.
  std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(big) +
                    "\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
                    "property list int int vertex_indices\nend_header\n";
  for (size_t i = 0; i < big; ++i) {
    const float a = float(6.283185307179586 * double(i) / double(big));
    meshsal_test::put_bin(ply, std::cos(a));
    meshsal_test::put_bin(ply, std::sin(a));
    meshsal_test::put_bin(ply, 0.0f);
  }
  meshsal_test::put_bin(ply, int32_t(big));
  for (size_t i = 0; i < big; ++i) meshsal_test::put_bin(ply, int32_t(i));
  const std::string ply_path = dir.write("big.ply", ply);
  CHECK(meshsal_test::load_error(ply_path).find("face 0 has 70000 vertices (65536 is the most a polygon may have)") != std::string::npos);
  // 65536 corners: read, as 65534 triangles.
  const std::string ok = dir.write("ok.obj", vertices(65536, "v ") + face(65536, "f"));
  CHECK(meshsal::load_mesh(ok).triangle_count() == 65534);
}
