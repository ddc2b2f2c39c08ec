// meshsal CLI: loading an input mesh with the notes a user should see (STL welding).
#pragma once
#include <string>

#include "meshsal/meshsal.h"

namespace meshsal_cli {

// load_mesh, then, unless `quiet`, one note on stderr when STL corners were welded:
// "note: PATH: welded N STL corners into V shared vertices".
meshsal::Mesh load_input(const std::string& path, bool quiet,
                         meshsal::VertexProperties* properties = nullptr);

}  // namespace meshsal_cli
