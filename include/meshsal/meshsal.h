// meshsal: mesh saliency (Lee, Varshney, Jacobs, "Mesh Saliency", SIGGRAPH 2005) on the CPU
// and on Vulkan GPUs, saliency-guided simplification, best viewpoints and pictures.
//
// This is the whole public interface: link `meshsal::core` (CPU only, no Vulkan) or
// `meshsal::gpu` (adds the Vulkan backend) from `find_package(meshsal)`.
//
// Conventions, for every function below:
//  - A mesh is flat arrays, as in meshoptimizer: `positions` holds x,y,z per vertex (float,
//    in the model's own units), `triangles` 3 vertex indices per triangle (uint32). Polygons
//    are fan-triangulated by the loaders. Vertices no triangle uses are allowed: they keep
//    their index and get curvature and saliency 0. The *mesh points* are the vertices that
//    at least one triangle uses.
//  - Distances and the saliency scale unit eps are in model units; eps is eps_frac times the
//    bounding-box diagonal of the mesh points.
//  - Bad input (an unreadable or malformed file, an index out of range, NaN coordinates, an
//    option out of range) and device failures throw meshsal::Error, whose message is one
//    line meant for a person. std::bad_alloc can escape when memory runs out.
//  - Functions are reentrant: calls on different data may run on different threads at the
//    same time. A result never refers to its inputs (everything returned is owned by value).
//  - Results do not depend on the number of threads.
// The method's fixed choices are documented in docs/method.md of the repository.
#pragma once
#include <cstddef>
#include <cstdint>
#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

// The version: CMake's project(VERSION) is the one source; the build checks that these agree.
#define MESHSAL_VERSION 200  // major * 10000 + minor * 100 + patch
#define MESHSAL_VERSION_STRING "0.2.0"

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

// ------------------------------------------------------------------------------------------
// Reading and writing files

// Scalar vertex properties found in a PLY besides x,y,z (e.g. "quality"), as floats.
using VertexProperties = std::map<std::string, std::vector<float>>;

// Bounds on what loading may hold in memory.
struct LoadOptions {
  // The most bytes a gzipped file may inflate to, and a pipe (FIFO) may deliver. 0 means
  // the default: for a gzipped PLY or OFF, 64 MiB + 64 times the bytes its header's counts
  // need (a binary STL: its triangle count); for a gzipped OBJ or ASCII STL (no counts)
  // and for a pipe, 1 GiB. The library reads no environment variable for it (the meshsal
  // command fills it from MESHSAL_MAX_INPUT).
  uint64_t max_input_bytes = 0;
  // Fill Mesh::attributes (and Mesh::position_vertex): OBJ vt/vn, whose faces' v/vt/vn
  // corners become one vertex per distinct (v, vt, vn) (a v's first combination keeps its
  // index, the others are appended), PLY's other scalar vertex properties, OFF's normals,
  // colours and texture coordinates, glTF's NORMAL, TEXCOORD_n, COLOR_0 and scalar custom
  // attributes (_SALIENCY as quality). Off by default: then an OBJ's vt/vn are ignored and
  // vertices are the file's v lines. A PLY's seams (vertices at one position whose
  // properties differ: Mesh::position_vertex) are found either way, so that every front
  // end computes S on one surface there.
  bool attributes = false;
  // Refuse named pipes too: only regular files are read (meshsal batch, where a pipe
  // among the inputs would block its loader until something writes to it).
  bool regular_files_only = false;
};

// What loading did to the file's data besides parsing it.
struct LoadReport {
  // STL only (0 for the other formats): the triangle corners that were merged into an
  // earlier vertex at exactly the same position (float equality, -0 equal to +0), i.e.
  // 3 * triangles - vertices of the result. STL stores every corner by value; welding
  // gives the shared vertices that curvature needs.
  uint64_t welded_corners = 0;
  // What the file holds that no loading keeps, e.g. a PLY's "vertex list property
  // 'texcoord'", "face property 'flags'", "element 'edge'", a glTF's "vertex attribute
  // 'JOINTS_0'", an OBJ's unreadable "material library 'x.mtl': ...". Tells a user what an
  // output will lack.
  std::vector<std::string> unread;
  // What the file holds that LoadOptions::attributes (off) left unread: "normals",
  // "texture coordinates", "vertex colours", "the attribute 'NAME'" (empty with attributes).
  std::vector<std::string> attributes_not_read;
};

// Loads OBJ, PLY (ascii, binary little/big endian), OFF, STL (ascii or binary) or glTF 2.0
// (.gltf with its buffers, .glb), optionally gzipped, chosen by extension (.obj .ply .off
// .stl .gltf .glb, each optionally followed by .gz). glTF: every triangle primitive of every
// mesh instance in the default scene (scene 0 when none is named), node transforms applied
// (positions in world coordinates; a transform all instances share is kept in Mesh::frame),
// strips and fans made triangles, merged into one mesh whose vertices at one position are
// linked (Mesh::position_vertex) so saliency sees one surface; with attributes, NORMAL,
// TEXCOORD_0 and COLOR_0 (when every primitive has them); materials carried
// (Mesh::gltf_assets). Points, lines, Draco or meshopt compression and GPU instancing are
// refused, naming them.
// Polygons are fan-triangulated. STL corners at identical positions are welded into shared
// vertices, numbered in order of first appearance (the count goes to `report`); a binary
// STL is recognised by its size (84 + 50 n bytes), whatever its header says, and an STL
// with a non-finite coordinate is refused. The result is validated. Throws Error with a
// one-line message that names `path` on any problem. If `properties` is given, scalar PLY
// vertex properties are returned there. Only regular files and FIFOs are read (devices
// such as /dev/zero are refused).
Mesh load_mesh(const std::string& path, VertexProperties* properties = nullptr,
               const LoadOptions& options = {}, LoadReport* report = nullptr);

// The same from bytes in memory: `name` picks the format by its extension, as a path
// does, and starts every error message.
Mesh load_mesh_bytes(std::string_view bytes, const std::string& name,
                     VertexProperties* properties = nullptr, const LoadOptions& options = {},
                     LoadReport* report = nullptr);

struct PlyFloatProperty {
  std::string name;
  const std::vector<double>* values;  // one per vertex, written as float
};

// Writes binary little-endian PLY: positions, the given float properties, optional uchar
// red/green/blue (3 per vertex) and the triangles. Written to a fresh temporary file in the
// same folder and renamed, so a failure never leaves a half-written file in place.
void write_ply(const std::string& path, const Mesh& mesh,
               const std::vector<PlyFloatProperty>& properties,
               const std::vector<uint8_t>* rgb = nullptr);

// Writes OBJ (v and f lines), the same atomic way.
void write_obj(const std::string& path, const Mesh& mesh);

// Writes the saliency PLY of `meshsal saliency` (SPEC section 4): write_ply with the
// property quality = S, then `extra` (e.g. curvature and the raw maps of --dump-scales), and
// red/green/blue = the colour scale of S over the mesh points (the pictures' scale:
// minimum..maximum of S, square-root position). The mesh points are `is_point` when given
// (SaliencyResult::is_point, one per vertex), else the vertices a triangle uses. The mesh's
// own attributes come before them, unless one of these replaces them.
void write_saliency_ply(const std::string& path, const Mesh& mesh, const std::vector<double>& saliency,
                        const std::vector<PlyFloatProperty>& extra = {},
                        const std::vector<uint8_t>* is_point = nullptr);

struct ColorRange;  // the pictures' colour scale (below)

// One mesh of a glTF file written by write_gltf: the mesh (not owned), optionally its
// saliency (one value per vertex) with the mesh points that set the colour scale (null:
// the vertices a triangle uses), and the name of its node and mesh ("" = "mesh" or "LODi").
struct GltfLevel {
  const Mesh* mesh = nullptr;
  const std::vector<double>* saliency = nullptr;
  const std::vector<uint8_t>* is_point = nullptr;
  std::string name;
  // The ends of the colour scale COLOR_0 puts S on (not owned; null: the pictures' default,
  // minimum to maximum).
  const ColorRange* range = nullptr;
};

// Writes glTF 2.0: binary for a name ending in .glb, JSON with its buffer embedded (base64)
// for .gltf; the same atomic way as write_ply. Each level becomes a mesh under a node of
// its own: levels[0] is the scene's node, and with more levels its MSFT_lod extension lists
// the others' nodes in order (finest first, as MSFT_lod reads them). Per vertex: POSITION,
// NORMAL (nx ny nz, renormalised; a zero one replaced by the faces' normal), TEXCOORD_0 (u v,
// s t or texture_u texture_v, v flipped to glTF's convention), COLOR_0 (unsigned byte
// RGBA: the saliency on the pictures' colour scale, else the mesh's red green blue alpha),
// _SALIENCY (float) and every other attribute as a float _NAME in capitals (quality ->
// _QUALITY). Triangles go into one primitive per material (triangle_material), with the
// input's glTF materials, textures and images when it has them (Mesh::gltf_assets), else a
// plain material per name. Positions are written in the node's frame: a glTF input's
// shared node transform (Mesh::frame) is written back as the node's matrix; otherwise
// the node is translated to Mesh::origin and the local floats are written as they are, so
// survey coordinates keep their precision. The levels' meshes should share the frame
// (levels of one input do); levels[0]'s materials and frame are the file's.
void write_gltf(const std::string& path, const std::vector<GltfLevel>& levels);
// One mesh, with its saliency when given.
void write_gltf(const std::string& path, const Mesh& mesh, const std::vector<double>* saliency = nullptr);

