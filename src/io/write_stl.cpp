// meshsal: the STL writer: binary STL (an 80-byte header, the triangle count, then per
// triangle its unit normal, its three corners and a zero attribute word), positions in the
// model's coordinates rounded to float, the only numbers STL has.
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "core/model_frame.h"
#include "io/atomic_write.h"
#include "io/mesh_io_internal.h"
#include "meshsal/meshsal.h"

namespace meshsal {

void write_stl(const std::string& path, const Mesh& mesh) {
  check_mesh(path, mesh);
  if (mesh.triangle_count() > UINT32_MAX) throw Error(path + ": cannot write: STL holds at most 2^32 - 1 triangles");
  write_file_atomically(path, [&](std::FILE* f) {
    char header[80] = {};
    std::memcpy(header, "binary STL written by meshsal", 29);  // never "solid": that starts an ASCII STL
    write_all(f, header, sizeof header, path);
    const uint32_t count = uint32_t(mesh.triangle_count());
    write_all(f, &count, 4, path);
    std::vector<char> block;
    block.reserve(50 << 14);
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
      double p[3][3];
      for (int k = 0; k < 3; ++k) model_position(mesh, mesh.triangles[3 * t + size_t(k)], p[k]);
      const double u[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
      const double w[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
      double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
      const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      for (double& x : n) x = len > 0 ? x / len : 0.0;
      float record[12];
      for (int k = 0; k < 3; ++k) record[k] = float(n[k]);
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k) record[3 + 3 * c + k] = float(p[c][k]);
      const char* bytes = reinterpret_cast<const char*>(record);
      block.insert(block.end(), bytes, bytes + 48);
      block.push_back(0), block.push_back(0);
      if (block.size() >= (50u << 14)) write_all(f, block.data(), block.size(), path), block.clear();
    }
    write_all(f, block.data(), block.size(), path);
  });
}

}  // namespace meshsal
