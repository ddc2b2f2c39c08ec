// meshsal: Wavefront OBJ reader (v, f, mtllib and usemtl lines; with LoadOptions::attributes
// also vt, vn and the v/vt/vn corners of faces; everything else is ignored).
// A small dedicated parser instead of tinyobjloader: tinyobjloader turns an unparsable
// coordinate ("nan", "1,5") into 0 and silently drops faces with < 3 vertices, and it
// reads through iostreams. Here every problem is an Error naming the line.
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include "io/mesh_io_internal.h"
#include "io/model_reference.h"
#include "io/text_scan.h"

namespace meshsal {
namespace {

constexpr uint32_t kNone = UINT32_MAX;  // a corner without vt or vn

// One face corner's v, vt and vn (0-based; kNone when absent).
struct Corner {
  uint32_t v, vt, vn;
};

// "v", "v/vt", "v//vn" or "v/vt/vn"; negative indices count back from the entries defined
// so far. Returns a problem, or "" when fine.
std::string parse_corner(std::string_view tok, const int64_t defined[3], Corner& out) {
  const std::string_view whole = tok;
  uint32_t idx[3] = {kNone, kNone, kNone};
  static const char* what[3] = {"face index", "texture coordinate index", "normal index"};
  for (int part = 0; part < 3; ++part) {
    const size_t slash = tok.find('/');
    const std::string_view field = tok.substr(0, slash);
    if (!field.empty() || part == 0) {
      int64_t i;
      auto r = std::from_chars(field.data() + (!field.empty() && field[0] == '+'),
                               field.data() + field.size(), i);
      if (field.empty() || r.ec != std::errc() || r.ptr != field.data() + field.size())
        return "bad " + std::string(what[part]) + " " + quoted(whole);
      if (i == 0) return std::string(what[part]) + " 0 (OBJ indices start at 1)";
      // Negative = relative to the entries defined so far; positive ones are checked
      // against the final count at the end (forward references are legal).
      const int64_t v = i > 0 ? i - 1 : defined[part] + i;
      if (v < 0) return std::string(what[part]) + " " + std::to_string(i) + " points before the first entry";
      if (v > 0xFFFFFFFEll) return std::string(what[part]) + " " + std::to_string(i) + " is out of range";
      idx[part] = uint32_t(v);
    }
    if (slash == std::string_view::npos) break;
    tok.remove_prefix(slash + 1);
    if (part == 2) return "bad face corner (more than v/vt/vn)";
  }
  out = {idx[0], idx[1], idx[2]};
  return "";
}

// Takes n floats (at least `need`, at most n) from the line into out (missing ones 0).
std::string take_floats(std::string_view& line, int need, int n, std::vector<float>& out) {
  for (int k = 0; k < n; ++k) {
    std::string_view tok = next_token(line);
    float x = 0;
    if (tok.empty()) {
      if (k < need) return "needs " + std::to_string(need) + " numbers";
    } else if (!parse_coord(tok, x) || !std::isfinite(x)) {
      return "bad number " + quoted(tok);
    }
    out.push_back(x);
  }
  return "";
}

// One vertex per distinct (v, vt, vn) corner: a v's first combination keeps index v, the
// others become twins appended after the file's vertices (position_vertex = v).
void split_corners(Mesh& mesh, const std::vector<Corner>& corners, const std::vector<float>& texcoords,
                   const std::vector<float>& normals, bool any_vt, bool any_vn, const std::string& name) {
  const size_t nv = mesh.source_positions.size() / 3, nvt = texcoords.size() / 2, nvn = normals.size() / 3;
  for (size_t i = 0; i < corners.size(); ++i) {
    const Corner& c = corners[i];
    if (c.vt != kNone && c.vt >= nvt)
      throw Error(name + ": a face uses texture coordinate " + std::to_string(uint64_t(c.vt) + 1) +
                  " but the file has " + std::to_string(nvt));
    if (c.vn != kNone && c.vn >= nvn)
      throw Error(name + ": a face uses normal " + std::to_string(uint64_t(c.vn) + 1) + " but the file has " +
                  std::to_string(nvn));
  }
  std::vector<uint32_t> first_vt(nv, kNone), first_vn(nv, kNone);
  std::vector<uint8_t> used(nv, 0);
  std::map<std::tuple<uint32_t, uint32_t, uint32_t>, uint32_t> twins;
  std::vector<uint32_t> pv;
  std::vector<Corner> source;  // which vt/vn each vertex takes
  source.reserve(nv);
  for (size_t v = 0; v < nv; ++v) source.push_back({uint32_t(v), kNone, kNone});
  for (size_t i = 0; i < corners.size(); ++i) {
    const Corner& c = corners[i];
    if (c.v >= nv) continue;  // validate_mesh names it
    if (!used[c.v]) {
      used[c.v] = 1;
      source[c.v] = c;
      mesh.triangles[i] = c.v;
      continue;
    }
    if (source[c.v].vt == c.vt && source[c.v].vn == c.vn) {
      mesh.triangles[i] = c.v;
      continue;
    }
    auto [it, fresh] = twins.try_emplace({c.v, c.vt, c.vn}, uint32_t(source.size()));
    if (fresh) {
      if (source.size() >= 0xFFFFFFFEu) throw Error(name + ": too many split vertices");
      source.push_back(c);
      for (int k = 0; k < 3; ++k) mesh.source_positions.push_back(mesh.source_positions[3 * size_t(c.v) + k]);
    }
    mesh.triangles[i] = it->second;
  }
  const size_t n = source.size();
  if (n > nv) {
    mesh.position_vertex.resize(n);
    for (size_t v = 0; v < n; ++v) mesh.position_vertex[v] = source[v].v;
  }
  if (any_vt) {
    VertexAttribute u{"u", std::vector<float>(n, 0.f)}, w{"v", std::vector<float>(n, 0.f)};
    for (size_t v = 0; v < n; ++v)
      if (source[v].vt != kNone) {
        u.values[v] = texcoords[2 * size_t(source[v].vt)];
        w.values[v] = texcoords[2 * size_t(source[v].vt) + 1];
      }
    mesh.attributes.push_back(std::move(u));
    mesh.attributes.push_back(std::move(w));
  }
  if (any_vn) {
    static const char* names[3] = {"nx", "ny", "nz"};
    for (int k = 0; k < 3; ++k) {
      VertexAttribute a{names[k], std::vector<float>(n, 0.f)};
      for (size_t v = 0; v < n; ++v)
        if (source[v].vn != kNone) a.values[v] = normals[3 * size_t(source[v].vn) + k];
      mesh.attributes.push_back(std::move(a));
    }
  }
}

// Vertex colours of the v lines (r g b in [0, 1], or 0..255 when any is above 1) as the
// red green blue attributes, in bytes; twins take their v's, a v without colour is white.
void add_vertex_colours(Mesh& mesh, std::vector<float> colours) {
  const size_t n = mesh.source_positions.size() / 3;
  const bool bytes = *std::max_element(colours.begin(), colours.end()) > 1.0f;
  static const char* names[3] = {"red", "green", "blue"};
  for (int k = 0; k < 3; ++k) {
    VertexAttribute a{names[k], std::vector<float>(n, 255.0f)};
    for (size_t v = 0; v < n; ++v) {
      const size_t line = mesh.position_vertex.empty() ? v : mesh.position_vertex[v];
      const float x = 3 * line + size_t(k) < colours.size() ? colours[3 * line + size_t(k)] : -1.0f;
      if (x >= 0) a.values[v] = float(std::clamp(std::nearbyint(bytes ? double(x) : x * 255.0), 0.0, 255.0));
    }
    mesh.attributes.push_back(std::move(a));
  }
}

}  // namespace

Mesh load_obj_text(std::string_view text, const std::string& name, bool attributes, std::vector<std::string>* not_read) {
  Mesh mesh;
  TextScan scan(text, name);
  scan.skip_bom();  // otherwise the first line's key would be "\xEF\xBB\xBFv" and be ignored
  std::string_view line;
  std::vector<uint32_t> poly;
  std::vector<Corner> face, corners;  // with attributes: this face's, and every triangle's
  std::vector<float> texcoords, normals;
  std::vector<float> colours;  // r g b per v line up to the last one with colours (-1: none)
  bool seen_vt = false, seen_vn = false, seen_colours = false;  // without attributes: noted once
  bool any_vt = false, any_vn = false;
  // Face indices beyond the vertices defined so far (forward references, legal) and their
  // lines: checked against the final count at the end, named as the file writes them.
  std::vector<std::pair<uint32_t, size_t>> forward;
  // The current usemtl's index into mesh.materials (kNone before the first), one per
  // triangle as the faces are read.
  uint32_t material = kNone;
  std::map<std::string, uint32_t, std::less<>> material_index;
  auto fail = [&](const std::string& problem) -> Error {
    return Error(name + ": line " + std::to_string(scan.line_no) + ": " + problem);
  };
  while (scan.next_line(line)) {
    line = strip_comment(line);
    const std::string_view key = next_token(line);
    if (key == "mtllib") {
      // Carried into outputs (and read once materials are), so held to the rule of every
      // file a model names: in its folder or below (io/model_reference.h).
      for (std::string_view tok = next_token(line); !tok.empty(); tok = next_token(line)) {
        if (const std::string problem = reference_text_problem(std::string(tok), /*uri=*/false); !problem.empty())
          throw fail("mtllib " + quoted(tok, 200) + ": " + problem);
        mesh.material_libraries.emplace_back(tok);
      }
    } else if (key == "usemtl") {
      // The name is the rest of the line (without surrounding blanks): "usemtl" alone is "".
      while (!line.empty() && is_space(line.front())) line.remove_prefix(1);
      while (!line.empty() && is_space(line.back())) line.remove_suffix(1);
      auto [it, fresh] = material_index.try_emplace(std::string(line), uint32_t(mesh.materials.size()));
      if (fresh) {
        // The faces so far have no material; from here on every triangle gets one entry.
        if (mesh.materials.empty()) mesh.triangle_material.assign(mesh.triangles.size() / 3, kNone);
        mesh.materials.emplace_back(line);
      }
      material = it->second;
    } else if (key == "v") {
      const std::string problem = take_xyz(line, mesh.source_positions);
      if (!problem.empty()) throw fail(problem);
      // Named here, as the file numbers its vertices (from 1), not by validate_mesh.
      for (size_t k = mesh.source_positions.size() - 3; k < mesh.source_positions.size(); ++k)
        if (!std::isfinite(mesh.source_positions[k]))
          throw fail("vertex " + std::to_string(mesh.source_positions.size() / 3) + " has a non-finite coordinate (" +
                     std::to_string(mesh.source_positions[k]) + ")");
      // Optional columns follow: w, or r g b (MeshLab's vertex colours, kept with attributes).
      if (!attributes && !seen_colours && not_read) {
        int more = 0;
        for (std::string_view tok = next_token(line); !tok.empty() && more < 4; tok = next_token(line)) ++more;
        if (more == 3) note_not_read(not_read, "red"), seen_colours = true;
      } else if (attributes) {
        float rgb[3];
        int got = 0;
        for (std::string_view tok = next_token(line); !tok.empty() && got < 4; tok = next_token(line), ++got)
          if (got < 3 && (!parse_coord(tok, rgb[got]) || !std::isfinite(rgb[got]))) got = 4;
        if (got == 3) {
          colours.resize(mesh.source_positions.size() - 3, -1.0f);
          colours.insert(colours.end(), rgb, rgb + 3);
        }
      }
    } else if (!attributes && (key == "vt" || key == "vn")) {
      // Not read: said once (LoadReport::attributes_not_read).
      if (key == "vt" && !seen_vt) note_not_read(not_read, "u"), seen_vt = true;
      if (key == "vn" && !seen_vn) note_not_read(not_read, "nx"), seen_vn = true;
    } else if (attributes && key == "vt") {
      const std::string problem = take_floats(line, 1, 2, texcoords);  // u [v [w]]
      if (!problem.empty()) throw fail("texture coordinate " + problem);
    } else if (attributes && key == "vn") {
      const std::string problem = take_floats(line, 3, 3, normals);
      if (!problem.empty()) throw fail("normal " + problem);
    } else if (key == "f" && attributes) {
      face.clear();
      const int64_t defined[3] = {int64_t(mesh.source_positions.size() / 3), int64_t(texcoords.size() / 2),
                                  int64_t(normals.size() / 3)};
      for (std::string_view tok = next_token(line); !tok.empty(); tok = next_token(line)) {
        Corner c;
        const std::string problem = parse_corner(tok, defined, c);
        if (!problem.empty()) throw fail(problem);
        if (c.v >= defined[0]) forward.emplace_back(c.v, scan.line_no);
        any_vt |= c.vt != kNone;
        any_vn |= c.vn != kNone;
        face.push_back(c);
        if (face.size() > kMaxPolygonCorners) break;  // refused below, before the rest is read
      }
      if (const std::string problem = polygon_size_problem(face.size()); !problem.empty()) throw fail(problem);
      for (size_t i = 1; i + 1 < face.size(); ++i) {
        for (const Corner& c : {face[0], face[i], face[i + 1]}) {
          corners.push_back(c);
          mesh.triangles.push_back(c.v);
        }
        if (!mesh.materials.empty()) mesh.triangle_material.push_back(material);
      }
    } else if (key == "f") {
      poly.clear();
      const int64_t defined = static_cast<int64_t>(mesh.source_positions.size() / 3);
      for (std::string_view tok = next_token(line); !tok.empty(); tok = next_token(line)) {
        int64_t idx;
        if (!parse_int_prefix(tok, idx)) throw fail("bad face index " + quoted(tok));
        if (idx == 0) throw fail("face index 0 (OBJ indices start at 1)");
        // Negative = relative to the vertices defined so far; positive ones are checked
        // against the final count by validate_mesh (forward references are legal).
        int64_t v = idx > 0 ? idx - 1 : defined + idx;
        if (v < 0) throw fail("face index " + std::to_string(idx) + " points before the first vertex");
        if (v > 0xFFFFFFFEll) throw fail("face index " + std::to_string(idx) + " is out of range");
        if (v >= defined) forward.emplace_back(uint32_t(v), scan.line_no);
        poly.push_back(static_cast<uint32_t>(v));
        if (poly.size() > kMaxPolygonCorners) break;  // refused below, before the rest is read
      }
      if (const std::string problem = polygon_size_problem(poly.size()); !problem.empty()) throw fail(problem);
      append_fan(mesh.triangles, poly.data(), poly.size());
      if (!mesh.materials.empty()) mesh.triangle_material.resize(mesh.triangles.size() / 3, material);
    }
  }
  if (mesh.materials.empty()) {
    mesh.triangle_material.clear();
  } else if (std::find(mesh.triangle_material.begin(), mesh.triangle_material.end(), kNone) !=
             mesh.triangle_material.end()) {
    // Faces before the first usemtl: the material "" (no material).
    auto [it, fresh] = material_index.try_emplace(std::string(), uint32_t(mesh.materials.size()));
    if (fresh) mesh.materials.emplace_back();
    for (uint32_t& m : mesh.triangle_material)
      if (m == kNone) m = it->second;
  }
  for (const auto& [v, line_no] : forward)
    if (v >= mesh.source_positions.size() / 3)
      throw Error(name + ": line " + std::to_string(line_no) + ": face index " + std::to_string(uint64_t(v) + 1) +
                  " is beyond the file's " + std::to_string(mesh.source_positions.size() / 3) +
                  " vertices (OBJ indices start at 1)");
  if (any_vt || any_vn) split_corners(mesh, corners, texcoords, normals, any_vt, any_vn, name);
  if (!colours.empty()) add_vertex_colours(mesh, colours);
  localize_read_positions(mesh);
  return mesh;
}

}  // namespace meshsal
