// meshsal: split vertices at UV seams found by position (seam_twins.h).
#include "io/seam_twins.h"

#include <algorithm>
#include <numeric>

#include "core/model_frame.h"
#include "io/mesh_io_internal.h"

namespace meshsal {

namespace {

// A vertex by its position's bits (-0 read as +0): sorting these puts each group of
// vertices at one exact position together, lowest index first.
struct Keyed {
  uint64_t key[3];
  uint32_t v;
  bool same_place(const Keyed& o) const { return key[0] == o.key[0] && key[1] == o.key[1] && key[2] == o.key[2]; }
  bool operator<(const Keyed& o) const {
    for (int k = 0; k < 3; ++k)
      if (key[k] != o.key[k]) return key[k] < o.key[k];
    return v < o.v;
  }
};

bool same_attributes(const Mesh& mesh, uint32_t a, uint32_t b) {
  for (const VertexAttribute& at : mesh.attributes)
    if (!(at.values[a] == at.values[b])) return false;
  return true;
}

}  // namespace

namespace {

// Links each group of vertices at one position; `every_group`: also groups that agree in
// every attribute (else only those that differ somewhere).
void link_groups(Mesh& mesh, bool every_group) {
  mesh.position_vertex.clear();
  const size_t n = mesh.vertex_count();
  if ((!every_group && mesh.attributes.empty()) || n < 2) return;
  std::vector<Keyed> sorted(n);
  for (size_t v = 0; v < n; ++v) {
    sorted[v].v = uint32_t(v);
    double p[3];
    model_position(mesh, v, p);  // as read: two values one float apart stay apart
    for (int k = 0; k < 3; ++k) sorted[v].key[k] = position_bits(p[k]);
  }
  std::sort(sorted.begin(), sorted.end());
  std::vector<uint32_t> pv;
  for (size_t i = 0; i < n;) {
    size_t j = i + 1;
    while (j < n && sorted[j].same_place(sorted[i])) ++j;
    bool split = every_group && j > i + 1;
    for (size_t k = i + 1; k < j && !split; ++k) split = !same_attributes(mesh, sorted[i].v, sorted[k].v);
    if (split) {
      if (pv.empty()) {
        pv.resize(n);
        std::iota(pv.begin(), pv.end(), 0u);
      }
      for (size_t k = i; k < j; ++k) pv[sorted[k].v] = sorted[i].v;
    }
    i = j;
  }
  mesh.position_vertex = std::move(pv);
}

}  // namespace

void find_seam_twins(Mesh& mesh) { link_groups(mesh, false); }

void link_position_twins(Mesh& mesh) { link_groups(mesh, true); }

}  // namespace meshsal
