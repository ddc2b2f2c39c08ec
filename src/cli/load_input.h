// meshsal CLI: loading an input mesh with the notes a user should see (STL welding).
#pragma once
#include <string>

#include "meshsal/meshsal.h"

namespace meshsal_cli {

// load_mesh, then, unless `quiet`, one note on stderr when STL corners were welded:
// "note: PATH: welded N STL corners into V shared vertices".
// `attributes`: LoadOptions::attributes (OBJ vt/vn, PLY properties into Mesh::attributes).
meshsal::Mesh load_input(const std::string& path, bool quiet,
                         meshsal::VertexProperties* properties = nullptr, bool attributes = false);

}  // namespace meshsal_cli
