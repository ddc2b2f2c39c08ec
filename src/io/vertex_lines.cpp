// meshsal: one text line per position in the OBJ and OFF writers (welded_lines).
#include <string>
#include <vector>

#include "io/mesh_io_internal.h"

namespace meshsal {

std::vector<uint64_t> welded_lines(const std::string& path, const Mesh& mesh) {
  const std::vector<uint32_t>& pv = mesh.position_vertex;
  std::vector<uint64_t> line;
  if (pv.size() != mesh.vertex_count()) return line;
  line.resize(pv.size());
  uint64_t n = 0;
  for (size_t v = 0; v < pv.size(); ++v) line[v] = pv[v] == v ? ++n : 0;
  for (size_t v = 0; v < pv.size(); ++v)
    if (pv[v] != v) {
      if (pv[v] > v || pv[pv[v]] != pv[v]) throw Error(path + ": cannot write: a position_vertex is not below its vertex");
      line[v] = line[pv[v]];
    }
  return line;
}

}  // namespace meshsal
