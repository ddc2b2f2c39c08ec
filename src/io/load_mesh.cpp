// meshsal: load_mesh picks the parser from the file name (case-insensitive, .gz stripped),
// reads the bytes (gunzipping within a limit), parses, and validates.
#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <new>
#include <stdexcept>
#include <string>

#include "meshsal/meshsal.h"
#include "io/mesh_io_internal.h"
#include "io/read_bytes.h"
#include "io/read_observer.h"
#include "io/text_scan.h"

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

std::string check_extension(const std::string& name, bool& gz) {
  const std::string ext = lower_extension(name, gz);
  if (ext != ".obj" && ext != ".ply" && ext != ".off" && ext != ".stl" && ext != ".gltf" && ext != ".glb")
    throw Error(name + ": unknown mesh format" + (ext.empty() ? std::string() : " '" + ext + "'") +
                " (expected .obj, .ply, .off, .stl, .gltf or .glb, optionally gzipped as .gz)");
  return ext;
}

// `folder`: where a .gltf's external buffers and images are looked up ("" = none may be read).
// `raw_owner` (may be null): the block `raw` lies in, released once it is inflated (a gzip
// file's bytes are not kept beside the inflated ones while they are parsed).
Mesh parse(std::string_view raw, const std::string& name, const std::string& ext, bool gz_name,
           VertexProperties* properties, uint64_t limit, LoadReport* report, bool attributes,
           const std::string& folder, Bytes* raw_owner = nullptr, ReadObserver* observer = nullptr) {
  Bytes inflated;
  std::string_view bytes = raw;
  if (has_gzip_magic(raw)) {
    inflated = gunzip(raw, name, [&](std::string_view head) -> uint64_t {
      // The header is checked either way, so garbage fails before the rest is inflated.
      const uint64_t rule = ext == ".ply"   ? ply_input_limit(head, name)
                            : ext == ".off" ? off_input_limit(head, name)
                            : ext == ".stl" ? stl_input_limit(head, name)
                                            : kNoHeaderLimitBytes;
      return limit ? limit : rule;
    });
    bytes = inflated.view();
    if (raw_owner) raw_owner->release();
  } else if (gz_name) {
    throw Error(name + ": not a gzip file (the name ends in .gz but the data is not gzip)");
  }
  Mesh mesh;
  if (ext == ".obj") {
    mesh = load_obj_text(bytes, name, attributes, report ? &report->attributes_not_read : nullptr);
    if (!folder.empty() && !mesh.material_libraries.empty())
      read_material_libraries(mesh, folder, limit ? limit : kNoHeaderLimitBytes, report ? &report->unread : nullptr);
  }
  else if (ext == ".off") mesh = load_off_text(bytes, name, attributes, report ? &report->attributes_not_read : nullptr);
  else if (ext == ".stl") mesh = load_stl_bytes(bytes, name, report ? &report->welded_corners : nullptr);
  else if (ext == ".gltf" || ext == ".glb")
    mesh = load_gltf_bytes(bytes, name, ext == ".glb", folder, limit, attributes, report ? &report->unread : nullptr,
                           report ? &report->attributes_not_read : nullptr);
  else
    mesh = load_ply_bytes(bytes, name, properties, attributes, report ? &report->unread : nullptr,
                          report ? &report->attributes_not_read : nullptr, observer);
  return mesh;
}

// Runs `load` and gives every failure a one-line message that names the input.
// `observer` (may be null) is ended before the mesh is returned or dropped (read_observer.h).
template <typename Load>
Mesh load_named(const std::string& name, VertexProperties* properties, Load&& load, ReadObserver* observer = nullptr) {
  if (properties) properties->clear();
  Mesh mesh;
  const EndObserver end(observer);
  try {
    mesh = load();
    validate_mesh(mesh);
  } catch (const Error& e) {
    if (properties) properties->clear();
    const std::string what = e.what();
    if (what.compare(0, name.size() + 2, name + ": ") == 0) throw;
    throw Error(name + ": " + what);
  } catch (const std::bad_alloc&) {
    if (properties) properties->clear();
    throw Error(name + ": out of memory while loading");
  } catch (const std::length_error&) {
    if (properties) properties->clear();
    throw Error(name + ": out of memory while loading (a count too large to hold)");
  }
  return mesh;
}

}  // namespace

namespace {

Mesh load_file(const std::string& path, const LoadOptions& options, VertexProperties* properties,
               LoadReport* report, ReadObserver* observer = nullptr) {
  bool gz = false;
  const std::string ext = check_extension(path, gz);
  return load_named(path, properties, [&] {
    const uint64_t limit = options.max_input_bytes;  // 0: the default rules
    Bytes file = read_file(path, limit ? limit : kNoHeaderLimitBytes, options.regular_files_only);
    const size_t slash = path.find_last_of('/');
    const std::string folder = slash == std::string::npos ? "." : path.substr(0, slash + 1);
    return parse(file.view(), path, ext, gz, properties, limit, report, options.attributes, folder, &file, observer);
  }, observer);
}

Mesh load_bytes(std::string_view bytes, const std::string& name, const LoadOptions& options,
                VertexProperties* properties, LoadReport* report) {
  bool gz = false;
  const std::string ext = check_extension(name, gz);
  return load_named(name, properties, [&] {
    return parse(bytes, name, ext, gz, properties, options.max_input_bytes, report, options.attributes, "");
  });
}

}  // namespace

// load_mesh reads no properties: a PLY's scalars cost memory only read_mesh's callers want.
Mesh load_mesh(const std::string& path, const LoadOptions& options) {
  return load_file(path, options, nullptr, nullptr);
}

LoadedMesh read_mesh(const std::string& path, const LoadOptions& options) {
  return read_mesh_observed(path, options, nullptr);
}

LoadedMesh read_mesh_observed(const std::string& path, const LoadOptions& options, ReadObserver* observer) {
  LoadedMesh r;
  r.mesh = load_file(path, options, &r.properties, &r.report, observer);
  return r;
}

Mesh load_mesh_bytes(std::string_view bytes, const std::string& name, const LoadOptions& options) {
  return load_bytes(bytes, name, options, nullptr, nullptr);
}

LoadedMesh read_mesh_bytes(std::string_view bytes, const std::string& name, const LoadOptions& options) {
  LoadedMesh r;
  r.mesh = load_bytes(bytes, name, options, &r.properties, &r.report);
  return r;
}

}  // namespace meshsal
