// meshsal: write_mesh, the one place a file name picks the writer (every front end's -o).
#include <algorithm>
#include <cctype>
#include <string>

#include "meshsal/meshsal.h"

namespace meshsal {

std::string mesh_output_format(const std::string& path) {
  std::string lower = path;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  for (const char* ext : {".obj", ".ply", ".glb", ".gltf"}) {
    const std::string e = ext;
    if (lower.size() > e.size() && lower.compare(lower.size() - e.size(), e.size(), e) == 0) return e;
  }
  return "";
}

void write_mesh(const std::string& path, const Mesh& mesh, const std::vector<double>* saliency) {
  const std::string format = mesh_output_format(path);
  if (format == ".glb" || format == ".gltf") return write_gltf(path, mesh, saliency);
  if (format == ".ply") {
    if (saliency) return write_saliency_ply(path, mesh, *saliency);
    return write_ply(path, mesh, {});
  }
  if (format == ".obj") {
    if (saliency) throw Error(path + ": cannot write: OBJ has no place for per-vertex saliency (use .ply, .glb or .gltf)");
    return write_obj(path, mesh);
  }
  throw Error(path + ": cannot write: unknown mesh format (expected .obj, .ply, .glb or .gltf)");
}

}  // namespace meshsal
