// meshsal: reading meshes (OBJ, PLY, OFF, any of them .gz) and writing result PLYs.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "meshsal/mesh.h"

namespace meshsal {

// Scalar vertex properties found in a PLY besides x,y,z (e.g. "quality"), as floats.
using VertexProperties = std::map<std::string, std::vector<float>>;

// Loads OBJ / PLY (ascii, binary LE/BE) / OFF, optionally gzipped, chosen by extension
// (.obj .ply .off, plus .gz). Polygons are fan-triangulated. The result is validated
// (validate_mesh). Throws Error with a one-line message on any problem.
// If `properties` is given, scalar PLY vertex properties are returned there.
Mesh load_mesh(const std::string& path, VertexProperties* properties = nullptr);

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
