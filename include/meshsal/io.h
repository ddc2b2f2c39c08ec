// meshsal public interface: reading and writing mesh files, their formats, the output check.
// Part of meshsal.h (which includes every part); the conventions at the top of
// meshsal.h hold for every function here.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "meshsal/mesh.h"

namespace meshsal {

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
// one-line message that names `path` on any problem. Only regular files and FIFOs are read
// (devices such as /dev/zero are refused).
Mesh load_mesh(const std::string& path, const LoadOptions& options = {});

// What read_mesh returns: the mesh and what else the file told.
struct LoadedMesh {
  Mesh mesh;
  // A PLY's scalar vertex properties besides x,y,z (e.g. "quality"), whatever
  // LoadOptions::attributes says; empty for the other formats.
  VertexProperties properties;
  LoadReport report;
};

// load_mesh with the file's scalar properties and the report of what loading did.
LoadedMesh read_mesh(const std::string& path, const LoadOptions& options = {});

// The same two from bytes in memory: `name` picks the format by its extension, as a path
// does, and starts every error message.
Mesh load_mesh_bytes(std::string_view bytes, const std::string& name, const LoadOptions& options = {});
LoadedMesh read_mesh_bytes(std::string_view bytes, const std::string& name, const LoadOptions& options = {});

struct PlyFloatProperty {
  std::string name;
  const std::vector<double>* values;  // one per vertex, written as float
};

// Writes binary little-endian PLY: positions, the given float properties, uchar
// red/green/blue when `rgb` is not empty (3 per vertex) and the triangles. Written to a fresh temporary file in the
// same folder and renamed, so a failure never leaves a half-written file in place.
void write_ply(const std::string& path, const Mesh& mesh,
               const std::vector<PlyFloatProperty>& properties,
               const std::vector<uint8_t>& rgb = {});

// Writes OBJ (v and f lines), the same atomic way.
void write_obj(const std::string& path, const Mesh& mesh);

// Writes the saliency PLY of `meshsal saliency` (SPEC section 4): write_ply with the
// property quality = S, then `extra` (e.g. curvature and the raw maps of --dump-scales), and
// red/green/blue = the colour scale of S over the mesh points (the pictures' scale:
// minimum..maximum of S, square-root position). The mesh points are `is_point` when given
// (SaliencyResult::is_point, one per vertex) when not empty, else the vertices a triangle uses. The mesh's
// own attributes come before them, unless one of these replaces them.
void write_saliency_ply(const std::string& path, const Mesh& mesh, const std::vector<double>& saliency,
                        const std::vector<PlyFloatProperty>& extra = {},
                        const std::vector<uint8_t>& is_point = {});

struct ColorRange;  // the pictures' colour scale (view.h)

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
// One mesh, with its saliency when `saliency` is not empty (one value per vertex).
void write_gltf(const std::string& path, const Mesh& mesh, const std::vector<double>& saliency = {});

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
// mesh's own), STL (binary; positions only); S is written when `saliency` is not empty (one
// value per vertex). S given for an STL is an Error naming the formats that keep it, as is
// an unknown suffix. Atomic as write_ply.
void write_mesh(const std::string& path, const Mesh& mesh, const std::vector<double>& saliency = {});

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

}  // namespace meshsal