// ---- One mesh document, every format -----------------------------------------------------
// A Mesh is the one document every reader fills and every writer writes. Its per-vertex
// attributes are known by name; attribute_role() is the one table of what a name holds,
// and each format's MeshFormat says which of those it can keep. What a format cannot keep
// is named once, by mesh_output_note().

// What a per-vertex attribute holds.
enum class AttributeKind {
  Normal,    // nx ny nz
  TexCoord,  // u v (also s t, texture_u texture_v: PLY's names) = set 0; u1 v1 .. u7 v7 = sets 1..7
  Color,     // red green blue alpha, 0..255 (sRGB bytes, as PLY's uchar colours)
  Saliency,  // quality: meshsal's S (PLY's `quality`, glTF's _SALIENCY)
  Scalar     // any other name: one float per vertex
};

struct AttributeRole {
  AttributeKind kind = AttributeKind::Scalar;
  int set = 0;        // TexCoord: the UV set (glTF's TEXCOORD_<set>)
  int component = 0;  // Normal: x y z = 0 1 2; TexCoord: u v = 0 1; Color: r g b a = 0..3
};

// The role of an attribute name (above).
AttributeRole attribute_role(const std::string& name);

// The attribute S travels under in a Mesh: PLY's `quality` (MeshLab reads it as such). The
// glTF reader names its _SALIENCY so, and the glTF writer writes it back as _SALIENCY;
// simplify_mesh carries it as any attribute.
constexpr const char* kSaliencyAttribute = "quality";

// How much of S a format keeps: the value (PLY quality, glTF _SALIENCY, with colours
// beside it), only the colours of the pictures' scale (OBJ `v x y z r g b`, OFF's COFF), or
// nothing (STL).
enum class SaliencyKept { Value, Colors, None };

// A mesh file format and what its files hold besides positions and triangles.
struct MeshFormat {
  std::string suffix;      // ".ply" (lower case; the writer a name ending so picks)
  std::string name;        // "PLY"
  bool normals = false;    // Normal attributes
  int texcoord_sets = 0;   // TexCoord sets kept (OBJ: 1, its vt; PLY and glTF: all 8)
  bool colors = false;     // Color attributes
  bool scalars = false;    // Scalar attributes
  bool materials = false;  // per-triangle materials (OBJ: usemtl, with an .mtl written beside)
  SaliencyKept saliency = SaliencyKept::None;
};

// Every format meshsal reads and writes: PLY, glTF, GLB, OBJ, OFF, STL (the order messages
// name them in).
const std::vector<MeshFormat>& mesh_formats();

// The format a file name picks by its suffix (case-insensitive; not .gz), null for none.
const MeshFormat* mesh_format(const std::string& path);

// The writer a file name picks, for every front end's -o: ".ply", ".gltf", ".glb", ".obj",
// ".off" or ".stl" (case-insensitive), "" for none of them.
std::string mesh_output_format(const std::string& path);

// One line naming what writing `mesh` to `path` loses (with S when `saliency`), from the
// table above, "" when its format keeps everything, e.g. "out.obj keeps S as vertex colours
// only, and not the attribute 'curvature' (.ply, .gltf and .glb keep them)". Front ends
// print it once, as a note. Error for an unknown format.
std::string mesh_output_note(const std::string& path, const Mesh& mesh, bool saliency);

// The files besides `path` that write_mesh writes for `mesh`: for an OBJ with materials,
// its material library OUT.mtl and the images of a glTF input's materials as OUT_texN.EXT
// (OUT: `path` without .obj); none for the other formats. For the output checks before any
// work, and for the list of outputs a command prints.
std::vector<std::string> mesh_side_files(const std::string& path, const Mesh& mesh);

// Writes `mesh` in the format its name gives (mesh_output_format), keeping what the format
// can hold (above): PLY (write_ply, or write_saliency_ply with S), glTF and GLB
// (write_gltf), OBJ (write_obj; S as vertex colours), OFF (COFF with S's colours, or the
// mesh's own), STL (binary; positions only). S given for an STL is an Error naming the
// formats that keep it, as is an unknown suffix. Atomic as write_ply.
void write_mesh(const std::string& path, const Mesh& mesh, const std::vector<double>* saliency = nullptr);

// One file a call is about to write (check_outputs).
struct OutputFile {
  std::string path;                     // as given; "" = not requested (skipped)
  std::string option;                   // what names it in messages: "-o", "--map", "path"
  std::vector<std::string> extensions;  // accepted endings, lower case (".png"), matched
                                        // case-insensitively; empty = any name
};

// The check every front end makes on the files it will write, before any work (loading,
// saliency, rendering): a typo costs nothing and an input is never lost. The meshsal
// command checks every output with it, Python's save() its path, and saliency_file() and
// simplify_file() their output against their input. Throws Error "PATH: problem" (PATH as
// given) when an output's name has none of its `extensions` ("PATH: OPTION must be a .ply
// or .glb file"), it cannot be written by the writers' rule (an empty name, a folder, a
// block device, a socket, a missing or unwritable folder; symlinks are followed, and a
// character device or named pipe is written in place), two outputs are the same file
// ("given for both -o and --map"), or an output is the same file as one of `inputs` ("-o
// is the input file 'IN'"): the same device and inode, so through a symbolic or hard link
// too, since the writers' rename would replace the input whatever its permissions. Inputs
// that are "" or do not exist are skipped (loading them fails later with its own message);
// outputs that do not exist yet are fine. Then removes the temporaries (NAME.tmp.XXXXXX)
// that a writer killed while writing one of these outputs left beside it; a live writer's
// are kept. Checks, it does not reserve: a file made between this check and the write is
// not seen.
void check_outputs(const std::vector<OutputFile>& outputs, const std::vector<std::string>& inputs);

// Reads the saliency S back for `mesh` from a file that keeps its value: a PLY's `quality`
// (as `meshsal saliency` writes it) or a glTF's _SALIENCY. Throws Error when the file holds
// no S (an OBJ, OFF or STL: their colours cannot be turned back into values), a value is
// not finite or negative (S >= 0: a quality from another program), or the file belongs to
// another mesh: another vertex count, or a vertex at another position (beyond float
// precision: 1e-6 of the bounding-box diagonal), named.
std::vector<double> load_saliency(const std::string& path, const Mesh& mesh);
// The same (its name before glTF could hold S).
std::vector<double> load_saliency_ply(const std::string& path, const Mesh& mesh);

// ------------------------------------------------------------------------------------------
// Saliency (the paper's section 3)

enum class Backend {
  Auto,  // a discrete or integrated GPU when there is one, else the CPU (with a notice on failure)
  Cpu,   // the CPU reference path
  Gpu    // a Vulkan device (Error when built without Vulkan or no device works)
};

// The GPU sweep's arithmetic. Mixed: distances and weights in float, sums folded into
// doubles, cutoffs decided exactly and near ties of the local-maximum test rechecked in
// double (the default scales; other scales run in double). Double: all in double.
// Auto: mixed on GPUs whose doubles run at most a quarter as fast as floats (consumer GPUs:
// 1/32..1/64; timed once per device by a short probe), double on the others (the H200,
// 1/2: double measured 2.2x faster on igea_loop2) and on CPU devices (lavapipe), where the
// double sweep measured faster too. The CPU path is always double.
enum class Precision { Auto, Mixed, Double };

// How the Gaussian-weighted averages are taken (SPEC section 5; docs/method.md).
// Exact: over every mesh point within 2 sigma (SPEC section 1), cost ~ n x neighbours.
// Fast: over per-cell aggregates (count, curvature sum, centroid) of cells of sigma/6, a
//   fixed number of cells per vertex whatever the density, so the cost is linear in n;
//   measured against Exact on the scans: final-saliency correlation >= 0.999 and >= 98% of
//   the exact top-30% vertices in the fast top 30% (docs/method.md has the figures).
//   Everything after the averages is unchanged; with `smoothed`, Sm uses the same method.
//   Runs on either backend, picked as for Exact; the Vulkan path is held to the CPU's fast
//   path per vertex to 1e-4 of each raw map's maximum (in double on the device).
// Auto: Fast when the exact sweep's estimated pair count (mesh points x mean neighbours
//   within 4 x the largest scale x eps, from 256 sampled points) exceeds kAutoPairBudget,
//   with a one-line notice; else Exact.
enum class Method { Exact, Fast, Auto };
constexpr double kAutoPairBudget = 2e9;  // ~6 s of exact sweep on 2 CPU cores

