// Shared by the batch tests: a scratch folder of small synthetic meshes plus one broken
// file, running `meshsal batch`, and reading its JSON Lines log.
#pragma once
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli/synthetic.h"
#include "meshsal/meshsal.h"
#include "test_io_util.h"

namespace meshsal_test {

namespace fs = std::filesystem;

struct BatchRun {
  int exit_code;  // -1 when killed by a signal
  std::string out, err;
};

inline std::string read_text(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

inline fs::path batch_scratch(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("meshsal_batch_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  remove_at_exit(d);
  return d;
}

// `meshsal ARGS` with stdout and stderr captured (stdin from /dev/null).
inline BatchRun run_meshsal(const std::string& args, const fs::path& dir) {
  const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  const std::string cmd = std::string(MESHSAL_CLI) + " " + args + " > " + out.string() + " 2> " +
                          err.string() + " < /dev/null";
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_text(out), read_text(err)};
}

// DIR/in: ball.obj (sphere), bumpy.ply (bumpy sphere), cube.off, and broken.obj (junk).
inline fs::path make_batch_inputs(const fs::path& dir) {
  const fs::path in = dir / "in";
  fs::create_directories(in);
  meshsal::write_obj((in / "ball.obj").string(), meshsal::make_sphere(1.0, 2));
  meshsal::write_ply((in / "bumpy.ply").string(), meshsal::make_bumpy_sphere(2), {});
  const meshsal::Mesh cube = meshsal::make_cube(4);
  std::ofstream off(in / "cube.off");
  off << "OFF\n" << cube.vertex_count() << " " << cube.triangle_count() << " 0\n";
  for (size_t v = 0; v < cube.vertex_count(); ++v)
    off << cube.positions[3 * v] << " " << cube.positions[3 * v + 1] << " " << cube.positions[3 * v + 2] << "\n";
  for (size_t t = 0; t < cube.triangle_count(); ++t)
    off << "3 " << cube.triangles[3 * t] << " " << cube.triangles[3 * t + 1] << " " << cube.triangles[3 * t + 2] << "\n";
  off.close();
  std::ofstream(in / "broken.obj") << "v 0 0 0\nv 1 0 0\nf 1 2 7\n";  // index out of range
  return in;
}

inline std::vector<std::string> log_lines(const fs::path& log) {
  std::vector<std::string> lines;
  std::istringstream ss(read_text(log));
  std::string line;
  while (std::getline(ss, line)) lines.push_back(line);
  return lines;
}

// The text value of "KEY": "..." (the first occurrence, no escapes), or "".
inline std::string json_text(const std::string& json, const std::string& key) {
  const std::string k = "\"" + key + "\": \"";
  const size_t at = json.find(k);
  if (at == std::string::npos) return "";
  const size_t end = json.find('"', at + k.size());
  return json.substr(at + k.size(), end - at - k.size());
}

// Modification time in nanoseconds.
inline long long mtime_ns(const fs::path& p) {
  struct stat st;
  if (::stat(p.c_str(), &st) != 0) return -1;
  return (long long)st.st_mtim.tv_sec * 1000000000LL + st.st_mtim.tv_nsec;
}

}  // namespace meshsal_test
