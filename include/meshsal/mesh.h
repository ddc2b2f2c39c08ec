// meshsal public interface: errors and the mesh (one document, in memory).
// Part of meshsal.h (which includes every part); the conventions at the top of
// meshsal.h hold for every function here.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace meshsal {

// ------------------------------------------------------------------------------------------
// Errors and meshes

// The one exception type meshsal throws for bad input or a failed device. Its message is a
// single line; the command-line tool prints it after "error: ".
struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Thrown by a call whose cancel flag was set (SaliencyOptions::cancel and its twins in the
// other options): the call stopped early and returns nothing. An Error, so code that only
// catches Error still stops; code that falls back on Error must let this one through.
struct Cancelled : Error {
  using Error::Error;
};

// One per-vertex attribute channel besides the position (a texture coordinate, a normal
// component, a colour, a quality): one float per vertex, under its name.
struct VertexAttribute {
  std::string name;
  std::vector<float> values;  // one per vertex
};

struct GltfAssets;  // a glTF input's materials and textures (see Mesh::gltf_assets)

struct Mesh {
  // x,y,z per vertex, in input order, in local coordinates: relative to `origin`. Every
  // computation (saliency, simplification, views, distances) works on these floats.
  std::vector<float> positions;
  std::vector<uint32_t> triangles;  // 3 vertex indices per triangle

  // Local coordinates (SPEC section 6). The model's own coordinates of vertex v are
  // origin + positions[3v..3v+2], added in double. Loaders and make_mesh set the origin to
  // the centre of the mesh points' bounding box, computed in double from the values as read,
  // and round only the difference to float: a scan at survey coordinates (x ~ 5e5,
  // y ~ 4e6 m) keeps its millimetres, and every result is invariant to translation. A Mesh
  // filled by hand may leave the origin at 0 (positions are then the model's coordinates).
  double origin[3] = {0, 0, 0};
  // Optional: the model's coordinates as read (3 doubles per vertex), kept where
  // origin + positions would not give them back exactly. A writer writes vertex v from
  // here while positions[v] is still float(source - origin) (no computation moved it), so
  // an unmoved vertex is written as it was read; a moved one is written as origin +
  // positions. Empty, or 3 per vertex.
  std::vector<double> source_positions;
  // The file stored double coordinates (a PLY with double x, y, z): write_ply writes double.
  bool double_positions = false;

  // Optional (empty unless LoadOptions::attributes asked for them; saliency ignores them).
  // From OBJ: "u", "v" (vt) and "nx", "ny", "nz" (vn). From PLY: every scalar vertex
  // property besides x, y, z under its own name (nx, texture_u, red, quality, ...). A
  // channel named red, green, blue or alpha is written back as uchar, the rest as float;
  // write_obj writes u v (or s t, texture_u texture_v) as vt and nx ny nz as vn.
  // simplify_mesh interpolates them at each new vertex and renormalises nx ny nz.
  std::vector<VertexAttribute> attributes;
  // Optional: set when vertices were split where their attributes differ at one position
  // (a UV seam: an OBJ v used with different vt/vn, or PLY vertices at exactly one
  // position with different property values). position_vertex[i] is the lowest vertex at
  // the same position (i itself for that one; the OBJ loader appends the split twins after
  // the file's own vertices, a PLY keeps the file's order). Empty = no vertex is split;
  // PLY vertices that share a position and agree in every property are plain duplicates
  // and stay separate vertices. Saliency and
  // curvature are computed on the position-welded mesh (each corner replaced by its
  // position_vertex) and copied to the twins, so a seam does not cut the surface; the
  // simplifier keeps seams closed (see simplify_mesh).
  std::vector<uint32_t> position_vertex;

  // Optional: per-triangle materials. materials: their names, each once (an OBJ's usemtl
  // names in order of first use, "" standing for "no material": the faces before the first
  // usemtl; a glTF's material names, made unique). triangle_material: empty = no
  // materials; else one index into materials per triangle (a polygon's fan triangles all
  // take the polygon's). simplify_mesh keeps each surviving triangle's material (a collapse
  // never changes it). An OBJ's are read by load_obj always, whatever
  // LoadOptions::attributes says.
  // material_libraries: the file names of an OBJ's mtllib lines, in order, as written
  // (relative to its folder, held to the rule of the files a model may name: README);
  // material_library_text: the text of each as read from the model's folder by load_mesh
  // ("" where it could not be read, or loaded from memory), and material_library_folder
  // that folder (so that no output replaces a library of its input). write_obj writes the
  // materials into one .mtl beside its output (OUT.mtl: the libraries' text, or the glTF
  // materials in MTL terms, their images beside it as OUT_texN.EXT; mesh_side_files names
  // them), an mtllib line naming it after its header and a usemtl line before each run of
  // triangles with another material than the previous one ("usemtl" with no name for ""
  // after a named run).
  std::vector<std::string> material_libraries;
  std::vector<std::string> material_library_text;
  std::string material_library_folder;
  std::vector<std::string> materials;
  std::vector<uint32_t> triangle_material;

  // Optional (glTF input): the file's materials, textures, images and samplers, opaque
  // here, so write_gltf carries them over unchanged (triangle_material's slots name them).
  std::shared_ptr<const GltfAssets> gltf_assets;

  // Optional (glTF input): the world transform that every mesh instance of the file's scene
  // shares (the usual single mesh node), 16 numbers, column-major as glTF writes them.
  // positions are world coordinates, as for any instancing; write_gltf writes them back in
  // this frame under a node with this matrix, so a file keeps its node transform on the
  // way through. Empty = the identity (or instances with different transforms).
  std::vector<double> frame;

  size_t vertex_count() const { return positions.size() / 3; }
  size_t triangle_count() const { return triangles.size() / 3; }
};

// Copies flat arrays into a Mesh and validates it (validate_mesh). `positions` holds
// 3 * vertex_count floats, `indices` index_count uint32 (a multiple of 3).
Mesh make_mesh(const float* positions, size_t vertex_count, const uint32_t* indices,
               size_t index_count);

// The same from coordinates in double (the model's own frame): origin, local floats and the
// source as make_mesh does for floats (set_model_positions).
Mesh make_mesh(const double* positions, size_t vertex_count, const uint32_t* indices,
               size_t index_count);

// Sets mesh.positions, origin and source_positions from the model's own coordinates `xyz`
// (3 per vertex, vertex_count vertices): origin = the centre of the bounding box of the
// mesh points (the vertices mesh.triangles uses; all vertices when none is usable), computed
// in double; positions = float(xyz - origin); source_positions = xyz where that loses bits,
// else empty. Non-finite values stay non-finite (validate_mesh refuses them).
void set_model_positions(Mesh& mesh, const double* xyz, size_t vertex_count);

// The model's own coordinates of every vertex, 3 doubles per vertex: what the writers write
// (the source for an unmoved vertex, else origin + positions, in double).
std::vector<double> model_positions(const Mesh& mesh);

// True when float coordinates would not do for writing `mesh`: its file had double ones
// (double_positions), or rounding some vertex's model coordinates to float would move it by
// more than 1e-7 of the bounding-box diagonal of the mesh points. write_ply then writes
// double x, y, z; write_obj the digits of a double.
bool positions_need_double(const Mesh& mesh);

// Sets the per-vertex attribute `name` of `mesh` to `values` (one per vertex, kept as float),
// replacing an attribute of that name or adding it last: e.g. S as "quality", which
// `meshsal simplify` and Python's simplify() put on the mesh they simplify. Error when the
// count is not the vertex count.
void set_vertex_attribute(Mesh& mesh, const std::string& name, const std::vector<double>& values);
// Removes the attribute `name` from mesh.attributes and returns its values (empty when the
// mesh has none by that name): how a value carried along simplification is taken back out.
std::vector<double> take_vertex_attribute(Mesh& mesh, const std::string& name);

// Throws Error when the mesh is empty, an index is out of range, a coordinate is NaN/Inf
// or no triangle has non-zero area.
void validate_mesh(const Mesh& mesh);

// "" when the float32 positions resolve the mesh's detail, else a one-line warning
// ("float precision: ...") that they do not: the median edge (over a sample of triangles) is under 64 float steps at the
// largest coordinate magnitude of the mesh points, so normals, curvature and collapse tests
// work on rounding noise (a vertex 1e15 away from a 1-unit model; a scan at survey
// coordinates in float). It names that vertex. compute_saliency passes it to
// SaliencyOptions::notice ("warning: ...") and simplify_mesh to SimplifyReport::warning (and
// to its note when the target is missed).
std::string precision_warning(const Mesh& mesh);

}  // namespace meshsal
