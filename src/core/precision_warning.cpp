// meshsal: precision_warning (meshsal.h): positions too coarse in float32 for the mesh's detail.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <vector>

#include "core/mesh_points.h"
#include "core/model_frame.h"
#include "core/parallel.h"
#include "meshsal/meshsal.h"

namespace meshsal {
namespace {

// A float32 coordinate of magnitude m is held to about m * 2^-24; an edge under this many
// such steps has lost its shape (normals, curvature and collapse tests go by its bits).
constexpr double kMinEdgeSteps = 64;
constexpr size_t kSampledTriangles = 4096;

}  // namespace

std::string precision_warning(const Mesh& mesh) {
  const size_t nt = mesh.triangle_count();
  if (nt == 0 || mesh.vertex_count() == 0) return "";
  // The median edge over up to 4096 triangles spread over the mesh (zero-length ones skipped).
  std::vector<double> edges;
  const size_t step = std::max<size_t>(1, nt / kSampledTriangles);
  for (size_t t = 0; t < nt; t += step)
    for (int k = 0; k < 3; ++k) {
      const float* a = &mesh.positions[3 * size_t(mesh.triangles[3 * t + k])];
      const float* b = &mesh.positions[3 * size_t(mesh.triangles[3 * t + (k + 1) % 3])];
      const double dx = double(a[0]) - b[0], dy = double(a[1]) - b[1], dz = double(a[2]) - b[2];
      const double len = std::sqrt(dx * dx + dy * dy + dz * dz);
      if (len > 0) edges.push_back(len);
    }
  if (edges.empty()) return "";
  std::nth_element(edges.begin(), edges.begin() + edges.size() / 2, edges.end());
  const double median_edge = edges[edges.size() / 2];
  // The largest coordinate magnitude over the mesh points, and the vertex that has it.
  const std::vector<uint8_t> is_point = referenced_vertices(mesh);
  // On every core; of equal magnitudes the first vertex, as a serial scan finds it.
  double largest = 0;
  size_t where = 0;
  std::mutex lock;
  parallel_for(mesh.vertex_count(), 0, size_t(1) << 18, [&](size_t begin, size_t end) {
    double big = 0;
    size_t at = 0;
    for (size_t v = begin; v < end; ++v) {
      if (!is_point[v]) continue;
      for (int k = 0; k < 3; ++k)
        if (std::fabs(double(mesh.positions[3 * v + k])) > big) big = std::fabs(double(mesh.positions[3 * v + k])), at = v;
    }
    std::lock_guard<std::mutex> hold(lock);
    if (big > largest || (big == largest && big > 0 && at < where)) largest = big, where = at;
  });
  const double float_step = largest * std::ldexp(1.0, -24);
  if (median_edge >= kMinEdgeSteps * float_step) return "";
  const BoundingBox box = mesh_points_bbox(mesh, is_point);
  double at[3];
  model_position(mesh, where, at);  // named in the file's coordinates
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "float precision: coordinates reach %.3g (vertex %zu at %.6g, %.6g, %.6g; the mesh spans "
                "%.3g) while the median edge is %.3g, under %g float steps at that size: results on this mesh are "
                "unreliable (a vertex far from the rest? coordinates far from the origin?)",
                largest, where, at[0], at[1], at[2],
                box.diagonal(), median_edge, kMinEdgeSteps);
  return buf;
}

}  // namespace meshsal
