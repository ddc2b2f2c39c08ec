// Shared helpers for the tests: where the real meshes are, and skipping cleanly without them.
#pragma once
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>
#include <sys/stat.h>

#include <catch2/catch.hpp>

#include "meshsal/meshsal.h"

namespace meshsal_test {

// A mesh's vertices in its own coordinates (meshsal::model_positions), rounded to float: what
// a file said, whatever origin loading chose for the local positions.
inline std::vector<float> world_floats(const meshsal::Mesh& mesh) {
  const std::vector<double> xyz = meshsal::model_positions(mesh);
  return std::vector<float>(xyz.begin(), xyz.end());
}

inline std::string data_dir() { return MESHSAL_DATA_DIR; }

inline bool file_exists(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0;
}

// Path of a mesh in ../shared/data/meshes, or "" (with a warning) if it is absent.
inline std::string shared_mesh(const std::string& name) {
  std::string path = data_dir() + "/" + name;
  if (!file_exists(path)) {
    WARN("skipped: " << path << " is absent (../shared/data/meshes not found)");
    return "";
  }
  return path;
}

// max_v |a - b| / max_v |a| (the error of b against the reference a, relative to a's
// largest value); max_v |a - b| when a is all zero.
inline double rel_error(const std::vector<double>& a, const std::vector<double>& b) {
  REQUIRE(a.size() == b.size());
  double mx = 0, err = 0;
  for (size_t v = 0; v < a.size(); ++v) {
    mx = std::max(mx, std::fabs(a[v]));
    err = std::max(err, std::fabs(a[v] - b[v]));
  }
  return mx > 0 ? err / mx : err;
}

// A GPU twin's saliency against the CPU path's on the same options: as many raw maps, S
// positive somewhere, and every raw map, S and Sm within `tol` (rel_error) of the CPU's.
inline void check_maps_match(const meshsal::SaliencyResult& cpu, const meshsal::SaliencyResult& gpu,
                             const std::vector<double>& scales, double tol) {
  REQUIRE(gpu.raw.size() == cpu.raw.size());
  for (size_t i = 0; i < cpu.raw.size(); ++i) {
    INFO("raw map " << i << " (scale " << scales[i] << ")");
    CHECK(rel_error(cpu.raw[i], gpu.raw[i]) <= tol);
  }
  CHECK(*std::max_element(cpu.saliency.begin(), cpu.saliency.end()) > 0);
  CHECK(rel_error(cpu.saliency, gpu.saliency) <= tol);
  CHECK(rel_error(cpu.smoothed, gpu.smoothed) <= tol);
}

}  // namespace meshsal_test

// Skip the rest of the test case (Catch2 v2 has no SKIP) when a shared mesh is missing.
#define MESHSAL_REQUIRE_MESH(var, name)               \
  const std::string var = meshsal_test::shared_mesh(name); \
  if (var.empty()) return
