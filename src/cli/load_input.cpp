// meshsal CLI: load_input (see load_input.h).
#include "load_input.h"

#include <cstdio>

namespace meshsal_cli {

meshsal::Mesh load_input(const std::string& path, bool quiet, meshsal::VertexProperties* properties,
                         bool attributes) {
  meshsal::LoadReport report;
  meshsal::LoadOptions options;
  options.attributes = attributes;
  meshsal::Mesh mesh = meshsal::load_mesh(path, properties, options, &report);
  if (report.welded_corners && !quiet)
    std::fprintf(stderr, "note: %s: welded %llu STL corners into %zu shared vertices\n", path.c_str(),
                 static_cast<unsigned long long>(report.welded_corners), mesh.vertex_count());
  return mesh;
}

}  // namespace meshsal_cli
