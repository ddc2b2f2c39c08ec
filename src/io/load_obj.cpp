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

// One OBJ text read line by line: the mesh so far and what later lines need of earlier ones.
class ObjReader {
 public:
  ObjReader(std::string_view text, const std::string& name, bool attributes, std::vector<std::string>* not_read)
      : scan_(text, name), name_(name), attributes_(attributes), not_read_(not_read) {}

  Mesh read() {
    scan_.skip_bom();  // otherwise the first line's key would be "\xEF\xBB\xBFv" and be ignored
    std::string_view line;
    while (scan_.next_line(line)) {
      line = strip_comment(line);
      const std::string_view key = next_token(line);
      if (key == "mtllib") {
        mtllib(line);
      } else if (key == "usemtl") {
        usemtl(line);
      } else if (key == "v") {
        vertex(line);
      } else if (!attributes_ && (key == "vt" || key == "vn")) {
        // Not read: said once (LoadReport::attributes_not_read).
        if (key == "vt" && !seen_vt_) note_not_read(not_read_, "u"), seen_vt_ = true;
        if (key == "vn" && !seen_vn_) note_not_read(not_read_, "nx"), seen_vn_ = true;
      } else if (attributes_ && key == "vt") {
        const std::string problem = take_floats(line, 1, 2, texcoords_);  // u [v [w]]
        if (!problem.empty()) throw fail("texture coordinate " + problem);
      } else if (attributes_ && key == "vn") {
        const std::string problem = take_floats(line, 3, 3, normals_);
        if (!problem.empty()) throw fail("normal " + problem);
      } else if (key == "f" && attributes_) {
        face_with_corners(line);
      } else if (key == "f") {
        face(line);
      }
    }
    finish_materials();
    check_forward_references();
    if (any_vt_ || any_vn_) split_corners(mesh_, corners_, texcoords_, normals_, any_vt_, any_vn_, name_);
    if (!colours_.empty()) add_vertex_colours(mesh_, colours_);
    localize_read_positions(mesh_);
    return std::move(mesh_);
  }

 private:
  Error fail(const std::string& problem) const {
    return Error(name_ + ": line " + std::to_string(scan_.line_no) + ": " + problem);
  }

  // Carried into outputs (and read once materials are), so held to the rule of every file
  // a model names: in its folder or below (io/model_reference.h).
  void mtllib(std::string_view line) {
    for (std::string_view tok = next_token(line); !tok.empty(); tok = next_token(line)) {
      if (const std::string problem = reference_text_problem(std::string(tok), /*uri=*/false); !problem.empty())
        throw fail("mtllib " + quoted(tok, 200) + ": " + problem);
      mesh_.material_libraries.emplace_back(tok);
    }
  }

  // The name is the rest of the line (without surrounding blanks): "usemtl" alone is "".
  void usemtl(std::string_view line) {
    while (!line.empty() && is_space(line.front())) line.remove_prefix(1);
    while (!line.empty() && is_space(line.back())) line.remove_suffix(1);
    auto [it, fresh] = material_index_.try_emplace(std::string(line), uint32_t(mesh_.materials.size()));
    if (fresh) {
      // The faces so far have no material; from here on every triangle gets one entry.
      if (mesh_.materials.empty()) mesh_.triangle_material.assign(mesh_.triangles.size() / 3, kNone);
      mesh_.materials.emplace_back(line);
    }
    material_ = it->second;
  }

  void vertex(std::string_view line) {
    const std::string problem = take_xyz(line, mesh_.source_positions);
    if (!problem.empty()) throw fail(problem);
    // Named here, as the file numbers its vertices (from 1), not by validate_mesh.
    for (size_t k = mesh_.source_positions.size() - 3; k < mesh_.source_positions.size(); ++k)
      if (!std::isfinite(mesh_.source_positions[k]))
        throw fail("vertex " + std::to_string(mesh_.source_positions.size() / 3) + " has a non-finite coordinate (" +
                   std::to_string(mesh_.source_positions[k]) + ")");
    // Optional columns follow: w, or r g b (MeshLab's vertex colours, kept with attributes).
    if (!attributes_ && !seen_colours_ && not_read_) {
      int more = 0;
      for (std::string_view tok = next_token(line); !tok.empty() && more < 4; tok = next_token(line)) ++more;
      if (more == 3) note_not_read(not_read_, "red"), seen_colours_ = true;
    } else if (attributes_) {
      float rgb[3];
      int got = 0;
      for (std::string_view tok = next_token(line); !tok.empty() && got < 4; tok = next_token(line), ++got)
        if (got < 3 && (!parse_coord(tok, rgb[got]) || !std::isfinite(rgb[got]))) got = 4;
      if (got == 3) {
        colours_.resize(mesh_.source_positions.size() - 3, -1.0f);
        colours_.insert(colours_.end(), rgb, rgb + 3);
      }
    }
  }

