// meshsal: an OBJ's materials as files: its .mtl libraries read from the model's folder
// (under the rule of io/model_reference.h), and the one .mtl an OBJ output gets beside it
// (OUT.mtl: the input's libraries, or a glTF input's materials in MTL terms with their
// images written as OUT_texN.EXT).
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "io/atomic_write.h"
#include "io/gltf_assets.h"
#include "io/mesh_io_internal.h"
#include "io/model_reference.h"
#include "io/text_scan.h"
#include "meshsal/meshsal.h"

namespace meshsal {
namespace {

// OUT for an output OUT.obj (any case of the suffix), else the path itself.
std::string stem_of(const std::string& path) {
  const std::string format = mesh_output_format(path);
  return format.empty() ? path : path.substr(0, path.size() - format.size());
}

std::string file_name(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string image_extension(const tinygltf::Image& image) {
  if (image.mimeType == "image/jpeg") return ".jpg";
  if (image.mimeType == "image/webp") return ".webp";
  if (image.mimeType == "image/ktx2") return ".ktx2";
  return ".png";
}

// The images of a glTF input's materials that the .mtl names (base colour, normal and
// emissive textures), by image index, with the bytes they have.
std::map<int, std::string> written_images(const std::string& obj_path, const GltfAssets& a) {
  std::map<int, std::string> out;
  auto use = [&](int texture) {
    if (texture < 0 || size_t(texture) >= a.textures.size()) return;
    const int image = a.textures[size_t(texture)].source;
    if (image < 0 || size_t(image) >= a.images.size()) return;
    if (size_t(image) >= a.image_source.size() || a.image_source[size_t(image)] < 0) return;
    out[image] = stem_of(obj_path) + "_tex" + std::to_string(image) + image_extension(a.images[size_t(image)]);
  };
  for (int m : a.slot_material) {
    if (m < 0 || size_t(m) >= a.materials.size()) continue;
    const tinygltf::Material& mat = a.materials[size_t(m)];
    use(mat.pbrMetallicRoughness.baseColorTexture.index);
    use(mat.normalTexture.index);
    use(mat.emissiveTexture.index);
  }
  return out;
}

// The lines of an .mtl's text, without their line ends and trailing blanks.
std::vector<std::string> trimmed_lines(const std::string& text) {
  std::vector<std::string> lines;
  size_t at = 0;
  while (at < text.size()) {
    size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(at, end - at);
    at = end + 1;
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t')) line.pop_back();
    lines.push_back(std::move(line));
  }
  return lines;
}

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

// A glTF input's materials in MTL terms: base colour and alpha (Kd, d), emissive (Ke), and
// their textures as the images written beside (map_Kd, norm, map_Ke); the rest of PBR has
// no MTL equivalent every reader shares.
std::string gltf_materials_as_mtl(const std::string& obj_path, const Mesh& mesh, const GltfAssets& a) {
  const std::map<int, std::string> images = written_images(obj_path, a);
  auto image_of = [&](int texture) -> std::string {
    if (texture < 0 || size_t(texture) >= a.textures.size()) return "";
    const auto it = images.find(a.textures[size_t(texture)].source);
    if (it != images.end()) return file_name(it->second);
    const int image = a.textures[size_t(texture)].source;
    // An external image that was not read keeps the name the input gave it.
    return image >= 0 && size_t(image) < a.images.size() ? a.images[size_t(image)].uri : "";
  };
  std::string out = "# written by meshsal from glTF materials\n";
  for (size_t slot = 0; slot < mesh.materials.size(); ++slot) {
    const int m = slot < a.slot_material.size() ? a.slot_material[slot] : -1;
    if (mesh.materials[slot].empty()) continue;
    out += "\nnewmtl " + mesh.materials[slot] + "\n";
    if (m < 0 || size_t(m) >= a.materials.size()) continue;
    const tinygltf::Material& mat = a.materials[size_t(m)];
    const std::vector<double>& c = mat.pbrMetallicRoughness.baseColorFactor;
    if (c.size() == 4) {
      out += "Kd " + number(c[0]) + " " + number(c[1]) + " " + number(c[2]) + "\n";
      if (c[3] < 1) out += "d " + number(c[3]) + "\n";
    }
    if (mat.emissiveFactor.size() == 3 && (mat.emissiveFactor[0] > 0 || mat.emissiveFactor[1] > 0 || mat.emissiveFactor[2] > 0))
      out += "Ke " + number(mat.emissiveFactor[0]) + " " + number(mat.emissiveFactor[1]) + " " + number(mat.emissiveFactor[2]) + "\n";
    if (const std::string t = image_of(mat.pbrMetallicRoughness.baseColorTexture.index); !t.empty()) out += "map_Kd " + t + "\n";
    if (const std::string t = image_of(mat.normalTexture.index); !t.empty()) out += "norm " + t + "\n";
    if (const std::string t = image_of(mat.emissiveTexture.index); !t.empty()) out += "map_Ke " + t + "\n";
  }
  return out;
}

// The input's libraries as read, then a plain entry for every used material they do not
// define (a library that could not be read, or none named), so that every usemtl resolves.
std::string obj_materials_as_mtl(const Mesh& mesh) {
  std::string out = "# written by meshsal from ";
  std::set<std::string> defined;
  for (size_t i = 0; i < mesh.material_libraries.size(); ++i) {
    out += (i ? ", " : "") + mesh.material_libraries[i];
    const std::string text = i < mesh.material_library_text.size() ? mesh.material_library_text[i] : "";
    for (const std::string& line : trimmed_lines(text)) {
      const size_t b = line.find_first_not_of(" \t");
      if (b != std::string::npos && line.compare(b, 7, "newmtl ") == 0) defined.insert(line.substr(b + 7));
    }
  }
  if (mesh.material_libraries.empty()) out += "the mesh's material names";
  out += "\n";
  for (size_t i = 0; i < mesh.material_library_text.size(); ++i) {
    out += "\n" + mesh.material_library_text[i];
    if (!out.empty() && out.back() != '\n') out += "\n";
  }
  for (const std::string& name : mesh.materials)
    if (!name.empty() && !defined.count(name)) out += "\nnewmtl " + name + "\n";
  return out;
}

// True when `path` is the same file as one the mesh was read with (a library beside an
// input OBJ that OUT.mtl would be named like): never written over.
bool is_source_library(const std::string& path, const Mesh& mesh, const std::string& folder) {
  if (folder.empty()) return false;
  struct stat out;
  if (::stat(path.c_str(), &out) != 0) return false;
  for (const std::string& lib : mesh.material_libraries) {
    struct stat in;
    if (::stat((folder + "/" + lib).c_str(), &in) == 0 && in.st_dev == out.st_dev && in.st_ino == out.st_ino) return true;
  }
  return false;
}

}  // namespace

void read_material_libraries(Mesh& mesh, const std::string& folder, uint64_t budget, std::vector<std::string>* unread) {
  mesh.material_library_text.assign(mesh.material_libraries.size(), "");
  mesh.material_library_folder = folder;
  for (size_t i = 0; i < mesh.material_libraries.size(); ++i) {
    try {
      const std::vector<unsigned char> bytes = read_model_reference(folder, mesh.material_libraries[i], false, budget);
      budget -= bytes.size();
      mesh.material_library_text[i].assign(bytes.begin(), bytes.end());
    } catch (const ReferenceRefused& e) {
      throw Error(std::string("material library ") + e.what());  // a model naming its way out: refused whole
    } catch (const Error& e) {
      if (unread) unread->push_back(std::string("material library ") + e.what());  // missing: noted
    }
  }
  // The textures a library names are carried into the output's .mtl: held to the same rule.
  for (size_t i = 0; i < mesh.material_libraries.size(); ++i) {
    Mesh one;
    one.material_library_text = {mesh.material_library_text[i]};
    for (const std::string& texture : library_textures(one))
      if (const std::string problem = reference_text_problem(texture, false); !problem.empty())
        throw Error("material library '" + mesh.material_libraries[i] + "': texture " + quoted(texture, 200) + ": " + problem);
  }
}

std::vector<std::string> library_textures(const Mesh& mesh) {
  std::vector<std::string> out;
  for (const std::string& text : mesh.material_library_text) {
    for (const std::string& line : trimmed_lines(text)) {
      const size_t b = line.find_first_not_of(" \t");
      if (b == std::string::npos) continue;
      const size_t e = line.find_first_of(" \t", b);
      const std::string key = line.substr(b, e == std::string::npos ? std::string::npos : e - b);
      const bool texture = key.rfind("map_", 0) == 0 || key == "bump" || key == "norm" || key == "disp" || key == "decal" || key == "refl";
      if (!texture || e == std::string::npos) continue;
      // The file name is the last word (options such as -s 1 1 1 come before it).
      const size_t last = line.find_last_of(" \t");
      const std::string name = line.substr(last + 1);
      if (!name.empty() && std::find(out.begin(), out.end(), name) == out.end()) out.push_back(name);
    }
  }
  return out;
}

std::vector<std::string> mesh_side_files(const std::string& path, const Mesh& mesh) {
  std::vector<std::string> out;
  if (mesh_output_format(path) != ".obj" || mesh.triangle_material.empty()) return out;
  out.push_back(stem_of(path) + ".mtl");
  if (mesh.gltf_assets)
    for (const auto& [image, name] : written_images(path, *mesh.gltf_assets)) out.push_back(name);
  return out;
}

std::string material_library_name(const std::string& obj_path) { return file_name(stem_of(obj_path) + ".mtl"); }

void write_material_files(const std::string& obj_path, const Mesh& mesh) {
  const std::vector<std::string> files = mesh_side_files(obj_path, mesh);
  if (files.empty()) return;
  for (const std::string& f : files)
    if (is_source_library(f, mesh, mesh.material_library_folder))
      throw Error(f + ": cannot write: it is a material library of the input (an output never replaces an input)");
  const std::string text = mesh.gltf_assets ? gltf_materials_as_mtl(obj_path, mesh, *mesh.gltf_assets) : obj_materials_as_mtl(mesh);
  write_file_atomically(files[0], [&](std::FILE* f) { write_all(f, text.data(), text.size(), files[0]); });
  if (!mesh.gltf_assets) return;
  const GltfAssets& a = *mesh.gltf_assets;
  for (const auto& written : written_images(obj_path, a)) {
    const std::string& name = written.second;
    const std::vector<unsigned char>& bytes = a.image_bytes[size_t(a.image_source[size_t(written.first)])];
    write_file_atomically(name, [&](std::FILE* f) { write_all(f, bytes.data(), bytes.size(), name); });
  }
}

}  // namespace meshsal
