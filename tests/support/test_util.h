// Shared helpers for the tests: where the real meshes are, and skipping cleanly without them.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
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

// The shared meshes: MESHSAL_DATA_DIR from the environment when set (the Python tests read the
// same variable; pointing it elsewhere shows what a machine without ../shared does), else
// ../shared/data/meshes next to the source tree.
inline std::string data_dir() {
  const char* env = std::getenv("MESHSAL_DATA_DIR");
  return env && *env ? env : MESHSAL_DATA_DIR;
}

inline bool file_exists(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0;
}

// MESHSAL_REQUIRE_DATA=1 (set by .ci/run): a missing shared mesh fails the test instead of
// skipping it.
inline bool data_required() {
  const char* env = std::getenv("MESHSAL_REQUIRE_DATA");
  return env && *env && std::string(env) != "0";
}

// The shared meshes the running test case found missing; the listener in test_main.cpp prints
// "SKIPPED: missing shared data <path>" for each at the end of a case with no failures, and
// ctest (SKIP_REGULAR_EXPRESSION, CMakeLists.txt) reports such a case as skipped, not passed.
inline std::vector<std::string>& missing_data() {
  static std::vector<std::string> missing;
  return missing;
}

// Why the running test case (or a part of it) cannot run on this machine: a tool, a CPU
// feature, a device, root. The listener in test_main.cpp prints "SKIPPED: not run here:
// <reason>" at the end of a case with no failures, and ctest reports the case as skipped
// (SKIP_REGULAR_EXPRESSION, CMakeLists.txt), not passed. The caller returns, or leaves out
// the part that cannot run.
inline std::vector<std::string>& skip_reasons() {
  static std::vector<std::string> reasons;
  return reasons;
}
inline void skip_case(const std::string& reason) { skip_reasons().push_back(reason); }

// Path of a mesh in ../shared/data/meshes, or "" if it is absent: recorded as a skip, or a
// failure under MESHSAL_REQUIRE_DATA=1. The caller returns (MESHSAL_REQUIRE_MESH) or, in a
// loop over meshes, goes on to the next one (MESHSAL_MESH_OR_CONTINUE).
inline std::string shared_mesh(const std::string& name) {
  std::string path = data_dir() + "/" + name;
  if (file_exists(path)) return path;
  if (data_required())
    FAIL_CHECK("missing shared data " << path << " (MESHSAL_REQUIRE_DATA=1 makes this a failure)");
  else
    missing_data().push_back(path);
  return "";
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

// The mean of VALUES (of |VALUES| with `absolute`) over the vertices MASK marks (at least one).
inline double mean_over(const std::vector<double>& values, const std::vector<uint8_t>& mask, bool absolute = false) {
  double sum = 0;
  size_t count = 0;
  for (size_t v = 0; v < values.size(); ++v)
    if (mask[v]) {
      sum += absolute ? std::fabs(values[v]) : values[v];
      count++;
    }
  REQUIRE(count > 0);
  return sum / double(count);
}

// A sphere of radius R has the same curvature everywhere, so each of its five raw
// center-surround maps (the default scales) stays below 1% of |H| = 1/R.
inline void check_sphere_raw_maps(const meshsal::SaliencyResult& s, double r) {
  REQUIRE(s.raw.size() == 5);
  for (size_t i = 0; i < s.raw.size(); ++i) {
    const double worst = *std::max_element(s.raw[i].begin(), s.raw[i].end());
    INFO("scale " << i << ": max raw " << worst);
    CHECK(worst < 0.01 / r);
  }
}

// The (v, x) mesh-point pairs with |x - v| < radius, v itself included, counted one by one
// (quadratic: for small meshes). The exact sweep's FilterStats::pairs counts these for the
// largest cutoff, 2 max(sigma).
inline uint64_t pairs_within(const meshsal::Mesh& mesh, const std::vector<uint8_t>& is_point, double radius) {
  uint64_t n = 0;
  const double r2 = radius * radius;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    if (!is_point[v]) continue;
    for (size_t x = 0; x < mesh.vertex_count(); ++x) {
      if (!is_point[x]) continue;
      double d2 = 0;
      for (int a = 0; a < 3; ++a) {
        const double d = double(mesh.positions[3 * x + a]) - double(mesh.positions[3 * v + a]);
        d2 += d * d;
      }
      n += d2 < r2;
    }
  }
  return n;
}

// A GPU twin's saliency against the CPU path's on the same options: as many raw maps, S
// positive somewhere, and every raw map within `tol` (rel_error) of the CPU's, S and Sm
// within `s_tol` (default: tol).
inline void check_maps_match(const meshsal::SaliencyResult& cpu, const meshsal::SaliencyResult& gpu,
                             const std::vector<double>& scales, double tol, double s_tol = 0) {
  if (s_tol == 0) s_tol = tol;
  REQUIRE(gpu.raw.size() == cpu.raw.size());
  for (size_t i = 0; i < cpu.raw.size(); ++i) {
    INFO("raw map " << i << " (scale " << scales[i] << ")");
    CHECK(rel_error(cpu.raw[i], gpu.raw[i]) <= tol);
  }
  CHECK(*std::max_element(cpu.saliency.begin(), cpu.saliency.end()) > 0);
  CHECK(rel_error(cpu.saliency, gpu.saliency) <= s_tol);
  CHECK(rel_error(cpu.smoothed, gpu.smoothed) <= s_tol);
}

// Built with AddressSanitizer (tools/sanitize.sh): its shadow memory and quarantine
// multiply the resident memory, so peak-memory assertions hold only without it.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif

}  // namespace meshsal_test

// Skip the rest of the test case (Catch2 v2 has no SKIP) when a shared mesh is missing
// (a failure under MESHSAL_REQUIRE_DATA=1). Not for loops: it returns from the test case.
#define MESHSAL_REQUIRE_MESH(var, name)                    \
  const std::string var = meshsal_test::shared_mesh(name); \
  if (var.empty()) return

// In a loop over meshes: go on to the next mesh when this one is missing, so the present ones
// still run (the missing one is a skip, or a failure under MESHSAL_REQUIRE_DATA=1).
#define MESHSAL_MESH_OR_CONTINUE(var, name)                \
  const std::string var = meshsal_test::shared_mesh(name); \
  if (var.empty()) continue
