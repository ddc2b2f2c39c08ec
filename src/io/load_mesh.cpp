// meshsal: load_mesh picks the parser from the file name (case-insensitive, .gz stripped),
// reads the bytes (gunzipping), parses, and validates.
#include <algorithm>
#include <cctype>
#include <new>
#include <string>

#include "meshsal/meshsal.h"
#include "io/mesh_io_internal.h"
#include "io/read_bytes.h"

namespace meshsal {
namespace {

std::string lower_extension(const std::string& path, bool& gz) {
  size_t slash = path.find_last_of('/');
  std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
  std::transform(base.begin(), base.end(), base.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  gz = base.size() > 3 && base.compare(base.size() - 3, 3, ".gz") == 0;
  if (gz) base.resize(base.size() - 3);
  size_t dot = base.find_last_of('.');
  return dot == std::string::npos ? std::string() : base.substr(dot);
}

}  // namespace

Mesh load_mesh(const std::string& path, VertexProperties* properties) {
  bool gz = false;
  const std::string ext = lower_extension(path, gz);
  if (ext != ".obj" && ext != ".ply" && ext != ".off")
    throw Error(path + ": unknown mesh format" + (ext.empty() ? std::string() : " '" + ext + "'") +
                " (expected .obj, .ply or .off, optionally gzipped as .gz)");
  if (properties) properties->clear();
  Mesh mesh;
  try {
    const Bytes file = read_bytes(path);
    const std::string_view bytes = file.view();
    if (ext == ".obj") mesh = load_obj_text(bytes, path);
    else if (ext == ".off") mesh = load_off_text(bytes, path);
    else mesh = load_ply_bytes(bytes, path, properties);
  } catch (const std::bad_alloc&) {
    throw Error(path + ": out of memory while loading");
  }
  try {
    validate_mesh(mesh);
  } catch (const Error& e) {
    if (properties) properties->clear();
    throw Error(path + ": " + e.what());
  }
  return mesh;
}

}  // namespace meshsal
