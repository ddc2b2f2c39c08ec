// meshsal (internal): UV seams of a mesh stored as split vertices, as PLY files (and most
// exporters) store them: vertices at one position that differ in their attributes.
#pragma once
#include "meshsal/meshsal.h"

namespace meshsal {

// Sets mesh.position_vertex (see Mesh) when some vertices share exactly one position (their
// model coordinates, model_position, equal in double; -0 equal to +0) and differ in at least one attribute value: every vertex of
// such a group then points at the group's lowest vertex, every other vertex at itself.
// Leaves it empty when there is no such group: no attributes, no shared positions, or only
// duplicates that agree in every attribute (those stay separate vertices, as in the file).
void find_seam_twins(Mesh& mesh);

// The same for every group of vertices at one position, whatever their attributes: glTF
// primitives (and the instances of a scene) meet at duplicated vertices that are one
// surface.
void link_position_twins(Mesh& mesh);

}  // namespace meshsal