  // An f line read with attributes: its v/vt/vn corners, kept per triangle for split_corners.
  void face_with_corners(std::string_view line) {
    face_.clear();
    const int64_t defined[3] = {int64_t(mesh_.source_positions.size() / 3), int64_t(texcoords_.size() / 2),
                                int64_t(normals_.size() / 3)};
    for (std::string_view tok = next_token(line); !tok.empty(); tok = next_token(line)) {
      Corner c;
      const std::string problem = parse_corner(tok, defined, c);
      if (!problem.empty()) throw fail(problem);
      if (c.v >= defined[0]) forward_.emplace_back(c.v, scan_.line_no);
      any_vt_ |= c.vt != kNone;
      any_vn_ |= c.vn != kNone;
      face_.push_back(c);
      if (face_.size() > kMaxPolygonCorners) break;  // refused below, before the rest is read
    }
    if (const std::string problem = polygon_size_problem(face_.size()); !problem.empty()) throw fail(problem);
    for (size_t i = 1; i + 1 < face_.size(); ++i) {
      for (const Corner& c : {face_[0], face_[i], face_[i + 1]}) {
        corners_.push_back(c);
        mesh_.triangles.push_back(c.v);
      }
      if (!mesh_.materials.empty()) mesh_.triangle_material.push_back(material_);
    }
  }

  // An f line read without attributes: its v indices only.
  void face(std::string_view line) {
    poly_.clear();
    const int64_t defined = static_cast<int64_t>(mesh_.source_positions.size() / 3);
    for (std::string_view tok = next_token(line); !tok.empty(); tok = next_token(line)) {
      int64_t idx;
      if (!parse_int_prefix(tok, idx)) throw fail("bad face index " + quoted(tok));
      if (idx == 0) throw fail("face index 0 (OBJ indices start at 1)");
      // Negative = relative to the vertices defined so far; positive ones are checked
      // against the final count by validate_mesh (forward references are legal).
      int64_t v = idx > 0 ? idx - 1 : defined + idx;
      if (v < 0) throw fail("face index " + std::to_string(idx) + " points before the first vertex");
      if (v > 0xFFFFFFFEll) throw fail("face index " + std::to_string(idx) + " is out of range");
      if (v >= defined) forward_.emplace_back(uint32_t(v), scan_.line_no);
      poly_.push_back(static_cast<uint32_t>(v));
      if (poly_.size() > kMaxPolygonCorners) break;  // refused below, before the rest is read
    }
    if (const std::string problem = polygon_size_problem(poly_.size()); !problem.empty()) throw fail(problem);
    append_fan(mesh_.triangles, poly_.data(), poly_.size());
    if (!mesh_.materials.empty()) mesh_.triangle_material.resize(mesh_.triangles.size() / 3, material_);
  }

  // No usemtl: no materials. Faces before the first usemtl: the material "" (no material).
  void finish_materials() {
    if (mesh_.materials.empty()) {
      mesh_.triangle_material.clear();
    } else if (std::find(mesh_.triangle_material.begin(), mesh_.triangle_material.end(), kNone) !=
               mesh_.triangle_material.end()) {
      auto [it, fresh] = material_index_.try_emplace(std::string(), uint32_t(mesh_.materials.size()));
      if (fresh) mesh_.materials.emplace_back();
      for (uint32_t& m : mesh_.triangle_material)
        if (m == kNone) m = it->second;
    }
  }

  void check_forward_references() const {
    for (const auto& [v, line_no] : forward_)
      if (v >= mesh_.source_positions.size() / 3)
        throw Error(name_ + ": line " + std::to_string(line_no) + ": face index " + std::to_string(uint64_t(v) + 1) +
                    " is beyond the file's " + std::to_string(mesh_.source_positions.size() / 3) +
                    " vertices (OBJ indices start at 1)");
  }

  Mesh mesh_;
  TextScan scan_;
  const std::string& name_;
  const bool attributes_;
  std::vector<std::string>* not_read_;
  std::vector<uint32_t> poly_;
  std::vector<Corner> face_, corners_;  // with attributes: this face's, and every triangle's
  std::vector<float> texcoords_, normals_;
  std::vector<float> colours_;  // r g b per v line up to the last one with colours (-1: none)
  bool seen_vt_ = false, seen_vn_ = false, seen_colours_ = false;  // without attributes: noted once
  bool any_vt_ = false, any_vn_ = false;
  // Face indices beyond the vertices defined so far (forward references, legal) and their
  // lines: checked against the final count at the end, named as the file writes them.
  std::vector<std::pair<uint32_t, size_t>> forward_;
  // The current usemtl's index into mesh.materials (kNone before the first), one per
  // triangle as the faces are read.
  uint32_t material_ = kNone;
  std::map<std::string, uint32_t, std::less<>> material_index_;
};

}  // namespace

Mesh load_obj_text(std::string_view text, const std::string& name, bool attributes, std::vector<std::string>* not_read) {
  return ObjReader(text, name, attributes, not_read).read();
}

}  // namespace meshsal
