// Helpers for the [io] tests: a private temporary folder and small file writers.
#pragma once
#include <zlib.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>
#include <unistd.h>

#include <catch2/catch.hpp>

#include "meshsal/meshsal.h"

namespace meshsal_test {

// Removes `dir` when this test process exits (ctest runs each case in a process of its own),
// so a suite run leaves nothing in /tmp; MESHSAL_KEEP_SCRATCH=1 keeps them for a post-mortem.
// Only the process that asked removes it: a forked child that exits leaves it alone.
inline void remove_at_exit(const std::filesystem::path& dir) {
  struct Sweeper {
    std::vector<std::filesystem::path> dirs;
    pid_t owner = ::getpid();
    ~Sweeper() {
      const char* keep = std::getenv("MESHSAL_KEEP_SCRATCH");
      if (::getpid() != owner || (keep && *keep && std::string(keep) != "0")) return;
      for (const auto& d : dirs) {
        std::error_code ec;
        std::filesystem::permissions(d, std::filesystem::perms::owner_all,
                                     std::filesystem::perm_options::add, ec);
        std::filesystem::remove_all(d, ec);
      }
    }
  };
  static Sweeper sweeper;
  sweeper.dirs.push_back(dir);
}

// A fresh folder under the system temp dir, removed with everything in it at scope exit.
struct TempDir {
  std::filesystem::path path;
  TempDir() {
    static std::atomic<int> counter{0};
    auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
    path = std::filesystem::temp_directory_path() /
           ("meshsal_io_" + std::to_string(::getpid()) + "_" + std::to_string(stamp) + "_" +
            std::to_string(counter++));
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::permissions(path, std::filesystem::perms::owner_all,
                                 std::filesystem::perm_options::add, ec);
    std::filesystem::remove_all(path, ec);
  }
  std::string file(const std::string& name) const { return (path / name).string(); }

  // Writes `bytes` to NAME in this folder and returns the full path.
  std::string write(const std::string& name, const std::string& bytes) const {
    std::string p = file(name);
    std::ofstream out(p, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return p;
  }

  // Writes `bytes` gzip-compressed.
  std::string write_gz(const std::string& name, const std::string& bytes) const {
    std::string p = file(name);
    gzFile gz = gzopen(p.c_str(), "wb");
    gzwrite(gz, bytes.data(), static_cast<unsigned>(bytes.size()));
    gzclose(gz);
    return p;
  }

  size_t entries() const {
    size_t n = 0;
    for (auto it = std::filesystem::directory_iterator(path); it != std::filesystem::directory_iterator(); ++it) ++n;
    return n;
  }
};

inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The message load_mesh throws for PATH, or "" when it loads fine.
// The message of the meshsal::Error that f throws, or "" when it throws none.
inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const meshsal::Error& e) {
    return e.what();
  }
  return "";
}

inline std::string load_error(const std::string& path) {
  try {
    meshsal::load_mesh(path);
  } catch (const meshsal::Error& e) {
    return e.what();
  }
  return "";
}

// Loads PATH expecting a meshsal::Error whose message is one line that starts with the file
// ("PATH: ...") and says `problem`.
inline void expect_error(const std::string& path, const std::string& problem) {
  INFO("file: " << path);
  const std::string msg = load_error(path);
  INFO("message: " << msg);
  REQUIRE(!msg.empty());
  CHECK(msg.find('\n') == std::string::npos);
  CHECK(msg.rfind(path + ": ", 0) == 0);
  CHECK(msg.find(problem) != std::string::npos);
}

// A file to write and the problem its loading must report (expect_errors).
struct BadFile {
  std::string name, bytes, problem;
};

// Writes each file into DIR and expects its load to fail as expect_error says.
inline void expect_errors(const TempDir& dir, const std::vector<BadFile>& files) {
  for (const BadFile& f : files) expect_error(dir.write(f.name, f.bytes), f.problem);
}

// Binary PLY body helpers: append raw values in the given byte order.
template <typename T>
void put_bin(std::string& s, T v, bool big_endian = false) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big_endian)
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  s.append(b, sizeof(T));
}

}  // namespace meshsal_test
