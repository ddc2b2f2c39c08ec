// meshsal (internal): what a glTF input carries besides its geometry (Mesh::gltf_assets):
// its materials with their textures, images and samplers, which write_gltf writes back
// unchanged (images as the bytes read, embedded in the output's buffer).
#pragma once
#include <tiny_gltf.h>

#include <string>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {

struct GltfAssets {
  std::vector<tinygltf::Material> materials;
  std::vector<tinygltf::Texture> textures;
  std::vector<tinygltf::Image> images;  // bytes in image (as_is); uri kept only where unread
  std::vector<tinygltf::Sampler> samplers;
  // The input's extensions other than those of geometry (KHR_materials_*, KHR_texture_*).
  std::vector<std::string> extensions_used, extensions_required;
  // Mesh::materials slot -> index into `materials` (-1: the primitive had none).
  std::vector<int> slot_material;
};

}  // namespace meshsal