class Device;  // an open Vulkan device, kept across calls (see "Devices" below)

// Processes that share one tiled saliency computation (SaliencyOptions::tiles), such as
// the ranks of an MPI run: process rank() computes the tiles t with t % ranks() == rank()
// and the processes exchange the few values saliency needs from the whole mesh (each
// scale's maximum and the local maxima behind mbar) and their results through all_gather.
// Every process calls compute_saliency with the same mesh and options and gets the whole
// result. The library holds no MPI: the caller implements this over its transport.
class TileExchange {
 public:
  virtual ~TileExchange() = default;
  virtual int rank() const = 0;
  virtual int ranks() const = 0;
  // Called by every process in the same order; returns every process's bytes, in rank
  // order (its own included). Throws Error when the transport fails.
  virtual std::vector<std::vector<uint8_t>> all_gather(const std::vector<uint8_t>& mine) = 0;
};

struct SaliencyOptions {
  // Limits (Error otherwise): eps_frac in (0, 0.1], 1..16 scales each in (0, 100], and
  // 2 x largest scale x eps_frac <= 1 (the widest Gaussian at most the bbox diagonal).
  double eps_frac = 0.003;                    // eps = eps_frac * bbox diagonal
  std::vector<double> scales{2, 3, 4, 5, 6};  // s_i = scales[i] * eps
  unsigned threads = 0;                       // CPU threads, 0 = all cores (at most 1024)
  Backend backend = Backend::Cpu;
  int device = -1;                            // Vulkan device index (list_devices), -1 = choose
  // An open Device to run on (may be null; not owned, must outlive the call). With it,
  // Backend::Gpu runs there and Backend::Auto too (falling back to the CPU on failure, as
  // Auto does); `device` is not read and the process's device cache is not used.
  // Backend::Cpu with a session is an Error (the two contradict each other).
  Device* session = nullptr;
  bool smoothed = false;                      // also compute Sm = G(S, 3 eps) (simplification)
  // Keep the raw center-surround maps in SaliencyResult::raw (8 bytes per vertex per
  // scale); false leaves raw empty, and the fast CPU path then holds one map at a time
  // (the CLI asks for them only with --dump-scales). S is the same bits either way.
  bool raw_maps = true;
  Precision precision = Precision::Auto;      // the GPU sweep's arithmetic
  Method method = Method::Exact;              // exact or approximate averages (see Method)
  // Called with a stage name and the fraction done of that stage (0..1), from the calling
  // thread. May be empty.
  std::function<void(const char* stage, double fraction)> progress;
  // Called with a one-line notice (e.g. "auto: no GPU, using the CPU path"). May be empty.
  std::function<void(const std::string&)> notice;
  // Cancellation (may be null): set *cancel from any thread or a signal handler and the
  // call throws Cancelled within a fraction of a second (it polls the flag between chunks
  // of work on every thread, and between GPU submissions). The same in SimplifyOptions,
  // OptimiserOptions and CompareOptions; the flag is only read.
  const std::atomic<bool>* cancel = nullptr;
  // Tiles (0 or 1: none): the mesh points' bounding box is cut into cubes, `tiles` of them
  // along its longest axis, and each tile computes its own vertices from a sub-mesh holding
  // them and a halo (every mesh point within the largest cutoff of its queries, with their
  // triangles); each scale's maximum and mbar are reduced over all tiles before the
  // suppression. Exact: the same bits as without tiles; Fast: the same to rounding (the
  // order of sums over cells). CPU only (Backend::Gpu with tiles is an Error, Auto takes
  // the CPU). Memory: the mesh, every tile's raw maps at its query points (about 60
  // bytes per vertex) and one tile's work at a time; saliency_file() keeps the mesh and
  // the maps on disk instead.
  unsigned tiles = 0;
  // With tiles: processes sharing the tiles (null: this process computes them all).
  TileExchange* exchange = nullptr;
};

struct StageTime {
  std::string name;
  double seconds;
  // The process's peak resident memory during the stage, in bytes; 0 unless measured
  // (meshsal bench turns it on; reading it restarts the kernel's high-water mark).
  uint64_t peak_bytes = 0;
};

struct SaliencyResult {
  double eps = 0;                         // the scale unit, model units
  std::vector<uint8_t> is_point;          // 1 for mesh points, per vertex
  std::vector<double> curvature;          // mean curvature H per vertex (1/model units)
  std::vector<std::vector<double>> raw;   // raw center-surround maps S_i, [scale][vertex]
  std::vector<double> saliency;           // final saliency S per vertex (0 on non-points)
  std::vector<double> smoothed;           // Sm = G(S, 3 eps) when options.smoothed, else empty
  uint64_t pairs = 0;                     // neighbour pairs the sweep visited (Fast:
                                          // (vertex, cell aggregate) pairs)
  Method method = Method::Exact;          // the method that ran (Auto resolved)
  bool mixed_precision = false;           // the GPU sweep ran in mixed precision
  uint64_t rechecked = 0;                 // points a mixed sweep swept again in double
  std::vector<StageTime> stages;          // wall time per stage
  std::string backend_name;               // "cpu (N threads)" or the Vulkan device name
  size_t tiles = 0;                       // tiles of the grid (SaliencyOptions::tiles), 0: untiled
  int ranks = 1;                          // processes that shared them (TileExchange)
};

// Saliency of every vertex, on options.backend. Throws Error on an invalid mesh or option,
// or (Backend::Gpu) when no Vulkan device can run it; Backend::Auto falls back to the CPU.
SaliencyResult compute_saliency(const Mesh& mesh, const SaliencyOptions& options);

// The same over flat arrays (copied once; see make_mesh).
SaliencyResult compute_saliency(const float* positions, size_t vertex_count,
                                const uint32_t* indices, size_t index_count,
                                const SaliencyOptions& options);

// ------------------------------------------------------------------------------------------
// Out of core: saliency (and, below, simplification) of a mesh file larger than memory

struct OutOfCoreOptions {
  // The process's peak resident memory stays under this many bytes (0: no limit; then
  // SaliencyOptions::tiles decides the tiling). The input is streamed into tiles on disk
  // and the tiles are computed one at a time; the fewest tiles whose largest (with its
  // halo) fits are taken. A limit too small for one tile is an Error naming the smallest
  // workable one.
  uint64_t memory_limit = 0;
  std::string temp_dir;      // where the tiles go ("" = $TMPDIR or /tmp); removed at the end
  bool dump_scales = false;  // also write curvature and saliency_raw_i (as write_saliency_ply)
};

struct OutOfCoreReport {
  uint64_t vertices = 0, points = 0, triangles = 0;
  size_t tiles = 0;               // tiles of the grid
  int ranks = 1;                  // processes that shared them (SaliencyOptions::exchange)
  double eps = 0;
  uint64_t pairs = 0;             // the sweeps' pairs over every tile (halos included)
  uint64_t tile_estimate = 0;     // bytes: the largest tile's estimated peak
  double saliency_min = 0, saliency_max = 0, saliency_mean = 0;  // over the mesh points
  std::vector<StageTime> stages;
};

// Saliency of the mesh in `input` written to `output` as write_saliency_ply() writes it
// (the input's vertex order, positions as read, quality and colours; the same bytes as
// compute_saliency + write_saliency_ply for the exact method), without ever holding the
// whole mesh: binary PLY is streamed (other formats are loaded once and converted to a
// temporary binary PLY). options.method Auto is taken as Fast; tiles run on the CPU.
// With options.exchange, every process passes the same arguments, the temporary folder
// must be on a disk they share, and only rank 0 writes `output`. Before any work, `output`
// must end in .ply (Error "OUTPUT: saliency_file writes a binary PLY: ..." for a .obj or
// .glb name) and pass check_outputs against `input`: it is never the input file, not
// through a symbolic or hard link either.
OutOfCoreReport saliency_file(const std::string& input, const std::string& output,
                              const SaliencyOptions& options, const OutOfCoreOptions& out_of_core);

// A size as every front end reads it ("700M", "2G", "1.5G", "512K", "700MB", "2000000"): a
// decimal number with an optional K, M, G or T (powers of 1024, either case, a B after it
// allowed), truncated to whole bytes. Error on anything else: 0 bytes after truncation, more
// than 64 bits hold, hex, inf, a sign, an exponent, and a bare number under 1M (surely a
// forgotten unit: the message suggests it).
uint64_t parse_memory_size(const std::string& text);

// "auto", "mixed" or "double"; throws Error on anything else.
Precision parse_precision(const std::string& name);

// "exact", "fast" or "auto"; throws Error on anything else.
Method parse_method(const std::string& name);

// "auto", "cpu" or "gpu"; throws Error on anything else.
Backend parse_backend(const std::string& name);

// The names the parsers above read, for each value (the front ends' option texts).
const char* precision_name(Precision precision);
const char* method_name(Method method);
const char* backend_name(Backend backend);

