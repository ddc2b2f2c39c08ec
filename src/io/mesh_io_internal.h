// meshsal: the per-format parsers behind load_mesh. Each one parses bytes already in
// memory; `name` is only used to prefix error messages ("NAME: line 7: ...").
// They fan-triangulate polygons and reject faces with fewer than 3 vertices; the caller
// (load_mesh) runs validate_mesh on the result.
#pragma once
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "core/first_index_where.h"
#include "meshsal/meshsal.h"

namespace meshsal {

class ReadObserver;  // io/read_observer.h

// `attributes`: also vt, vn and v/vt/vn corners (LoadOptions::attributes).
// `not_read` (may be null): what `attributes` off left unread (LoadReport::attributes_not_read).
Mesh load_obj_text(std::string_view text, const std::string& name, bool attributes = false,
                   std::vector<std::string>* not_read = nullptr);
// `attributes`: the vertex columns COFF, NOFF and STOFF announce (normals, colours, u v).
Mesh load_off_text(std::string_view text, const std::string& name, bool attributes = false,
                   std::vector<std::string>* not_read = nullptr);
// `attributes`: the extra scalar vertex properties also go to Mesh::attributes, in file order.
// `unread` (may be null) gets what no option keeps (LoadReport::unread). `observer` (may be
// null) is told of the positions and triangles as they are read (io/read_observer.h).
Mesh load_ply_bytes(std::string_view bytes, const std::string& name, VertexProperties* properties,
                    bool attributes = false, std::vector<std::string>* unread = nullptr,
                    std::vector<std::string>* not_read = nullptr, ReadObserver* observer = nullptr);
// STL, ASCII or binary, welded (load_stl.cpp); `welded` gets the corners merged into an
// earlier vertex at the same position.
Mesh load_stl_bytes(std::string_view bytes, const std::string& name, uint64_t* welded);

// glTF 2.0 (load_gltf.cpp): `binary` for GLB. `folder` is where external buffers and images
// are read from ("" = the glTF came from memory: any external reference is an Error);
// each is read whole, at most `limit` bytes (0: kNoHeaderLimitBytes), regular files only.
// `attributes`: NORMAL, TEXCOORD_n, COLOR_0 and the scalar custom attributes (Channel).
Mesh load_gltf_bytes(std::string_view bytes, const std::string& name, bool binary, const std::string& folder,
                     uint64_t limit, bool attributes, std::vector<std::string>* unread,
                     std::vector<std::string>* not_read = nullptr);

// Every parser reads coordinates in double into mesh.source_positions and ends with this:
// origin, local float positions, and the source kept where it is needed (set_model_positions).
inline void localize_read_positions(Mesh& mesh) {
  set_model_positions(mesh, mesh.source_positions.data(), mesh.source_positions.size() / 3);
}

// The bits of a coordinate for exact comparison of positions (STL welding, PLY seams):
// float equality, -0 equal to +0.
inline uint32_t position_bits(float x) {
  if (x == 0.0f) x = 0.0f;
  uint32_t b;
  std::memcpy(&b, &x, 4);
  return b;
}
inline uint64_t position_bits(double x) {
  if (x == 0.0) x = 0.0;
  uint64_t b;
  std::memcpy(&b, &x, 8);
  return b;
}

// The most corners one polygon may have, in every format: a fan of n corners is n - 2
// triangles, so one face line must not be able to ask for gigabytes (a 25M-corner OBJ
// face became 2.7 GB). Real polygons (a cylinder's cap) stay far below it.
constexpr uint64_t kMaxPolygonCorners = 65536;

// "" for a polygon of 3..kMaxPolygonCorners corners, else "face with ... vertices (...)".
inline std::string polygon_size_problem(uint64_t n) {
  if (n < 3) return "face with " + std::to_string(n) + " vertices (needs at least 3)";
  if (n > kMaxPolygonCorners)
    return "face with more than " + std::to_string(kMaxPolygonCorners) + " vertices (" +
           std::to_string(kMaxPolygonCorners) + " is the most a polygon may have)";
  return "";
}

// The fan triangulation of one polygon (n >= 3 indices, already checked): (p0, pi, pi+1).
template <class Index>
void append_fan(std::vector<uint32_t>& triangles, const Index* poly, size_t n) {
  for (size_t i = 1; i + 1 < n; ++i) {
    triangles.push_back(static_cast<uint32_t>(poly[0]));
    triangles.push_back(static_cast<uint32_t>(poly[i]));
    triangles.push_back(static_cast<uint32_t>(poly[i + 1]));
  }
}

// How many bytes a gzipped file may inflate to (and how much a pipe may deliver) when no
// limit is set: for PLY and OFF, whose headers give counts, 64 MiB plus 64 times the bytes
// those counts need (lists counted with 3 items); for OBJ, which has no header, 1 GiB.
// `head` is the start of the data (the first MiB, or all of it when shorter); the PLY and
// OFF versions parse it and throw the header's Error, so garbage is refused before the
// rest is inflated.
constexpr uint64_t kCountsSlackBytes = uint64_t(64) << 20;
constexpr uint64_t kCountsFactor = 64;
constexpr uint64_t kNoHeaderLimitBytes = uint64_t(1) << 30;
uint64_t ply_input_limit(std::string_view head, const std::string& name);
uint64_t off_input_limit(std::string_view head, const std::string& name);
// STL: a binary header's triangle count as PLY's counts; ASCII (no counts) as OBJ.
uint64_t stl_input_limit(std::string_view head, const std::string& name);

// header + slack + factor * need, saturating.
inline uint64_t counts_limit(uint64_t header_bytes, unsigned __int128 need) {
  const unsigned __int128 limit = header_bytes + kCountsSlackBytes + need * kCountsFactor;
  return limit > UINT64_MAX ? UINT64_MAX : static_cast<uint64_t>(limit);
}

// The bytes write_gltf writes (GLB when `binary`, else glTF JSON with its buffer embedded);
// `path` only names the output in messages (write_gltf.cpp).
std::string gltf_file_bytes(const std::string& path, const std::vector<GltfLevel>& levels, bool binary);

// The writers' common check: whole triples and every index inside the vertices.
inline void check_mesh(const std::string& path, const Mesh& mesh) {
  if (mesh.positions.size() % 3 != 0 || mesh.triangles.size() % 3 != 0)
    throw Error(path + ": cannot write: mesh arrays are not multiples of 3");
  const uint32_t* corners = mesh.triangles.data();
  const size_t nv = mesh.vertex_count();
  if (const size_t i = first_index_where(mesh.triangles.size(), [&](size_t j) { return corners[j] >= nv; });
      i < mesh.triangles.size())
    throw Error(path + ": cannot write: a triangle uses vertex " + std::to_string(corners[i]) +
                " but the mesh has " + std::to_string(nv) + " vertices");
}

// The 1-based line of each vertex in a text writer (OBJ's v, OFF's vertices, the latter
// from 0) where split twins (Mesh::position_vertex) share one line, so that a seam stays one
// surface in the file; empty when the mesh has no twins (vertex v is line v + 1).
std::vector<uint64_t> welded_lines(const std::string& path, const Mesh& mesh);

// The mesh's vertex colours as 3 bytes per vertex (red green blue attributes, rounded and
// clamped), empty when it has none.
std::vector<uint8_t> vertex_colour_bytes(const Mesh& mesh);

// The colours a text writer (OBJ, OFF) writes: S on the pictures' scale when given, else
// the mesh's own (vertex_colour_bytes); empty for none.
std::vector<uint8_t> written_colours(const std::string& path, const Mesh& mesh, const std::vector<double>* saliency);

// OFF (COFF with `rgb`, 3 bytes per vertex, when not empty), text (write_off.cpp).
void write_off(const std::string& path, const Mesh& mesh, const std::vector<uint8_t>& rgb);
// Binary STL (write_stl.cpp): positions in the model's coordinates as float.
void write_stl(const std::string& path, const Mesh& mesh);
// OBJ with `rgb` as `v x y z r g b` when not empty (write_obj.cpp).
void write_obj_colours(const std::string& path, const Mesh& mesh, const std::vector<uint8_t>& rgb);

// An OBJ's material libraries (Mesh::material_libraries) read from the model's folder into
// Mesh::material_library_text, together within `budget` bytes; what cannot be read goes to
// `unread` (material_library.cpp).
void read_material_libraries(Mesh& mesh, const std::string& folder, uint64_t budget, std::vector<std::string>* unread);
// The texture files an OBJ's libraries name (map_Kd, bump, norm, ...), each once, as written.
std::vector<std::string> library_textures(const Mesh& mesh);
// The name of the .mtl an OBJ output gets (OUT.mtl's file name), for its mtllib line.
std::string material_library_name(const std::string& obj_path);
// Writes the side files of an OBJ output (mesh_side_files): OUT.mtl and the textures.
void write_material_files(const std::string& obj_path, const Mesh& mesh);

// Adds what a file held and LoadOptions::attributes (off) left unread, once: "normals",
// "texture coordinates", "vertex colours", "the saliency", "the attribute 'NAME'", by the
// name's role (attribute_role).
inline void note_not_read(std::vector<std::string>* out, const std::string& attribute_name) {
  if (!out) return;
  const AttributeRole r = attribute_role(attribute_name);
  const std::string what = r.kind == AttributeKind::Normal     ? "normals"
                           : r.kind == AttributeKind::TexCoord ? "texture coordinates"
                           : r.kind == AttributeKind::Color    ? "vertex colours"
                           : r.kind == AttributeKind::Saliency ? "the saliency"
                                                               : "the attribute '" + attribute_name + "'";
  for (const std::string& w : *out)
    if (w == what) return;
  out->push_back(what);
}

inline const VertexAttribute* find_attribute(const Mesh& mesh, const char* name) {
  for (const VertexAttribute& a : mesh.attributes)
    if (a.name == name) return &a;
  return nullptr;
}

}  // namespace meshsal
