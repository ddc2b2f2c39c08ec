// meshsal: Wavefront OBJ reader (v and f lines; everything else is ignored).
// A small dedicated parser instead of tinyobjloader: tinyobjloader turns an unparsable
// coordinate ("nan", "1,5") into 0 and silently drops faces with < 3 vertices, and it
// reads through iostreams. Here every problem is an Error naming the line.
#include <string>
#include <string_view>

#include "io/mesh_io_internal.h"
#include "io/text_scan.h"

namespace meshsal {

Mesh load_obj_text(std::string_view text, const std::string& name) {
  Mesh mesh;
  TextScan scan(text, name);
  scan.skip_bom();  // otherwise the first line's key would be "\xEF\xBB\xBFv" and be ignored
  std::string_view line;
  std::vector<uint32_t> poly;
  auto fail = [&](const std::string& problem) -> Error {
    return Error(name + ": line " + std::to_string(scan.line_no) + ": " + problem);
  };
  while (scan.next_line(line)) {
    line = strip_comment(line);
    const std::string_view key = next_token(line);
    if (key == "v") {
      const std::string problem = take_xyz(line, mesh.positions);
      if (!problem.empty()) throw fail(problem);
      // Optional w or r g b columns follow; they are not needed.
    } else if (key == "f") {
      poly.clear();
      const int64_t defined = static_cast<int64_t>(mesh.vertex_count());
      for (std::string_view tok = next_token(line); !tok.empty(); tok = next_token(line)) {
        int64_t idx;
        if (!parse_int_prefix(tok, idx)) throw fail("bad face index " + quoted(tok));
        if (idx == 0) throw fail("face index 0 (OBJ indices start at 1)");
        // Negative = relative to the vertices defined so far; positive ones are checked
        // against the final count by validate_mesh (forward references are legal).
        int64_t v = idx > 0 ? idx - 1 : defined + idx;
        if (v < 0) throw fail("face index " + std::to_string(idx) + " points before the first vertex");
        if (v > 0xFFFFFFFEll) throw fail("face index " + std::to_string(idx) + " is out of range");
        poly.push_back(static_cast<uint32_t>(v));
      }
      if (poly.size() < 3)
        throw fail("face with " + std::to_string(poly.size()) + " vertices (needs at least 3)");
      append_fan(mesh.triangles, poly.data(), poly.size());
    }
  }
  return mesh;
}

}  // namespace meshsal