// Parses "2,3,4,5,6" into scales; throws Error on anything else (empty, <= 0, > 100, junk).
std::vector<double> parse_scales(const std::string& text);

// ------------------------------------------------------------------------------------------
// Simplification (the paper's section 4)

struct SimplifyOptions {
  size_t target_faces = 0;    // face count to reach; 0 = use `ratio`
  double ratio = 0;           // fraction of the input faces to keep, in (0, 1]
  // Weight of the border-edge quadrics (times the squared edge length). Larger keeps open
  // borders more exactly.
  double border_weight = 10;
  // A collapse is refused when it turns a remaining triangle's normal by more than
  // acos(min_normal_cos). 0 = refuse turns of 90 degrees or more.
  double min_normal_cos = 0;
  unsigned threads = 0;          // threads for the initial edge costs (0 = all cores)
  bool record_collapses = false; // record the collapse sequence (tests)
  // An error bound besides (or instead of) the face target, as meshoptimizer's
  // target_error: a collapse whose error exceeds it is refused, and simplification ends
  // when no collapse within it is left (or the face target is reached). In units of the
  // bounding-box diagonal of the mesh points (0.01 = 1%); 0 = no bound. A collapse's error
  // is the RMS distance of the new vertex to the planes its quadric holds,
  // sqrt(Q(v) / sum of the plane weights), with the unweighted quadrics: vertex weights
  // steer which collapses go first, never what their error reads.
  // With target_error > 0 and neither target_faces nor ratio, the face target is 1.
  double target_error = 0;
  // Vertices on an open border (or a non-manifold edge) are neither moved nor removed:
  // the border keeps its exact vertices and positions.
  bool lock_border = false;
  const std::atomic<bool>* cancel = nullptr;  // as SaliencyOptions::cancel
};

// One edge contraction: `removed` merges into `kept` (input indices); `cost` its quadric error.
struct Collapse {
  uint32_t kept;
  uint32_t removed;
  double cost;
};

struct SimplifyReport {
  size_t input_faces = 0;     // non-degenerate input triangles
  size_t target_faces = 0;    // the target actually used
  size_t output_faces = 0;
  size_t output_vertices = 0;
  bool reached = false;       // output_faces == target_faces
  // The target was at or above the mesh's face count (simplify_keeps_mesh): the mesh came
  // back as it was, every vertex and triangle, and `note` says so.
  bool unchanged = false;
  std::string note;           // why the target was not reached, or that the mesh is unchanged
  std::string warning;        // precision_warning(mesh): the input is too coarse to trust
  size_t collapses = 0;
  size_t refused = 0;         // collapses refused (link condition, flips, non-manifold edges)
  double seconds = 0;         // wall time of the whole call
  double error = 0;           // largest error of the collapses made (see target_error)
  std::vector<Collapse> sequence;      // when options.record_collapses
  std::vector<uint32_t> vertex_origin; // output vertex -> the input vertex it survived as
};

// True when `options` ask for at least `face_count` faces (target_faces >= face_count, or
// no target_faces and ratio 1): simplify_mesh and simplify_with_saliency then return the
// mesh unchanged (SimplifyReport::unchanged, as meshoptimizer does), so that a script over
// meshes of every size does not stop on the small ones. Front ends ask it to skip the
// saliency such a call would not use.
bool simplify_keeps_mesh(const SimplifyOptions& options, size_t face_count);

// Garland-Heckbert edge collapses with area-weighted plane quadrics, border quadrics and
// optimal placement. Mesh::attributes are carried along: the vertex kept by a collapse
// takes the attributes interpolated linearly along the collapsed edge at the new
// position's projection onto it; nx ny nz of moved vertices are renormalised. Vertices
// split at a seam (Mesh::position_vertex) never move or take another side's attributes: a
// collapse onto one keeps it in place, and a seam edge between two positions with one twin
// each side collapses along the seam on both sides at once; so a UV seam stays closed and
// every triangle's texture coordinates come from one side. With lock_border, border
// vertices (seam vertices included) are neither moved nor removed. vertex_weights (may be null): one weight W >= 0 per input vertex; each
// vertex quadric is multiplied by W once before any collapse (the paper's section 4; build
// W with saliency_weights()). The output is manifold and oriented where the input is, never
// has fewer faces than the target, and has exactly the target when reachable (otherwise
// report->note says why). Output vertices follow the input order of the survivors. A
// target at or above the face count returns the mesh as it is (simplify_keeps_mesh).
// Throws Error on a bad target or weights.
Mesh simplify_mesh(const Mesh& mesh, const SimplifyOptions& options,
                   const std::vector<double>* vertex_weights = nullptr,
                   SimplifyReport* report = nullptr);

// How the smoothed saliency Sm becomes the weights W (docs/method.md, "Weightings").
enum class WeightCurve {
  Threshold,   // the paper: W = lambda Sm if Sm >= alpha, else Sm
  Continuous,  // W = 1 + lambda min(cap, (Sm / alpha)^gamma)   (cap 0: no cap)
  Rank,        // W = 1 + lambda ((r - a) / (1 - a))^gamma where r >= a, else 1; r = the rank
               // of Sm among the mesh points in [0, 1], a = alpha_percentile / 100
               // (gamma 0: a step, 1 + lambda on the top 100 - alpha_percentile %)
};

constexpr double kDefaultWeightFloor = 0.001;

struct SaliencyWeightOptions {
  double lambda = 100;            // amplification of salient vertices, >= 0
  double alpha_percentile = 30;   // alpha = this percentile of Sm over mesh points, [0, 100]
  // Not in the paper: W is raised to at least floor * mean(W) over mesh points, so that no
  // collapse is free. The paper's rule gives W = 0 where Sm is 0 (flat regions), and there
  // every collapse, border ones included, costs nothing: a plane with one bump lost half its
  // area at 10% (Hausdorff 35% of the diagonal). kDefaultWeightFloor, chosen by measurement
  // (docs/method.md, "Weight floor"), removes that and leaves the paper's recipe on the
  // benchmark meshes as it was; 0 gives the literal rule. Where every W is 0 (nothing
  // salient), a floor > 0 makes every W 1: plain quadrics.
  double floor = kDefaultWeightFloor;
  WeightCurve curve = WeightCurve::Threshold;
  double gamma = 1;               // exponent of the Continuous and Rank curves, [0, 16]
  double cap = 0;                 // Continuous: largest (Sm / alpha)^gamma, 0 = no cap
};

// The named weightings of `meshsal simplify --weights`: None (plain quadrics, no weights),
// Saliency (the paper's recipe: SaliencyWeightOptions{} as declared) and Balanced (parameters
// chosen by measurement, docs/method.md "Weightings": the salient-region error drops by about
// a fifth while RMS and Hausdorff error stay within 1.25x of plain's on most models, where the
// paper's recipe costs 3x on the bunny; weight_preset() returns them).
enum class Weighting { None, Saliency, Balanced };

// The weighting a front end uses when none is named (`meshsal simplify` and `batch`
// without --weights, Python's simplify() without weights=): the one place it is decided.
constexpr Weighting kDefaultWeighting = Weighting::Balanced;

// "none", "saliency" or "balanced"; throws Error on anything else.
Weighting parse_weighting(const std::string& name);

// The name parse_weighting() reads: "none", "saliency" or "balanced".
const char* weighting_name(Weighting weighting);

// The SaliencyWeightOptions of a named weighting (None: the options are not used).
SaliencyWeightOptions weight_preset(Weighting weighting);

// W(v) for every mesh point (is_point != 0) by options.curve (above); 0 for other vertices.
// alpha is the alpha_percentile of Sm over the mesh points; `alpha_out` receives it.
std::vector<double> saliency_weights(const std::vector<double>& smoothed,
                                     const std::vector<uint8_t>& is_point,
                                     const SaliencyWeightOptions& options,
                                     double* alpha_out = nullptr);

// Smoothed saliency Sm = G(S, 3 eps) over the mesh points, eps = eps_frac * bbox diagonal,
// with the exact averages.
std::vector<double> smooth_saliency(const Mesh& mesh, const std::vector<double>& saliency,
                                    double eps_frac = 0.003, unsigned threads = 0);

// The same with the averages of options.method (Exact, Fast, or Auto decided as
// compute_saliency decides it on this mesh), eps_frac, threads and cancel: the method these
// options name, not necessarily the one that computed `saliency` (nothing records that).
// Given the options that computed S, the result is compute_saliency's own Sm
// (SaliencyOptions::smoothed) up to the backend's rounding. On the CPU, whatever
// options.backend says: the fast CPU filter takes seconds where the exact one took most of
// a simplification's time (igea_loop2: 35.5 s against 7.1 s).
std::vector<double> smooth_saliency(const Mesh& mesh, const std::vector<double>& saliency,
                                    const SaliencyOptions& options);

