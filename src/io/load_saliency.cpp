// meshsal: S read back from a file that keeps its value (PLY quality, glTF _SALIENCY), held
// to the mesh it is for.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/model_frame.h"
#include "io/mesh_io_internal.h"
#include "meshsal/meshsal.h"

namespace meshsal {
namespace {

// The mesh's own vertices when it is an OBJ split at seams: the file's v lines first, the
// twins appended (load_obj_text), so a saliency file of the same OBJ has only the first.
size_t leading_positions(const Mesh& mesh) {
  const std::vector<uint32_t>& pv = mesh.position_vertex;
  size_t n = 0;
  while (n < pv.size() && pv[n] == n) ++n;
  return n;
}

// Throws unless vertex v of `file` lies where vertex v of `mesh` does, for v < n (in the
// model's own coordinates: each file has its own origin), within 1e-6 of the diagonal.
void check_positions(const std::string& path, const Mesh& file, const Mesh& mesh, size_t n) {
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (size_t i = 0; i < 3 * n; ++i) {
    lo[i % 3] = std::min(lo[i % 3], double(mesh.positions[i]));
    hi[i % 3] = std::max(hi[i % 3], double(mesh.positions[i]));
  }
  const double diag = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                (hi[2] - lo[2]) * (hi[2] - lo[2]));
  const double tol = 1e-6 * diag;
  for (size_t v = 0; v < n; ++v) {
    double a[3], b[3];
    model_position(file, v, a);
    model_position(mesh, v, b);
    for (int k = 0; k < 3; ++k)
      if (!(std::fabs(a[k] - b[k]) <= tol)) {
        char buf[256];
        std::snprintf(buf, sizeof buf, "vertex %zu is at (%.9g, %.9g, %.9g) there but at (%.9g, %.9g, %.9g) in the mesh",
                      v, a[0], a[1], a[2], b[0], b[1], b[2]);
        throw Error("saliency file '" + path + "' belongs to another mesh: " + buf);
      }
  }
}

}  // namespace

std::vector<double> load_saliency(const std::string& path, const Mesh& mesh) {
  std::string name = path;
  if (name.size() > 3 && (name.compare(name.size() - 3, 3, ".gz") == 0 || name.compare(name.size() - 3, 3, ".GZ") == 0))
    name.resize(name.size() - 3);
  const MeshFormat* format = mesh_format(name);
  if (format && format->saliency != SaliencyKept::Value)
    throw Error("'" + path + "' cannot hold saliency values (" + format->name +
                (format->saliency == SaliencyKept::Colors ? " keeps S only as colours" : " keeps no S") +
                "): read S from the .ply, .gltf or .glb that `meshsal saliency` writes");
  LoadOptions options;
  options.attributes = true;  // a glTF's _SALIENCY, a PLY's quality
  const Mesh file = load_mesh(path, options);
  const VertexAttribute* s = find_attribute(file, kSaliencyAttribute);
  if (!s)
    throw Error("'" + path + "' has no per-vertex `quality` property (nor a glTF `_SALIENCY`; write it with `meshsal saliency`)");
  const size_t n = mesh.vertex_count();
  // An OBJ split at its seams: S of its positions, the twins taking their position's.
  const size_t own = file.vertex_count() < n && !mesh.position_vertex.empty() ? leading_positions(mesh) : n;
  if (file.vertex_count() != own)
    throw Error("saliency file '" + path + "' has " + std::to_string(file.vertex_count()) + " vertices but the mesh has " +
                std::to_string(own));
  check_positions(path, file, mesh, own);
  std::vector<double> out(n);
  for (size_t v = 0; v < own; ++v) {
    const float x = s->values[v];
    if (!std::isfinite(x))
      throw Error("saliency file '" + path + "': the quality of vertex " + std::to_string(v) + " is not finite");
    if (x < 0)  // every command reads S through here: one rule for all of them
      throw Error("saliency file '" + path + "': the quality of vertex " + std::to_string(v) + " is " +
                  std::to_string(x) + ", but a saliency is >= 0 (not a file `meshsal saliency` wrote?)");
    out[v] = x;
  }
  for (size_t v = own; v < n; ++v) out[v] = out[mesh.position_vertex[v]];
  return out;
}

std::vector<double> load_saliency_ply(const std::string& path, const Mesh& mesh) { return load_saliency(path, mesh); }

}  // namespace meshsal
