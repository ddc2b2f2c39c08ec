// meshsal: reading meshes (OBJ, PLY, OFF, any of them .gz) and writing result PLYs.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "meshsal/mesh.h"

namespace meshsal {

// Scalar vertex properties found in a PLY besides x,y,z (e.g. "quality"), as floats.
using VertexProperties = std::map<std::string, std::vector<float>>;

// Bounds on what loading may hold in memory.
struct LoadOptions {
  // The most bytes a gzipped file may inflate to, and a pipe (FIFO) may deliver. 0 means
  // the environment variable MESHSAL_MAX_INPUT when it is set (bytes, with an optional
  // K, M or G suffix), else the default: for a gzipped PLY or OFF, 64 MiB + 64 times the
  // bytes its header's counts need; for a gzipped OBJ (no header) and for a pipe, 1 GiB.
  uint64_t max_input_bytes = 0;
};

// Loads OBJ / PLY (ascii, binary LE/BE) / OFF, optionally gzipped, chosen by extension
// (.obj .ply .off, plus .gz). Polygons are fan-triangulated. The result is validated
// (validate_mesh). Throws Error with a one-line message that names `path` on any problem.
// If `properties` is given, scalar PLY vertex properties are returned there.
// Only regular files and FIFOs are read (devices such as /dev/zero are refused).
Mesh load_mesh(const std::string& path, VertexProperties* properties = nullptr,
               const LoadOptions& options = {});

// The same from bytes in memory (the fuzz targets use it): `name` picks the format by its
// extension, as a path does, and starts every error message.
Mesh load_mesh_bytes(std::string_view bytes, const std::string& name,
                     VertexProperties* properties = nullptr, const LoadOptions& options = {});

// Throws Error when the mesh is empty, an index is out of range, a coordinate is NaN/Inf
// or no triangle has non-zero area.
void validate_mesh(const Mesh& mesh);

struct PlyFloatProperty {
  std::string name;
  const std::vector<double>* values;  // one per vertex
};

// Writes binary little-endian PLY: positions, the given float properties, optional
// uchar red/green/blue (3 per vertex) and the triangles. Written to a temporary file
// in the same folder and renamed, so a failure never leaves a half-written file.
void write_ply(const std::string& path, const Mesh& mesh,
               const std::vector<PlyFloatProperty>& properties,
               const std::vector<uint8_t>* rgb = nullptr);

// Writes OBJ (v/f lines) the same atomic way.
void write_obj(const std::string& path, const Mesh& mesh);

}  // namespace meshsal
