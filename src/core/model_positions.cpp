// meshsal: local coordinates (SPEC section 6): set_model_positions, model_positions,
// positions_need_double.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>

#include "core/mesh_points.h"
#include "core/model_frame.h"
#include "core/parallel.h"
#include "meshsal/meshsal.h"

namespace meshsal {

void set_model_positions(Mesh& mesh, const double* xyz, size_t vertex_count) {
  // The origin: the centre of the mesh points' bounding box (every vertex when no triangle
  // is usable yet: validate_mesh refuses such a mesh anyway). Halves added, so 1e308 does
  // not overflow; non-finite values are left out, for validate_mesh to name.
  bool any = false;
  const std::vector<uint8_t> used = referenced_mask(mesh.triangles.data(), mesh.triangles.size(), vertex_count, &any);
  const BoundingBox box = bounding_box(xyz, vertex_count, any ? used.data() : nullptr);
  for (int k = 0; k < 3; ++k)
    mesh.origin[k] = box.min[k] <= box.max[k] ? box.min[k] / 2 + box.max[k] / 2 : 0.0;

  mesh.positions.resize(3 * vertex_count);
  std::atomic<bool> exact{true};
  float* out = mesh.positions.data();
  parallel_for(vertex_count, 0, 1 << 16, [&](size_t begin, size_t end) {
    bool mine = true;
    for (size_t i = 3 * begin; i < 3 * end; ++i) {
      const double o = mesh.origin[i % 3];
      const float local = local_coordinate(xyz[i], o);
      out[i] = local;
      mine &= double(local) + o == xyz[i] || !std::isfinite(xyz[i]);
    }
    if (!mine) exact.store(false, std::memory_order_relaxed);
  });
  if (exact.load()) mesh.source_positions.clear();
  else if (mesh.source_positions.data() != xyz) mesh.source_positions.assign(xyz, xyz + 3 * vertex_count);
}

std::vector<double> model_positions(const Mesh& mesh) {
  std::vector<double> out(mesh.positions.size());
  for (size_t v = 0; v < mesh.vertex_count(); ++v) model_position(mesh, v, &out[3 * v]);
  return out;
}

bool positions_need_double(const Mesh& mesh) {
  if (mesh.double_positions) return true;
  // Cheap exits: at the origin with no source, model coordinates are the floats themselves.
  if (mesh.source_positions.empty() && mesh.origin[0] == 0 && mesh.origin[1] == 0 && mesh.origin[2] == 0)
    return false;
  // The largest move float makes of a model coordinate; none (a float file's sources) needs
  // no tolerance, so the mesh points' box is only taken when something moved.
  double largest = 0;
  std::mutex lock;
  parallel_for(mesh.vertex_count(), 0, 1 << 16, [&](size_t begin, size_t end) {
    double mine = 0;
    for (size_t v = begin; v < end; ++v) {
      double p[3];
      model_position(mesh, v, p);
      for (int k = 0; k < 3; ++k) mine = std::max(mine, std::fabs(double(float(p[k])) - p[k]));  // NaN skipped
    }
    std::lock_guard<std::mutex> hold(lock);
    largest = std::max(largest, mine);
  });
  if (!(largest > 0)) return false;
  const std::vector<uint8_t> used = referenced_mask(mesh.triangles.data(), mesh.triangles.size(), mesh.vertex_count());
  const BoundingBox box = bounding_box(mesh.positions.data(), mesh.vertex_count(), used.data());
  double d2 = 0;
  for (int k = 0; k < 3; ++k)
    if (box.min[k] <= box.max[k]) d2 += (box.max[k] - box.min[k]) * (box.max[k] - box.min[k]);
  return largest > 1e-7 * std::sqrt(d2);
}

}  // namespace meshsal