// What simplification_weights() returns.
struct SimplificationWeights {
  std::vector<double> weights;   // W per vertex (0 on vertices no triangle uses)
  double alpha = 0;              // the alpha_percentile of Sm over the mesh points
  std::vector<double> saliency;  // S per vertex: computed, or the one given
  std::string device;            // what computed S (SaliencyResult::backend_name: "cpu (N
                                 // threads)" or the Vulkan device's name); empty when S was given
};

// The per-vertex weights W of saliency-guided simplification: saliency (computed with
// `saliency_options`, or taken from `saliency` when it is not null: one S per vertex),
// smoothed to Sm = G(S, 3 eps) with saliency_options.method (smooth_saliency), then
// saliency_weights(). A mesh split at seams (Mesh::position_vertex) is weighed welded (the
// twins get their position's values). Every front end (simplify, batch, Python) calls this.
SimplificationWeights simplification_weights(const Mesh& mesh, const SaliencyWeightOptions& weight_options,
                                             const SaliencyOptions& saliency_options,
                                             const std::vector<double>* saliency = nullptr);

// Saliency-guided simplification in one call: saliency (computed with `saliency_options`,
// or taken from `saliency` when it is not null: one S per vertex), smoothed, turned into
// weights and used by simplify_mesh. `alpha_out` receives alpha.
Mesh simplify_with_saliency(const Mesh& mesh, const SimplifyOptions& options,
                            const SaliencyWeightOptions& weight_options,
                            const SaliencyOptions& saliency_options,
                            const std::vector<double>* saliency = nullptr,
                            SimplifyReport* report = nullptr, double* alpha_out = nullptr);

// One level of a chain of levels of detail (simplify_lod).
struct LodLevel {
  Mesh mesh;                     // the level, attributes and materials carried
  std::vector<double> saliency;  // S per vertex of this level (the input's, carried); empty unweighted
  SimplifyReport report;         // of the step that made it from the level before
};

// Levels of detail in one call: each level's face target from `levels` (target_faces, or
// ratio of the INPUT's faces; lock_border and the rest as simplify_mesh reads them; no
// target_error), as parse_lod_levels would read them: all counts or all ratios, each below
// the one before (Error otherwise). A level at or above the faces of the level it starts
// from is that level unchanged (report.unchanged), as simplify_mesh leaves a mesh whose
// face count is at or below the target. With weight_options, the
// saliency is computed once on `mesh` (saliency_options; or taken from `saliency`) and
// carried down the chain as a vertex attribute, interpolated along each collapse; each
// level is simplified from the level before with weights from S on that mesh
// (simplification_weights). Without (null), plain quadrics. Simplifying from the level
// before measured better than from the input at equal faces (8-12% lower RMS error at 20%
// and 5% on bunny_36k, armadillo_43k and igea_134k: README, Levels of detail).
std::vector<LodLevel> simplify_lod(const Mesh& mesh, const std::vector<SimplifyOptions>& levels,
                                   const SaliencyWeightOptions* weight_options, const SaliencyOptions& saliency_options,
                                   const std::vector<double>* saliency = nullptr);

// The levels of "0.5,0.2,0.05" or "20000,5000" (--lod): a number with a decimal point or
// an exponent is a ratio in (0, 1), a whole number a face count; all ratios or all counts
// (which of 0.5 and 300 has fewer faces depends on the mesh), each below the one before, at
// most 16. Error otherwise, so a bad list is found before any mesh is read.
std::vector<SimplifyOptions> parse_lod_levels(const std::string& text);

// Writes a chain: a .glb or .gltf holds `mesh` (with its saliency, may be null) as LOD0 and
// each level as LOD1.. (write_gltf: one mesh each, linked by MSFT_lod); an .obj or .ply
// path gets one file per level, lod_level_path(path, 1..) (a PLY with the level's S as
// `quality`), and `mesh` is not written.
void write_lod(const std::string& path, const Mesh& mesh, const std::vector<double>* saliency,
               const std::vector<LodLevel>& levels);
// "dir/out_lod2.obj" for ("dir/out.obj", 2): the file of level `level` of write_lod.
std::string lod_level_path(const std::string& path, size_t level);

// simplify_mesh by tiles, for meshes larger than memory (simplify_file runs the same
// passes on disk). `tiles` cubic tiles along the longest axis of the mesh points' bounding
// box, the grid anchored at its minimum; each triangle belongs to the tile of its
// centroid. Rounds, each keeping at most half the faces it starts from: a first pass
// simplifies every tile alone, the vertices it shares with other tiles pinned (neither
// moved nor removed, nor joined by a new edge), every tile down to a common error level
// (the level at which the tiles together keep the round's faces, found from each tile's
// collapse costs); then strip passes: the triangles at the vertices still pinned, plus one
// ring, grouped by grids shifted by 1/2, 1/4 and 3/4 tile, then by tiles twice as large up
// to one piece, simplified with the same pins toward the round's target. The pieces share
// their pinned vertices, so the result has no crack and no border edge the input did not
// have; it is manifold and oriented where the input is. Every pass takes its groups'
// goals from the common level, strips too, so a small piece gives up only what is cheap.
// Open borders simplify as options.lock_border says. Weights apply per vertex as in
// simplify_mesh; each pass starts its quadrics afresh from the surface the last one left.
// Attributes and materials are carried; vertex_origin maps to input vertices, output
// vertices follow their input order. The face count lands at or above the target
// (report->note when above): within 1% unless the tiles are small against the output's
// triangles. The RMS error is within 1.2x of simplify_mesh's with 2-4 tiles at 10% and 1%
// on igea_134k (0.82-0.95x) and bunny_36k (0.82-0.93x) but for tiles a few output
// triangles wide (bunny at 1% with 4 tiles, 695 faces over ~40 tiles: 2.8x; README). It
// takes 3-5x simplify_mesh's time. report->error: the largest collapse error, in units of
// the whole mesh's diagonal; no collapse sequence. tiles 0 or 1, or a target at or above
// the face count: simplify_mesh itself. Throws Error as simplify_mesh does, and for tiles >
// 1024, options.target_error, options.record_collapses or a mesh split at seams
// (Mesh::position_vertex), which the tiled path does not take.
Mesh simplify_mesh_tiled(const Mesh& mesh, const SimplifyOptions& options, unsigned tiles,
                         const std::vector<double>* vertex_weights = nullptr, SimplifyReport* report = nullptr);

struct OutOfCoreSimplifyReport {
  SimplifyReport simplify;        // faces, collapses, error, note (no vertex_origin, no sequence)
  OutOfCoreReport saliency;       // the saliency the weights came from (tiles 0: no weights)
  unsigned tiles = 0;             // simplification tiles along the longest axis
  double alpha = 0;               // the weights' threshold: weights->alpha_percentile of Sm
  uint64_t tile_estimate = 0;     // bytes: the largest simplification tile's estimated peak
  std::vector<StageTime> stages;
};

// Out of core: simplify_mesh_tiled on the mesh in `input` without ever holding it whole,
// written to `output` as a binary PLY (the surviving vertices in input order, an unmoved
// one as read; with weights, S as the per-vertex `quality`, carried as simplify_mesh
// carries attributes). The input is streamed into tiles on disk as saliency_file() does
// (binary PLY; other formats converted once); the saliency (smoothed, method Auto taken as
// Fast) runs a tile at a time, Sm's percentile and mean are found by streaming, and each
// pass of the tiled simplifier reads one group of triangles and its guards at a time.
// weights: the weighting (the Rank curve needs every point's rank and is refused); null:
// plain quadrics. tiles: at least this many along the longest axis; with a memory limit,
// the fewest that fit it (an Error names the smallest workable limit when none does).
// Writes the bytes that simplify_mesh_tiled with the same tile count, weights from the
// same saliency (S as `quality`) and write_ply give. Positions and S only: other vertex
// properties, materials and seams are not read. Throws Error as simplify_mesh_tiled does,
// and, before any work, for an output as saliency_file() refuses it (not a .ply name, or
// the input file itself, through a link too).
OutOfCoreSimplifyReport simplify_file(const std::string& input, const std::string& output,
                                      const SimplifyOptions& options, const SaliencyWeightOptions* weights,
                                      const SaliencyOptions& saliency_options, const OutOfCoreOptions& out_of_core,
                                      unsigned tiles = 1);

// ------------------------------------------------------------------------------------------
// Comparing two surfaces

struct CompareOptions {
  size_t face_samples = 200000;     // area samples per surface, on top of its vertices
  double salient_fraction = 0.30;   // top fraction of the original's mesh points by saliency
  unsigned threads = 0;             // 0 = all cores
  const std::atomic<bool>* cancel = nullptr;  // as SaliencyOptions::cancel
};

// Distances in model units (divide by `diagonal` for a share of the model's size).
struct SurfaceComparison {
  double diagonal = 0;          // bbox diagonal of the original's mesh points
  double forward_max = 0;       // original's samples -> simplified surface
  double forward_rms = 0;
  double backward_max = 0;      // simplified's samples -> original surface
  double backward_rms = 0;
  double hausdorff = 0;         // max(forward_max, backward_max)
  double rms = 0;               // max(forward_rms, backward_rms)
  double salient_error = -1;    // mean distance of the salient vertices; -1 without saliency
  size_t salient_vertices = 0;
  size_t forward_samples = 0, backward_samples = 0;
};

