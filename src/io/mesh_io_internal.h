// meshsal: the per-format parsers behind load_mesh. Each one parses bytes already in
// memory; `name` is only used to prefix error messages ("NAME: line 7: ...").
// They fan-triangulate polygons and reject faces with fewer than 3 vertices; the caller
// (load_mesh) runs validate_mesh on the result.
#pragma once
#include <string>
#include <string_view>

#include "meshsal/meshsal.h"

namespace meshsal {

Mesh load_obj_text(std::string_view text, const std::string& name);
Mesh load_off_text(std::string_view text, const std::string& name);
Mesh load_ply_bytes(std::string_view bytes, const std::string& name, VertexProperties* properties);

}  // namespace meshsal
