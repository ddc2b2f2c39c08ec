#include "saliency/curvature.h"

#include <cmath>

#include "core/parallel.h"

namespace meshsal {

std::vector<double> vertex_normals(const Mesh& mesh) {
  const size_t n = mesh.vertex_count();
  const float* p = mesh.positions.data();
  std::vector<double> normals(3 * n, 0.0);
  for (size_t f = 0; f < mesh.triangle_count(); ++f) {
    const uint32_t* t = &mesh.triangles[3 * f];
    double e1[3], e2[3];
    for (int k = 0; k < 3; ++k) {
      e1[k] = double(p[3 * t[1] + k]) - p[3 * t[0] + k];
      e2[k] = double(p[3 * t[2] + k]) - p[3 * t[0] + k];
    }
    // Un-normalised face normal: its length is twice the area (area weighting).
    double fn[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                    e1[0] * e2[1] - e1[1] * e2[0]};
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) normals[3 * t[c] + k] += fn[k];
  }
  for (size_t v = 0; v < n; ++v) {
    double* nv = &normals[3 * v];
    double len = std::sqrt(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]);
    if (len > 0 && std::isfinite(len)) {
      nv[0] /= len, nv[1] /= len, nv[2] /= len;
    } else {
      nv[0] = nv[1] = nv[2] = 0.0;
    }
  }
  return normals;
}

// Taubin 1995 as SPEC 1 fixes it: H_i = sum_j w_ij k_ij |T_ij|^2, where |T_ij|^2 is 1 unless
// the edge is of zero length or parallel to N_i (then the term adds 0).
static double vertex_mean_curvature(const Mesh& mesh, const Adjacency& adj,
                                    const double* normals, size_t i) {
  const float* p = mesh.positions.data();
  const double* ni = &normals[3 * i];
  double total_area = 0.0, sum = 0.0;
  for (uint32_t e = adj.offsets[i]; e < adj.offsets[i + 1]; ++e) {
    uint32_t j = adj.neighbors[e];
    double w = adj.edge_area[e];
    total_area += w;
    double d[3] = {double(p[3 * j]) - p[3 * i], double(p[3 * j + 1]) - p[3 * i + 1],
                   double(p[3 * j + 2]) - p[3 * i + 2]};
    double len2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if (!(len2 > 0)) continue;
    double nd = ni[0] * d[0] + ni[1] * d[1] + ni[2] * d[2];
    double tangential2 = len2 - nd * nd;  // |(I - N N^T)(v_i - v_j)|^2
    if (!(tangential2 > 1e-12 * len2)) continue;
    sum += w * (2.0 * nd / len2);
  }
  return total_area > 0 ? sum / total_area : 0.0;
}

std::vector<double> mean_curvature(const Mesh& mesh, const Adjacency& adjacency,
                                   const std::vector<double>& normals, unsigned threads) {
  std::vector<double> H(mesh.vertex_count(), 0.0);
  parallel_for(H.size(), threads, 4096, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i)
      H[i] = vertex_mean_curvature(mesh, adjacency, normals.data(), i);
  });
  return H;
}

}  // namespace meshsal
