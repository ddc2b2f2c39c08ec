// meshsal (internal): what travels with a mesh besides its vertices and triangles, for the
// code that builds one mesh from another (simplification, tiles): the material names and
// files, a glTF input's materials and node frame, the local origin.
#pragma once
#include "meshsal/meshsal.h"

namespace meshsal {

inline void copy_mesh_context(const Mesh& from, Mesh& to) {
  to.material_libraries = from.material_libraries;
  to.material_library_text = from.material_library_text;
  to.material_library_folder = from.material_library_folder;
  to.materials = from.materials;
  to.gltf_assets = from.gltf_assets;
  to.frame = from.frame;
  for (int k = 0; k < 3; ++k) to.origin[k] = from.origin[k];
}

}  // namespace meshsal
