// bench_saliency_call: the wall time of one meshsal::compute_saliency call from C++ (CPU
// path, default options), the baseline tools/bench_python.py holds the Python call to.
//
//   bench_saliency_call MESH [REPEAT]     prints {"wall_s": [...], "stages_s": [...]}
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "meshsal/meshsal.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_saliency_call MESH [REPEAT]\n");
    return 2;
  }
  const int repeat = argc > 2 ? std::atoi(argv[2]) : 1;
  if (repeat < 1 || repeat > 1000) {
    std::fprintf(stderr, "error: REPEAT must be in [1, 1000]\n");
    return 2;
  }
  try {
    const meshsal::Mesh mesh = meshsal::load_mesh(argv[1]);
    meshsal::SaliencyOptions options;  // backend Cpu, the library's defaults
    std::vector<double> wall, stages;
    for (int i = 0; i < repeat; ++i) {
      const auto t0 = std::chrono::steady_clock::now();
      const meshsal::SaliencyResult r = meshsal::compute_saliency(mesh, options);
      wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      double s = 0;
      for (const meshsal::StageTime& st : r.stages) s += st.seconds;
      stages.push_back(s);
    }
    auto list = [](const std::vector<double>& v) {
      std::string out = "[";
      for (size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + std::to_string(v[i]);
      return out + "]";
    };
    std::printf("{\"wall_s\": %s, \"stages_s\": %s}\n", list(wall).c_str(), list(stages).c_str());
  } catch (const meshsal::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
