// meshsal: local coordinates (SPEC section 6): set_model_positions, model_positions,
// positions_need_double.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <mutex>

#include "core/mesh_points.h"
#include "core/model_frame.h"
#include "core/parallel.h"
#include "meshsal/meshsal.h"

namespace meshsal {

namespace {

// The centre of the box of the vertices `used` marks (null: all). Halves added, so 1e308
// does not overflow; non-finite values are left out, for validate_mesh to name.
void box_centre(const double* xyz, size_t vertex_count, const uint8_t* used, double origin[3]) {
  const BoundingBox box = bounding_box(xyz, vertex_count, used);
  for (int k = 0; k < 3; ++k) origin[k] = box.min[k] <= box.max[k] ? box.min[k] / 2 + box.max[k] / 2 : 0.0;
}

// mesh.positions = local_coordinate(xyz, origin); true when each one gives its source
// back exactly (origin + local == source: no source need be kept).
bool convert_positions(Mesh& mesh, const double* xyz, size_t vertex_count, const double origin[3]) {
  mesh.positions.resize(3 * vertex_count);
  std::atomic<bool> exact{true};
  float* out = mesh.positions.data();
  parallel_for(vertex_count, 0, 1 << 16, [&](size_t begin, size_t end) {
    bool mine = true;
    for (size_t i = 3 * begin; i < 3 * end; ++i) {
      const double o = origin[i % 3];
      const float local = local_coordinate(xyz[i], o);
      out[i] = local;
      mine &= double(local) + o == xyz[i] || !std::isfinite(xyz[i]);
    }
    if (!mine) exact.store(false, std::memory_order_relaxed);
  });
  return exact.load();
}

}  // namespace

void set_model_positions(Mesh& mesh, const double* xyz, size_t vertex_count) {
  double origin[3];
  model_origin(mesh, xyz, vertex_count, origin);
  set_model_positions_at(mesh, xyz, vertex_count, origin, nullptr);
}

void model_origin(const Mesh& mesh, const double* xyz, size_t vertex_count, double origin[3]) {
  // The centre of the mesh points' bounding box (every vertex when no triangle is usable
  // yet: validate_mesh refuses such a mesh anyway).
  bool any = false;
  const std::vector<uint8_t> used = referenced_mask(mesh.triangles.data(), mesh.triangles.size(), vertex_count, &any);
  box_centre(xyz, vertex_count, any ? used.data() : nullptr, origin);
}

bool keeps_early_positions(const EarlyPositions& early, size_t vertex_count, const double origin[3]) {
  // Bit for bit: a zero's sign changes what -0 - origin gives.
  return early.vertex_count == vertex_count && std::memcmp(early.origin, origin, sizeof early.origin) == 0;
}

void set_model_positions_at(Mesh& mesh, const double* xyz, size_t vertex_count, const double origin[3],
                            const EarlyPositions* early) {
  for (int k = 0; k < 3; ++k) mesh.origin[k] = origin[k];
  const bool exact = early ? early->exact : convert_positions(mesh, xyz, vertex_count, origin);
  if (exact) mesh.source_positions.clear();
  else if (mesh.source_positions.data() != xyz) mesh.source_positions.assign(xyz, xyz + 3 * vertex_count);
}

EarlyPositions early_model_positions(Mesh& mesh, const double* xyz, size_t vertex_count) {
  EarlyPositions early;
  early.vertex_count = vertex_count;
  box_centre(xyz, vertex_count, nullptr, early.origin);
  early.exact = convert_positions(mesh, xyz, vertex_count, early.origin);
  return early;
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
