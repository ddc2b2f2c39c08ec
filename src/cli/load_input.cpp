// meshsal CLI: load_input (see load_input.h).
#include "load_input.h"

#include <cctype>
#include <cstdio>

namespace meshsal_cli {

bool is_ply_path(std::string path) {
  for (char& c : path) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (path.size() > 3 && path.compare(path.size() - 3, 3, ".gz") == 0) path.resize(path.size() - 3);
  return path.size() > 4 && path.compare(path.size() - 4, 4, ".ply") == 0;
}

meshsal::Mesh load_input_mesh(const std::string& path, meshsal::VertexProperties* properties,
                              bool attributes, meshsal::LoadReport* report) {
  meshsal::LoadOptions options;
  options.attributes = attributes || is_ply_path(path);
  meshsal::Mesh mesh = meshsal::load_mesh(path, properties, options, report);
  if (!attributes) mesh.attributes.clear();
  return mesh;
}

meshsal::Mesh load_input(const std::string& path, bool quiet, meshsal::VertexProperties* properties,
                         bool attributes) {
  meshsal::LoadReport report;
  meshsal::Mesh mesh = load_input_mesh(path, properties, attributes, &report);
  if (report.welded_corners && !quiet)
    std::fprintf(stderr, "note: %s: welded %llu STL corners into %zu shared vertices\n", path.c_str(),
                 static_cast<unsigned long long>(report.welded_corners), mesh.vertex_count());
  return mesh;
}

}  // namespace meshsal_cli
