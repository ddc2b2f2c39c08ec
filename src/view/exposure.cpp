#include "view/exposure.h"

#include <algorithm>
#include <cmath>

#include "core/mesh_points.h"
#include "core/parallel.h"
#include "saliency/curvature.h"
#include "view/visibility.h"

namespace meshsal {

std::vector<ViewAngles> exposure_views() {
  const double pi = std::acos(-1.0);
  std::vector<ViewAngles> views;
  for (int j = 0; j < kExposureLatitudes; ++j) {
    const double t = kExposureLatitudes > 1 ? double(j) / (kExposureLatitudes - 1) : 0.5;
    const double phi = (kDefaultElevationMin + t * (kDefaultElevationMax - kDefaultElevationMin)) * pi / 180;
    for (int k = 0; k < kExposureLongitudes; ++k) {
      double theta = 2 * pi * k / kExposureLongitudes;
      if (theta > pi) theta -= 2 * pi;  // ViewAngles' theta lies in (-pi, pi]
      views.push_back({theta, phi});
    }
  }
  return views;
}

ExposureView exposure_view(const ViewFrame& frame, const ViewAngles& view) {
  ExposureView v;
  v.rows = view_rows(frame, view);
  double d[3];
  view_direction(frame, view, d);
  for (int k = 0; k < 3; ++k) v.direction[k] = float(d[k]);
  return v;
}

std::vector<float> exposure_normals(const Mesh& mesh, unsigned threads) {
  const std::vector<double> n = vertex_normals(mesh, threads);
  return std::vector<float>(n.begin(), n.end());
}

static void check_exposure_inputs(const Mesh& mesh, const std::vector<float>& normals,
                                  const VisibilityOptions& options) {
  check_visibility_options(options);
  if (normals.size() != 3 * mesh.vertex_count()) throw Error("exposure: normals do not match the mesh");
}

std::vector<double> exposure_cpu(const Mesh& mesh, const std::vector<float>& normals, const ViewFrame& frame,
                                 const std::vector<ViewAngles>& views, ExposureWeighting weighting,
                                 const VisibilityOptions& options) {
  check_exposure_inputs(mesh, normals, options);
  const size_t n = mesh.vertex_count();
  const int res = options.resolution;
  const float tol = float(options.depth_tol_px / res);
  const float half = 0.5f * float(res);
  const std::vector<uint8_t> is_point = referenced_vertices(mesh);
  std::vector<double> sum(n, 0.0);
  if (views.empty()) return sum;
  // A batch of views as wide as the threads: their z-buffers are made side by side (each
  // raster holds its own projection of the mesh, 12 bytes a vertex, while it runs), then
  // every vertex adds its scores over the batch in view order. At most kExposureScratch
  // bytes of projections and z-buffers at once, whatever the thread count.
  const unsigned threads = resolve_threads(options.threads);
  const size_t per_view = 12 * n + 4 * size_t(res) * size_t(res);
  const size_t batch = std::max<size_t>(
      1, std::min<size_t>({views.size(), size_t(threads), kExposureScratch / per_view}));
  std::vector<std::vector<float>> zbuf(batch);
  std::vector<ExposureView> ev(batch);
  for (size_t first = 0; first < views.size(); first += batch) {
    const size_t count = std::min(batch, views.size() - first);
    for (size_t v = 0; v < count; ++v) ev[v] = exposure_view(frame, views[first + v]);
    parallel_for(count, options.threads, 1, [&](size_t lo, size_t hi) {
      for (size_t v = lo; v < hi; ++v) zbuf[v] = depth_buffer_cpu(mesh, ev[v].rows, res);
    });
    parallel_for(n, options.threads, 4096, [&](size_t lo, size_t hi) {
      const float* pos = mesh.positions.data();
      for (size_t i = lo; i < hi; ++i) {
        if (!is_point[i]) continue;
        const float* p = pos + 3 * i;
        double s = sum[i];
        const float* nn = &normals[3 * i];
        for (size_t v = 0; v < count; ++v) {
          const Projected q = project(ev[v].rows, p[0], p[1], p[2], half);
          if (passes_depth_test(q, zbuf[v].data(), res, tol)) s += exposure_weight(ev[v], p, nn, weighting);
        }
        sum[i] = s;
      }
    });
  }
  for (double& s : sum) s /= double(views.size());
  return sum;
}

std::vector<double> exposure_plain_cpu(const Mesh& mesh, const std::vector<float>& normals, const ViewFrame& frame,
                                       const std::vector<ViewAngles>& views, ExposureWeighting weighting,
                                       const VisibilityOptions& options) {
  check_exposure_inputs(mesh, normals, options);
  const size_t n = mesh.vertex_count();
  std::vector<double> sum(n, 0.0);
  for (const ViewAngles& a : views) {
    const std::vector<uint8_t> seen = visible_vertices_cpu(mesh, frame, a, options);
    double d[3], right[3], up[3];
    view_basis(frame, a, right, up, d);
    for (size_t i = 0; i < n; ++i) {
      if (!seen[i]) continue;
      double w = 1;
      const float* nn = &normals[3 * i];
      if (weighting.facing) w = std::fabs(nn[0] * d[0] + nn[1] * d[1] + nn[2] * d[2]);
      if (weighting.centre) {
        // The point's place in the frame, in double, straight from the camera's definition.
        double x = 0, y = 0;
        for (int k = 0; k < 3; ++k) {
          const double c = double(mesh.positions[3 * i + k]) - frame.centre[k];
          x += c * right[k];
          y += c * up[k];
        }
        x /= frame.radius;
        y /= frame.radius;
        w *= std::exp(-x * x / (2 * double(kCentreVarianceX)) - y * y / (2 * double(kCentreVarianceY)));
      }
      sum[i] += w;
    }
  }
  for (double& s : sum) s /= double(views.size());
  return sum;
}

}  // namespace meshsal
