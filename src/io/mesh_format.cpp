// meshsal: the one table of what an attribute name holds (attribute_role) and of what each
// format keeps (mesh_formats), and the one note of what a write loses (mesh_output_note).
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "io/mesh_io_internal.h"
#include "meshsal/meshsal.h"

namespace meshsal {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() > tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// "a", "a and b", "a, b and c".
std::string listed(const std::vector<std::string>& items) {
  std::string s;
  for (size_t i = 0; i < items.size(); ++i) s += (i == 0 ? "" : i + 1 == items.size() ? " and " : ", ") + items[i];
  return s;
}

// The suffixes of the formats that keep what `keeps` says, for "(.ply and .glb keep it)".
template <typename Keeps>
std::string formats_keeping(Keeps keeps) {
  std::vector<std::string> out;
  for (const MeshFormat& f : mesh_formats())
    if (keeps(f)) out.push_back(f.suffix);
  return listed(out);
}

// True when the file `path` lies in `folder` (both resolved as far as they exist).
bool same_folder(const std::string& path, const std::string& folder) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path a = fs::weakly_canonical(fs::absolute(fs::path(path), ec).parent_path(), ec);
  const fs::path b = fs::weakly_canonical(fs::absolute(fs::path(folder), ec), ec);
  return a == b;
}

}  // namespace

AttributeRole attribute_role(const std::string& name) {
  AttributeRole r;
  if (name == "nx" || name == "ny" || name == "nz") return {AttributeKind::Normal, 0, name[1] - 'x'};
  if (name == "red" || name == "green" || name == "blue" || name == "alpha")
    return {AttributeKind::Color, 0, name == "red" ? 0 : name == "green" ? 1 : name == "blue" ? 2 : 3};
  if (name == kSaliencyAttribute) return {AttributeKind::Saliency, 0, 0};
  if (name == "u" || name == "s" || name == "texture_u") return {AttributeKind::TexCoord, 0, 0};
  if (name == "v" || name == "t" || name == "texture_v") return {AttributeKind::TexCoord, 0, 1};
  if (name.size() == 2 && (name[0] == 'u' || name[0] == 'v') && name[1] >= '1' && name[1] <= '7')
    return {AttributeKind::TexCoord, name[1] - '0', name[0] == 'u' ? 0 : 1};
  return r;
}

const std::vector<MeshFormat>& mesh_formats() {
  static const std::vector<MeshFormat> formats = {
      // suffix, name, normals, UV sets, colours, scalars, materials, S
      {".ply", "PLY", true, 8, true, true, false, SaliencyKept::Value},
      {".gltf", "glTF", true, 8, true, true, true, SaliencyKept::Value},
      {".glb", "GLB", true, 8, true, true, true, SaliencyKept::Value},
      {".obj", "OBJ", true, 1, true, false, true, SaliencyKept::Colors},
      {".off", "OFF", false, 0, true, false, false, SaliencyKept::Colors},
      {".stl", "STL", false, 0, false, false, false, SaliencyKept::None},
  };
  return formats;
}

const MeshFormat* mesh_format(const std::string& path) {
  const std::string name = lower(path);
  for (const MeshFormat& f : mesh_formats())
    if (ends_with(name, f.suffix)) return &f;
  return nullptr;
}

std::string mesh_output_format(const std::string& path) {
  const MeshFormat* f = mesh_format(path);
  return f ? f->suffix : "";
}

std::string mesh_output_note(const std::string& path, const Mesh& mesh, bool saliency) {
  const MeshFormat* f = mesh_format(path);
  if (!f) throw Error(path + ": unknown mesh format (expected " + formats_keeping([](const MeshFormat&) { return true; }) + ")");
  std::vector<std::string> lost;
  std::set<std::string> seen;
  auto lose = [&](const std::string& what) {
    if (seen.insert(what).second) lost.push_back(what);
  };
  bool scalar_lost = false;
  for (const VertexAttribute& a : mesh.attributes) {
    const AttributeRole r = attribute_role(a.name);
    switch (r.kind) {
      case AttributeKind::Normal:
        if (!f->normals) lose("normals");
        break;
      case AttributeKind::TexCoord:
        if (r.set >= f->texcoord_sets) lose(f->texcoord_sets == 0 ? "texture coordinates" : "texture coordinates of set " + std::to_string(r.set));
        break;
      case AttributeKind::Color:
        if (!f->colors) lose("vertex colours");
        break;
      case AttributeKind::Saliency:
        if (!saliency) saliency = true;  // carried S: as S
        break;
      case AttributeKind::Scalar:
        if (!f->scalars) lose("the attribute '" + a.name + "'"), scalar_lost = true;
        break;
    }
  }
  if (!mesh.triangle_material.empty() && !f->materials) lose("materials");
  std::string note;
  if (saliency && f->saliency == SaliencyKept::Colors) note = "keeps S as vertex colours only";
  if (saliency && f->saliency == SaliencyKept::None) note = "keeps no saliency";
  if (!lost.empty()) {
    note += std::string(note.empty() ? "has" : ", and has") + " no place for " + listed(lost);
    note += scalar_lost ? " (" + formats_keeping([](const MeshFormat& g) { return g.scalars; }) + " keep every attribute)" : "";
  }
  // An OBJ's libraries go into OUT.mtl beside the output; the textures they name stay
  // where the input's folder has them.
  if (f->suffix == ".obj" && !mesh.triangle_material.empty() && !mesh.gltf_assets && !mesh.material_library_folder.empty()) {
    const std::vector<std::string> textures = library_textures(mesh);
    if (!textures.empty() && !same_folder(path, mesh.material_library_folder)) {
      const std::string copy = "names the input's textures " + listed(textures) +
                               " relative to the input's folder, as its materials do: copy them beside it";
      note = note.empty() ? copy : note + "; it " + copy;
    }
  }
  return note.empty() ? "" : path + " " + note;
}

}  // namespace meshsal
