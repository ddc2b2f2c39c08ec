// Helpers of the out-of-core tests (saliency_file, simplify_file): a file's bytes, CPU
// saliency options, a mesh at survey coordinates.
#pragma once
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli/synthetic.h"
#include "meshsal/meshsal.h"

namespace meshsal_test {

inline std::string file_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline meshsal::SaliencyOptions cpu(meshsal::Method method) {
  meshsal::SaliencyOptions o;
  o.backend = meshsal::Backend::Cpu;
  o.method = method;
  return o;
}

// A bumpy sphere far from the origin (survey coordinates), so the input stores doubles.
inline meshsal::Mesh far_sphere() {
  meshsal::Mesh m = meshsal::make_bumpy_sphere(4);
  std::vector<double> xyz = meshsal::model_positions(m);
  for (size_t i = 0; i < xyz.size(); i += 3) xyz[i] += 5e5, xyz[i + 1] += 4e6;
  meshsal::set_model_positions(m, xyz.data(), m.vertex_count());
  m.double_positions = true;
  return m;
}

}  // namespace meshsal_test
