// meshsal: the OFF writer: OFF, or COFF with a colour per vertex (r g b a, 0..255, as
// MeshLab and Geomview read them). Split twins share a vertex, as in the OBJ writer.
#include <algorithm>
#include <string>
#include <vector>

#include "core/model_frame.h"
#include "io/atomic_write.h"
#include "io/mesh_io_internal.h"
#include "io/text_writer.h"
#include "meshsal/meshsal.h"

namespace meshsal {

void write_off(const std::string& path, const Mesh& mesh, const std::vector<uint8_t>& rgb) {
  check_mesh(path, mesh);
  if (!rgb.empty() && rgb.size() != 3 * mesh.vertex_count())
    throw Error(path + ": cannot write: " + std::to_string(rgb.size()) + " colour bytes for " +
                std::to_string(mesh.vertex_count()) + " vertices (need 3 each)");
  const std::vector<uint64_t> line = welded_lines(path, mesh);  // 1-based; OFF counts from 0
  const bool welded = !line.empty();
  const size_t vertices = welded ? size_t(line.empty() ? 0 : *std::max_element(line.begin(), line.end())) : mesh.vertex_count();
  write_file_atomically(path, [&](std::FILE* f) {
    TextWriter out(f, path, positions_need_double(mesh));
    out << (rgb.empty() ? "OFF\n" : "COFF\n") << "# written by meshsal\n";
    out.number(vertices);
    out << ' ';
    out.number(mesh.triangle_count());
    out << " 0";
    out.end_line();
    for (size_t v = 0; v < mesh.vertex_count(); ++v) {
      if (welded && mesh.position_vertex[v] != v) continue;
      double xyz[3];
      model_position(mesh, v, xyz);
      for (int k = 0; k < 3; ++k) {
        if (k) out << ' ';
        out.coordinate(xyz[k]);
      }
      if (!rgb.empty()) {
        for (int k = 0; k < 3; ++k) {
          out << ' ';
          out.number(unsigned(rgb[3 * v + size_t(k)]));
        }
        out << " 255";
      }
      out.end_line();
    }
    for (size_t i = 0; i < mesh.triangles.size(); i += 3) {
      out << '3';
      for (size_t k = 0; k < 3; ++k) {
        out << ' ';
        const uint32_t v = mesh.triangles[i + k];
        out.number(welded ? line[v] - 1 : uint64_t(v));
      }
      out.end_line();
    }
    out.flush();
  });
}

}  // namespace meshsal