// Point-to-surface distances both ways (BVH). `saliency` (may be null): one value per vertex
// of the original; its top salient_fraction of mesh points give salient_error.
SurfaceComparison compare_surfaces(const Mesh& original, const Mesh& simplified,
                                   const std::vector<double>* saliency,
                                   const CompareOptions& options = {});

// ------------------------------------------------------------------------------------------
// Viewpoints (the paper's section 5) and pictures

// Which axis of the mesh is up in pictures and in view angles. The angles of ViewAngles are
// taken in a frame where this axis plays the part of +y: for Z, theta 0 looks from -y (the
// front of a z-up scan), theta 90 degrees from +x, phi 90 degrees from +z (above).
enum class UpAxis { Y, MinusY, Z, MinusZ, X, MinusX };

// "x", "y", "z", "-x", "-y" or "-z" (also "+x", "+y", "+z"); throws Error otherwise.
UpAxis parse_up_axis(const std::string& name);

// Direction d(theta, phi) = (cos phi sin theta, sin phi, cos phi cos theta), y up:
// (0, 0) looks from +z, theta = pi/2 from +x, phi = pi/2 from above. Radians.
struct ViewAngles {
  double theta = 0;  // longitude, in (-pi, pi]
  double phi = 0;    // latitude, in [-pi/2, pi/2]
};

struct VisibilityOptions {
  int resolution = 256;       // z-buffer side in pixels, 16..8192
  double depth_tol_px = 2.0;  // depth tolerance in pixel widths, >= 0
  unsigned threads = 0;       // CPU threads (views in parallel), 0 = all cores
};

struct OptimiserOptions {
  int restarts = 8;              // random starts of the gradient ascent
  uint64_t seed = 1;             // runs with the same seed repeat
  double probe = 0.05;           // probe angle (radians) for the central differences
  double initial_step = 0.25;    // first step length along the gradient (radians)
  double min_step = 0.01;        // a restart stops when its step shrinks below this
  int max_iterations = 60;       // per restart
  // Called after each batch of views scored, from the calling thread, with a stage name and
  // the fraction done of that stage (0..1, never falling, 1 when it ends): "best view" for
  // the gradient ascent (an estimate: each restart's share of its iterations or of its
  // step's way down to min_step, whichever is further), then, in best_viewpoint with
  // views > 0, "view map" (views scored / views). May be empty.
  std::function<void(const char* stage, double fraction)> progress;
  const std::atomic<bool>* cancel = nullptr;  // as SaliencyOptions::cancel (best_viewpoint too)
};

struct OptimiserResult {
  ViewAngles best;
  double U = 0;                      // visible score of `best`
  std::vector<ViewAngles> starts;    // the random start of each restart
  std::vector<ViewAngles> finals;    // where each restart ended
  std::vector<double> final_U;
  uint64_t views_evaluated = 0;
  // Set when no direction tried saw anything (U = 0 everywhere): `best` is then the front
  // view (0, 0), not an arbitrary start, and this says why.
  std::string note;
};

struct ViewMap {
  std::vector<ViewAngles> views;
  std::vector<double> U;
  size_t best = 0;  // index of the largest U
};

struct BestView {
  OptimiserResult optimised;  // gradient ascent from seeded random starts
  ViewMap map;                // exhaustive map over `views` Fibonacci directions (empty if 0)
  std::string backend_name;   // where the views were scored
};

// The older form of best_viewpoint(mesh, score, ViewpointOptions) below, kept for its
// callers; new code uses that one. The view of largest visible score U = sum of score over
// the visible mesh points (`score`: one value per vertex, finite and >= 0 on the mesh
// points, else Error); `views` > 0 also evaluates that many directions exhaustively;
// backend as in SaliencyOptions. It runs the same search (ViewpointOptions with up Y and
// these settings): angles in the y-up frame, as the optimiser returns them (not through
// the direction round trip), VisibilityOptions' own resolution (256 by default), the whole
// sphere.
BestView best_viewpoint(const Mesh& mesh, const std::vector<double>& score,
                        const OptimiserOptions& options = {}, int views = 0,
                        const VisibilityOptions& visibility = {}, Backend backend = Backend::Cpu,
                        int device = -1);

// The z-buffer side of the viewpoint search: ViewpointOptions::resolution's default, and so
// that of every front end (`meshsal viewpoint`, `render --best`, `batch --view`, Python).
constexpr int kDefaultViewResolution = 512;

// ---- Limits of the view and picture settings (issue 38: one constant per limit; every check
// and its message, in the library and the front ends, is built from these) ----
// The side in pixels of every square picture and z-buffer: RenderStyle::size,
// VisibilityOptions::resolution and ViewpointOptions::resolution (--size, --resolution).
constexpr int kMinImageSize = 16, kMaxImageSize = 8192;
constexpr int kMinMapWidth = 32;  // the view map picture (--map): kMinMapWidth..kMaxImageSize wide
// What the front ends accept for the viewpoint search (--restarts, --views, --depth-tol).
constexpr int kMaxViewRestarts = 1000, kMaxViewMapViews = 1000000, kMaxDepthTolPx = 1000;
// ---- end of the view limits ----

// A band of latitudes, in degrees, in the frame of the up axis: -90 <= min <= max <= 90.
// The default is the whole sphere.
struct ElevationRange {
  double min = -90;
  double max = 90;
};

// "MIN,MAX" in degrees (e.g. "0,60": from the horizon to 60 degrees above it); throws Error
// naming the problem (not two numbers, outside [-90, 90], min > max).
ElevationRange parse_elevation_range(const std::string& text);

// Everything that picks a view. Every front end fills this and calls best_viewpoint, so the
// same settings give the same view to the last bit (docs/method.md, "One view pipeline").
struct ViewpointOptions {
  UpAxis up = UpAxis::Y;                    // the frame of the angles: searched, limited, returned
  int resolution = kDefaultViewResolution;  // z-buffer side in pixels, 16..8192
  double depth_tol_px = 2.0;                // depth tolerance in pixel widths, >= 0
  // The latitudes (phi, in the frame of `up`) the search may look from: the random starts
  // are uniform on that band of the sphere, every probe and step stays in it, and the
  // exhaustive map's directions are spread over it. Error when out of range (above).
  ElevationRange elevation;
  int restarts = 8;                         // random starts of the gradient ascent, >= 1
  uint64_t seed = 1;                        // runs with the same seed repeat
  int views = 0;                            // also score this many directions exhaustively, >= 0
  unsigned threads = 0;                     // CPU threads (views in parallel), 0 = all cores
  Backend backend = Backend::Cpu;           // as SaliencyOptions::backend (visibility)
  int device = -1;                          // Vulkan device index, -1 = choose
  Device* session = nullptr;                // as SaliencyOptions::session (visibility)
  // The gradient ascent's steps, as in OptimiserOptions.
  double probe = 0.05;
  double initial_step = 0.25;
  double min_step = 0.01;
  int max_iterations = 60;
  // As OptimiserOptions::progress ("best view", then "view map" with views > 0).
  std::function<void(const char* stage, double fraction)> progress;
  // Called with a one-line notice (e.g. Backend::Auto found no GPU); also kept in
  // Viewpoint::notices. May be empty.
  std::function<void(const std::string&)> notice;
  const std::atomic<bool>* cancel = nullptr;  // as SaliencyOptions::cancel
};

// The camera of a view: orthographic, looking from `eye` towards `target` (mesh
// coordinates), `up` the picture's up direction (unit), framing a square of half side
// `half_extent` model units around `target` (before RenderStyle::margin). view_camera()
// makes it; render_camera_view(mesh, score, camera, style) renders exactly that picture.
struct ViewCamera {
  ViewAngles view;              // the direction, in the frame of up_axis
  UpAxis up_axis = UpAxis::Y;
  double eye[3] = {0, 0, 0};     // target + radius * direction (radius: the bounding sphere's)
  double target[3] = {0, 0, 0};  // the centre of the picture
  double up[3] = {0, 1, 0};      // unit, the picture's up
  double direction[3] = {0, 0, 1};  // unit, from the mesh towards the viewer
  double half_extent = 1;       // half the side of the square shown, model units
};

// The camera render_view uses for `view` (angles in the frame of `up`) on this mesh: centred
// on the mesh points' projected extent, which it frames. Throws Error on an empty mesh.
ViewCamera view_camera(const Mesh& mesh, const ViewAngles& view, UpAxis up = UpAxis::Y);

