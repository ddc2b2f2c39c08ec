// meshsal: write_mesh, the one place a file name picks the writer (every front end's -o).
#include <string>
#include <vector>

#include "io/mesh_io_internal.h"
#include "meshsal/meshsal.h"

namespace meshsal {

void write_mesh(const std::string& path, const Mesh& mesh, const std::vector<double>& values) {
  const std::vector<double>* saliency = values.empty() ? nullptr : &values;
  const std::string format = mesh_output_format(path);
  if (format == ".glb" || format == ".gltf") return write_gltf(path, mesh, values);
  if (format == ".ply") {
    if (saliency) return write_saliency_ply(path, mesh, *saliency);
    return write_ply(path, mesh, {});
  }
  if (format == ".obj") return write_obj_colours(path, mesh, written_colours(path, mesh, saliency));
  if (format == ".off") return write_off(path, mesh, written_colours(path, mesh, saliency));
  if (format == ".stl") {
    if (saliency)
      throw Error(path + ": cannot write: STL has no place for saliency (.ply, .gltf and .glb keep its values; "
                         ".obj and .off its colours)");
    return write_stl(path, mesh);
  }
  throw Error(path + ": cannot write: unknown mesh format (expected .ply, .gltf, .glb, .obj, .off or .stl)");
}

}  // namespace meshsal
