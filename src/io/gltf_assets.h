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
  // The images, their `image` bytes empty: those are in image_bytes, each distinct source
  // once (images that share a bufferView share its bytes: a 2 MB file naming one view from
  // many images made 1 GB of copies). image_source[i] indexes image_bytes for image i; -1
  // where an external file was not read (its uri is kept).
  std::vector<tinygltf::Image> images;
  std::vector<std::vector<unsigned char>> image_bytes;
  std::vector<int> image_source;
  std::vector<tinygltf::Sampler> samplers;
  // The input's extensions other than those of geometry (KHR_materials_*, KHR_texture_*).
  std::vector<std::string> extensions_used, extensions_required;
  // Mesh::materials slot -> index into `materials` (-1: the primitive had none).
  std::vector<int> slot_material;
};

}  // namespace meshsal