// The result of the viewpoint search. Angles are in the frame of ViewpointOptions::up.
struct Viewpoint {
  ViewAngles view;                   // the best direction found (optimised.best)
  double U = 0;                      // its visible score
  double total = 0;                  // the score summed over all mesh points (as U sums it)
  double visible_fraction = 0;       // U / total (0 when total is 0)
  UpAxis up = UpAxis::Y;             // the frame of every angle here
  ViewCamera camera;                 // view_camera(mesh, view, up)
  OptimiserResult optimised;         // gradient ascent from seeded random starts
  ViewMap map;                       // the exhaustive map (empty without views)
  std::string note;                  // optimised.note: why the front view, when nothing was seen
  std::vector<std::string> notices;  // what options.notice heard
  std::string backend_name;          // where the views were scored
};

// The view of largest visible score U = sum of score over the visible mesh points (`score`:
// one value per vertex, e.g. SaliencyResult::saliency; finite and >= 0 on the mesh points,
// else Error), searched in the frame of options.up within options.elevation. The search runs
// on the mesh's coordinates turned into that frame (an exact permutation of the axes), so a
// mesh turned so that z is up, searched with up Z, gives the angles of the original with up
// Y. Throws Error for an option out of range.
Viewpoint best_viewpoint(const Mesh& mesh, const std::vector<double>& score,
                         const ViewpointOptions& options);

// The one colour scale of every picture and of the saliency PLY's vertex colours: a value v
// is placed at t = sqrt((v - lo) / (hi - lo)), clamped to [0, 1], and t runs through Turbo
// from blue (t = 0, RGB 73 88 221) through cyan, green and yellow to dark red (t = 1,
// 155 15 0); colour bars place their value ticks the same way. lo and hi are values, or
// percentiles (0..100) of the values over the mesh points. The default, 0th to 100th
// percentile (minimum to maximum), is unclipped, so the hottest colour means the highest
// values only (a percentile clip painted the demo's ~900 bumps as red as its unique
// feature); the square root spreads the moderate values (a face's eyes, nose and mouth)
// over more colours than a linear scale would.
struct ColorRange {
  double lo = 0, hi = 100;
  bool lo_percentile = true, hi_percentile = true;
};

// "LO,HI", each a number (a value) or a number followed by % (a percentile, 0..100), e.g.
// "0,0.5" or "5%,99%". Throws Error naming the problem (both values: lo < hi needed).
ColorRange parse_color_range(const std::string& text);

// What a viewer page shows besides the model (write_view_page).
struct ViewPageOptions {
  std::string title;                                        // the page's heading (the file name)
  std::vector<std::pair<std::string, std::string>> stats;  // rows of the statistics table
  std::string note;                                         // a line the page shows ("" = none)
  // A mesh with more faces is shown as a copy simplified to this many (plain quadrics,
  // the saliency carried along; or as close as the simplifier gets, ViewPageReport), and
  // the page says so; 0 = never.
  size_t max_faces = 2000000;
  // The ends of the colour scale the page opens with (ColorRange; minimum to maximum).
  ColorRange range;
};

// True when this build has the web viewer (three.js bundled at build time from web/;
// tools/setup.sh installs what it needs): write_view_page works.
bool built_with_viewer();

// What write_view_page drew.
struct ViewPageReport {
  size_t shown_faces = 0;         // the faces of the mesh the page shows
  bool simplified = false;        // a copy simplified towards ViewPageOptions::max_faces
  // shown_faces <= max_faces; false when the simplifier could go no further (a closed
  // surface keeps at least 4 faces; refused collapses), which the page's note then says.
  bool within_max_faces = true;
};

// Writes one self-contained HTML page (no network needed to open it): the mesh coloured by
// `saliency` (one value per vertex) on the pictures' colour scale with its colour bar and
// scale, orbit controls from `camera` (best_viewpoint's Viewpoint::camera for this mesh),
// a toggle between saliency, plain shading and wireframe, and options.stats. The mesh is
// embedded as a GLB (write_gltf's, in local coordinates), three.js (MIT licence, kept in
// the page) inline. The title, statistics and note are shown as their bytes are (no markup,
// bytes that are not UTF-8 and bidirectional controls escaped). Atomic as write_ply. Error
// when built without the viewer.
ViewPageReport write_view_page(const std::string& path, const Mesh& mesh, const std::vector<double>& saliency,
                               const ViewCamera& camera, const ViewPageOptions& options = {});

// An 8-bit RGB image, rows top to bottom.
struct Image {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;  // 3 bytes per pixel

  Image() = default;
  Image(int w, int h, uint8_t r = 255, uint8_t g = 255, uint8_t b = 255);
  uint8_t* at(int x, int y) { return &rgb[(size_t(y) * size_t(width) + size_t(x)) * 3]; }
  const uint8_t* at(int x, int y) const { return &rgb[(size_t(y) * size_t(width) + size_t(x)) * 3]; }
};


struct RenderStyle {
  int size = 512;            // square image side in pixels, 16..8192
  double margin = 1.05;      // the image frames the mesh's projected extent times this, >= 1
  bool smooth = true;        // interpolated vertex normals; false: flat faces
  bool edges = false;        // darken the edges of triangles at least 4 px tall
  int supersample = 2;       // anti-aliasing: rendered at this many times the size, averaged; 1..4
  UpAxis up = UpAxis::Y;     // the mesh axis that points up in the picture (see UpAxis)
  ColorRange range;          // the colour scale's ends (see ColorRange)
  uint8_t background[3] = {255, 255, 255};
  uint8_t base[3] = {190, 190, 190};  // surface colour when there are no vertex colours
};

// The mesh seen from `view` (orthographic, square image framed by the mesh's projected
// extent in that view, centred), Lambert-shaded, coloured by `score` (one value per vertex,
// may be null: plain grey) on the colour scale of style.range. Only the mesh: the CLI's
// pictures add a title line and a colour bar. Throws Error for a style out of range.
Image render_view(const Mesh& mesh, const std::vector<double>* score, const ViewAngles& view,
                  const RenderStyle& style = {});

// The same from a camera made by view_camera (or best_viewpoint) for this mesh: the picture
// of camera.view with camera.up_axis as the up axis (style.up is not read), pixel for pixel
// that of render_view(mesh, score, camera.view, style with up = camera.up_axis). (Its own
// name: an overload of render_view would make render_view(mesh, s, {}, style) ambiguous.)
Image render_camera_view(const Mesh& mesh, const std::vector<double>* score, const ViewCamera& camera,
                         const RenderStyle& style = {});

// Writes a PNG (atomically, as write_ply). Throws Error naming the file.
void write_png(const std::string& path, const Image& image);

// ------------------------------------------------------------------------------------------
// One request: what a run asks for, from any front end

// What the views and pictures of a run are coloured by and search for.
enum class Score {
  Saliency,  // S (computed, or read back)
  Curvature  // |H|, the mean curvature's magnitude: the paper's baseline
};

// "saliency" or "curvature"; throws Error on anything else.
Score parse_score(const std::string& name);

// Options of a request that do not combine (e.g. --lod with --memory-limit): raised by
// check_request() before any work. An Error; the command-line tool exits 2 for it, as for
// any usage error.
struct RequestError : Error {
  using Error::Error;
};

// What one run asks for: an input, how its S is had, and what to make of it. Every front
// end fills one and calls run_request(): `meshsal saliency`, `simplify`, `view`, `render`,
// `viewpoint`, each model of `batch`, and Python. The defaults below are every command's
// defaults, and check_request() holds the rules for what combines, so that a new option or
// output lands once for all of them.
struct Request {
  // The input: the mesh file `input`; or, when `mesh` is given (not owned; it must outlive
  // the call), that mesh as read plainly (LoadOptions::attributes off) and `input` only
  // names it (messages, pages, the check that no output replaces it). `attributed`: the
  // same file read with attributes, when the caller has it (batch reads ahead).
  std::string input;
  const Mesh* mesh = nullptr;
  const Mesh* attributed = nullptr;
  LoadOptions load;  // limits of reading (attributes is decided by the outputs: below)

  // S: computed with `saliency` (its defaults are every command's), or read back from
  // `saliency_from` (a PLY or glTF that keeps S: load_saliency); with saliency_from_input,
  // from the input itself when it holds S (a saliency PLY given to `render` or `view`).
  // Every front end's default backend is Auto (a GPU when there is one), not the CPU that
  // a bare SaliencyOptions names.
  SaliencyOptions saliency = [] {
    SaliencyOptions o;
    o.backend = Backend::Auto;
    return o;
  }();
  std::string saliency_from;
  bool saliency_from_input = false;
  // Or S given by the caller (not owned): one value per vertex of `mesh`, which must then
  // be given too (Python's saliency= argument).
  const std::vector<double>* saliency_values = nullptr;
  // What the views and pictures show (S, or |H| for the paper's comparison).
  Score score = Score::Saliency;

