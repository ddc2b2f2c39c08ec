// meshsal: writing a chain of levels of detail (write_lod in meshsal.h): one glTF with the
// levels linked by MSFT_lod, or one OBJ/PLY file per level.
#include <string>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {

std::string lod_level_path(const std::string& path, size_t level) {
  const std::string format = mesh_output_format(path);
  const std::string stem = path.substr(0, path.size() - format.size());
  return stem + "_lod" + std::to_string(level) + path.substr(path.size() - format.size());
}

void write_lod(const std::string& path, const Mesh& mesh, const std::vector<double>& saliency,
               const std::vector<LodLevel>& levels) {
  const std::string format = mesh_output_format(path);
  if (format == ".glb" || format == ".gltf") {
    std::vector<GltfLevel> gl(levels.size() + 1);
    gl[0].mesh = &mesh;
    gl[0].saliency = saliency.empty() ? nullptr : &saliency;
    gl[0].name = "LOD0";
    for (size_t i = 0; i < levels.size(); ++i) {
      gl[i + 1].mesh = &levels[i].mesh;
      gl[i + 1].saliency = levels[i].saliency.empty() ? nullptr : &levels[i].saliency;
      gl[i + 1].name = "LOD" + std::to_string(i + 1);
    }
    return write_gltf(path, gl);
  }
  for (size_t i = 0; i < levels.size(); ++i) {
    const std::string file = lod_level_path(path, i + 1);
    if (format == ".ply" && !levels[i].saliency.empty()) {
      // The saliency as `quality`, as `meshsal simplify` writes it to a PLY.
      Mesh m = levels[i].mesh;
      set_vertex_attribute(m, "quality", levels[i].saliency);
      write_mesh(file, m);
    } else {
      write_mesh(file, levels[i].mesh);
    }
  }
}

}  // namespace meshsal
