// meshsal: the model's own coordinates of a vertex (Mesh::origin, Mesh::source_positions),
// and carrying that frame from a mesh to one derived from it (simplified, subdivided).
#pragma once
#include <cstdint>
#include <vector>

#include "meshsal/meshsal.h"

namespace meshsal {

// float(x - origin): the one rounding from the model's coordinates to local ones. The
// loaders, make_mesh and the "was it moved?" test of model_position all use it.
inline float local_coordinate(double x, double origin) { return static_cast<float>(x - origin); }

// Model coordinates of a vertex from its source position as read (null: none kept) and its
// local position: the source while the local position is still the source's rounding (no
// computation moved it), else origin + position in double. Writers that stream vertices
// (out of core) call it; model_position() is it on a Mesh.
inline void model_coordinates(const double* source, const float* local, const double origin[3], double out[3]) {
  if (source && local_coordinate(source[0], origin[0]) == local[0] &&
      local_coordinate(source[1], origin[1]) == local[1] && local_coordinate(source[2], origin[2]) == local[2]) {
    for (int k = 0; k < 3; ++k) out[k] = source[k];
    return;
  }
  // An origin of 0 is not added: -0 + 0 would be +0, and a hand-made mesh is written as it is.
  for (int k = 0; k < 3; ++k) out[k] = origin[k] == 0 ? double(local[k]) : double(local[k]) + origin[k];
}

// Vertex v's model coordinates (model_coordinates with the mesh's source positions, if kept).
inline void model_position(const Mesh& mesh, size_t v, double out[3]) {
  const bool sourced = mesh.source_positions.size() == mesh.positions.size();
  model_coordinates(sourced ? &mesh.source_positions[3 * v] : nullptr, &mesh.positions[3 * v], mesh.origin, out);
}

// set_model_positions (meshsal.h) in two steps, for a loader that makes the positions
// before it has read the triangles (io/read_observer.h: so that work on them can start
// while it reads the rest). Positions made early take set_model_positions' rule as if
// every vertex were a mesh point, the centre of all the vertices' box: nearly always the
// same origin as the mesh points' box gives.
struct EarlyPositions {
  double origin[3] = {0, 0, 0};
  size_t vertex_count = 0;
  bool exact = false;  // every local position gives its source back
};
// mesh.positions from `xyz` (3 doubles a vertex) at the origin it returns; the origin,
// the source positions and everything else of the mesh are left as they are.
EarlyPositions early_model_positions(Mesh& mesh, const double* xyz, size_t vertex_count);
// The origin set_model_positions gives `xyz` with mesh.triangles (the mesh points' box).
void model_origin(const Mesh& mesh, const double* xyz, size_t vertex_count, double origin[3]);
// Whether the positions `early` made are the ones `origin` gives.
bool keeps_early_positions(const EarlyPositions& early, size_t vertex_count, const double origin[3]);
// The rest of set_model_positions at `origin`: the positions made, or kept where `early`
// made them (null: none; given only where keeps_early_positions says they are origin's),
// and the source positions kept or dropped.
void set_model_positions_at(Mesh& mesh, const double* xyz, size_t vertex_count, const double origin[3],
                            const EarlyPositions* early);

// Gives `out` the frame of `in`: its origin, double_positions and, where `in` keeps source
// positions, each out vertex i the source of in's vertex from[i] (UINT32_MAX: a vertex of
// out's own, whose source is its origin + position). out.positions must be set.
void carry_model_frame(const Mesh& in, const std::vector<uint32_t>& from, Mesh& out);

// `mesh` with its positions re-expressed relative to `origin` (two meshes loaded from
// separate files have their own origins; distances between them need one frame).
Mesh in_frame(const Mesh& mesh, const double origin[3]);

}  // namespace meshsal
