#include "core/mesh_points.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>

#include "core/parallel.h"
#include "meshsal/meshsal.h"

namespace meshsal {

std::vector<uint8_t> referenced_vertices(const Mesh& mesh) {
  return referenced_mask(mesh.triangles.data(), mesh.triangles.size(), mesh.vertex_count());
}

std::vector<uint8_t> referenced_mask(const uint32_t* indices, size_t count, size_t vertex_count, bool* any) {
  std::vector<uint8_t> is_point(vertex_count, 0);
  std::atomic<bool> some{false};
  // Threads may mark one vertex at once: relaxed atomic stores of the same 1 (plain moves;
  // the GCC/Clang builtin, as C++17 has no atomic_ref).
  parallel_for(count, 0, 1 << 20, [&](size_t begin, size_t end) {
    bool mine = false;
    for (size_t i = begin; i < end; ++i)
      if (indices[i] < vertex_count) {
        __atomic_store_n(&is_point[indices[i]], uint8_t(1), __ATOMIC_RELAXED);
        mine = true;
      }
    if (mine) some.store(true, std::memory_order_relaxed);
  });
  if (any) *any = some.load();
  return is_point;
}

double BoundingBox::diagonal() const {
  double dx = max[0] - min[0], dy = max[1] - min[1], dz = max[2] - min[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

namespace {

template <typename T>
BoundingBox bounding_box_of(const T* xyz, size_t vertex_count, const uint8_t* mask) {
  // On every core (the fast pipeline takes it once per sigma of a 10M-vertex scan): the
  // minimum and maximum do not depend on the order the vertices are seen in.
  BoundingBox box{{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
  std::mutex lock;
  parallel_for(vertex_count, 0, 1 << 18, [&](size_t begin, size_t end) {
    BoundingBox part{{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
    for (size_t v = begin; v < end; ++v) {
      if (mask && !mask[v]) continue;
      for (int a = 0; a < 3; ++a) {
        const double x = xyz[3 * v + a];
        if (!std::isfinite(x)) continue;
        part.min[a] = std::min(part.min[a], x);
        part.max[a] = std::max(part.max[a], x);
      }
    }
    std::lock_guard<std::mutex> hold(lock);
    for (int a = 0; a < 3; ++a) {
      box.min[a] = std::min(box.min[a], part.min[a]);
      box.max[a] = std::max(box.max[a], part.max[a]);
    }
  });
  return box;
}

}  // namespace

BoundingBox bounding_box(const float* xyz, size_t vertex_count, const uint8_t* mask) {
  return bounding_box_of(xyz, vertex_count, mask);
}

BoundingBox bounding_box(const double* xyz, size_t vertex_count, const uint8_t* mask) {
  return bounding_box_of(xyz, vertex_count, mask);
}

BoundingBox mesh_points_bbox(const Mesh& mesh, const std::vector<uint8_t>& is_point) {
  if (std::find(is_point.begin(), is_point.end(), 1) == is_point.end())
    throw Error("mesh has no vertex referenced by a triangle");
  return bounding_box(mesh.positions.data(), mesh.vertex_count(), is_point.data());
}

double scale_unit(const Mesh& mesh, const std::vector<uint8_t>& is_point, double eps_frac) {
  if (!(eps_frac > 0) || !std::isfinite(eps_frac))
    throw Error("eps fraction must be a positive number");
  double eps = eps_frac * mesh_points_bbox(mesh, is_point).diagonal();
  if (!(eps > 0) || !std::isfinite(eps))
    throw Error("mesh points all coincide: the bounding box has zero size");
  return eps;
}

}  // namespace meshsal