  // The outputs; "" = not made. Each is checked before any work (check_outputs: the
  // extension its writer takes, writable, distinct, never an input) with its side files.
  // saliency_output: the mesh with S, in any format (mesh_format: PLY and glTF keep the
  // value, OBJ and OFF its colours, STL is refused); a PLY holds the positions and faces
  // as read (no attributes: SPEC section 4), the others carry the input's attributes and
  // materials. dump_scales: also the curvature and raw maps (PLY, glTF).
  std::string saliency_output;
  bool dump_scales = false;
  // simplified_output: the mesh simplified toward `simplify`'s target (faces, ratio or
  // error), its attributes and materials carried, S carried as a PLY's `quality` or a
  // glTF's _SALIENCY where the format keeps it. tiles > 1: simplify_mesh_tiled.
  std::string simplified_output;
  SimplifyOptions simplify;
  unsigned tiles = 0;
  // lod_output: a chain of levels of detail, `lod` (parse_lod_levels), S computed once and
  // carried (write_lod: one glTF with MSFT_lod, or a file per level).
  std::string lod_output;
  std::vector<SimplifyOptions> lod;
  // Make the simplified mesh (with a target in `simplify`) and the levels (with `lod`) even
  // where no output file is named: they come back in the result (Python).
  bool simplify_in_memory = false;
  // The weights of simplified_output and lod_output: a named weighting, its parameters in
  // weight_options (weight_preset(weighting) unless the caller changed them).
  Weighting weighting = kDefaultWeighting;
  SaliencyWeightOptions weight_options = weight_preset(kDefaultWeighting);
  // Or the weights W themselves, one per vertex of `mesh` (not owned): no S is had for
  // them (Python's weights= array).
  const std::vector<double>* vertex_weights = nullptr;
  // memory_limit > 0: the mesh is never held whole (saliency_file, simplify_file; PLY
  // outputs only, no views).
  OutOfCoreOptions out_of_core;

  // The view: searched (best_viewpoint with `viewpoint`) when find_view, else `view`.
  // page_output: the viewer page (write_view_page) from the best view, which it needs.
  // picture_output: the picture (PNG) of that view, titled and with its colour bar (`grey`:
  // shaded only; `compare`: two more meshes beside it, PLAIN and SALIENT, coloured by their
  // distance to the input). map_output: the view map (with viewpoint.views directions,
  // 2000 when 0), map_width pixels wide.
  bool find_view = false;
  ViewpointOptions viewpoint = [] {
    ViewpointOptions o;
    o.backend = Backend::Auto;
    return o;
  }();
  ViewAngles view;
  std::string page_output;
  ViewPageOptions page;
  std::string picture_output;
  RenderStyle style;
  bool grey = false;
  std::vector<std::string> compare;
  std::string map_output;
  int map_width = 720;

  // What messages call the outputs: "-o" (the command line's option), "the output" (Python).
  std::string output_option = "-o";

  // Called once the input is read (before S; out of core, before the file is streamed):
  // where processes that share the run meet (the command line's MPI ranks). May be empty.
  std::function<void()> on_read;
};

// What a request made.
struct RequestResult {
  Mesh mesh;                       // the input as read (plainly, or with attributes when only those were needed)
  LoadReport load;                 // what reading it left out (LoadReport::unread), STL welding
  double load_seconds = 0;
  SaliencyResult saliency;         // S (computed; read back: only saliency and is_point filled)
  std::string saliency_source;     // "computed" or the file S was read from
  std::vector<double> score;       // what the views showed (S, or |H|), per vertex
  OutOfCoreReport out_of_core;     // saliency_output under a memory limit
  // simplified_output: its mesh (empty out of core), report, the weights' alpha and the
  // device that computed the S they came from ("" when S was read).
  Mesh simplified;
  SimplifyReport simplify;
  double alpha = 0;
  std::string weights_device;
  double weights_seconds = 0;  // having S (computed or read) and the weights from it
  OutOfCoreSimplifyReport simplify_out_of_core;
  std::vector<LodLevel> lod;       // lod_output's levels
  std::vector<std::string> lod_files;  // the files they went to (one GLB, or one per level)
  Viewpoint viewpoint;             // find_view's result
  ViewAngles view;                 // the view the picture shows
  ViewPageReport page;
  int picture_width = 0, picture_height = 0;
  double visible_score = 0, visible_total = 0;  // the picture's view: U and the score's sum
  // Every file written, in the order written (side files after their main file), and the
  // notes a front end shows once each: what an output cannot hold (mesh_output_note), a
  // face target missed, S read from the input.
  std::vector<std::string> outputs;
  std::vector<std::string> notes;
  // Wall time of each step that ran, in order: "read", "saliency output", "views",
  // "simplify", "levels of detail" (out of core: "saliency output", "simplify").
  std::vector<StageTime> steps;
  double seconds = 0;
};

// The saliency output of `meshsal saliency`: S of `result` (computed for `mesh`) written
// with the mesh in the format the name gives (write_saliency_ply, write_gltf, write_mesh),
// and with dump_scales its curvature and raw maps beside it (curvature, saliency_raw_0..;
// PLY and glTF keep them).
void write_saliency(const std::string& path, const Mesh& mesh, const SaliencyResult& result, bool dump_scales);

// Throws RequestError when the request's options do not combine (naming them as the
// command-line options do: "--lod runs in memory, in one piece: not with --tiles or
// --memory-limit"), or Error when one is out of range or an output cannot be written
// (check_outputs); before any file is read.
void check_request(const Request& request);

// Runs the request: check_request, then reads the input (once plainly and once with
// attributes where outputs need both, as each command always has), has S (computed or
// read back, once for every output), makes every output asked for and writes it. Progress,
// notices and cancellation go through request.saliency (progress, notice, cancel) and
// request.viewpoint. Throws Error (RequestError for the combinations) or Cancelled.
RequestResult run_request(const Request& request);

// ------------------------------------------------------------------------------------------
// Devices

struct DeviceInfo {
  int index = 0;                    // the `device` option's value for this device
  std::string name;
  std::string type;                 // "discrete", "integrated", "virtual", "cpu", "other"
  uint64_t device_local_bytes = 0;  // largest device-local heap
  std::string api_version;          // "1.3.239"
  bool has_compute = false;         // a queue family with compute
};

// True when this build has the Vulkan backend (linked with meshsal::gpu).
bool built_with_vulkan();

// The Vulkan devices. Throws Error when built without Vulkan or no driver is installed.
std::vector<DeviceInfo> list_devices();

// An open Vulkan device (instance, logical device, compute queue and, as calls use them,
// its compiled kernels and staging area), held by the caller: pass it as
// SaliencyOptions::session or ViewpointOptions::session and every call runs on it without
// opening the device or compiling its kernels again. The device is released when the
// Device is destroyed or closed (a call still running on it, or a view search's scorer,
// keeps it until that call returns). Calls given one Device from several threads run on it
// one at a time (each waits for the previous); calls of one thread must not nest on it (a
// progress callback calling compute_saliency with the same Device waits forever).
//
// Without a session, Backend::Gpu and Backend::Auto use a process-wide cache instead (one
// open device per index, kept until release_cached_devices() or the end of the process):
// the command-line tool relies on it; library callers who want control use a Device.
class Device {
 public:
  // Opens device `index` of list_devices(); -1 picks as Backend::Gpu does (the best
  // device: discrete, integrated, virtual, then a CPU device such as lavapipe). Throws Error
  // when built without Vulkan, the index does not exist (below -1, or not listed) or the
  // device cannot be opened.
  explicit Device(int index = -1);
  ~Device();
  Device(Device&& other) noexcept;
  Device& operator=(Device&& other) noexcept;
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  // What was opened (its `index` is the list_devices() index). Still readable after close().
  const DeviceInfo& info() const { return info_; }
  // Releases the device now (when the calls running on it return). A closed Device given
  // to a call is an Error. Idempotent.
  void close();
  bool is_open() const;

  // The open device, for the library's backend (opaque here); null once closed.
  std::shared_ptr<void> handle() const;

 private:
  std::shared_ptr<void> handle_;
  DeviceInfo info_;
};

// Closes the devices the process-wide cache holds (calls without a session opened them);
// one a call is using now closes when that call ends. The next such call opens its device
// again. Does nothing in a build without Vulkan. The cache is also closed at exit.
void release_cached_devices();

// ---------------------------------------------------------------------------------------
// The C heap: a choice for programs, never made by the library itself (it is process-wide).
// ---------------------------------------------------------------------------------------

// A saliency run allocates and frees arrays of tens of MB stage after stage. glibc maps
// each large block afresh and gives it back when freed, so every stage pays the page
// faults again (igea_loop2 --method fast: 310,000 faults, 2.6 s of system time). on = true
// keeps freed blocks in the heap for the next stage (110,000 faults, 1.0 s; peak memory
// about 4% higher): large blocks come from the heap (M_MMAP_MAX 0) and its free top is not
// given back (M_TRIM_THRESHOLD INT_MAX). on = false sets glibc's documented default values
// back (M_MMAP_MAX 65536, M_TRIM_THRESHOLD 128 KiB; glibc's dynamic mmap threshold stays
// off once either was set). Returns false, changing nothing, on other C libraries. The
// meshsal command calls it at start-up; Python programs call meshsal.keep_freed_memory().
bool keep_freed_memory_for_reuse(bool on = true);

}  // namespace meshsal
