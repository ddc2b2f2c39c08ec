#include "saliency/curvature.h"

#include <cmath>

#include "core/parallel.h"
#include "saliency/cpu_dispatch.h"

namespace meshsal {

namespace {

// The hot loops below are written once and compiled twice, for baseline x86-64 and for
// AVX2 (cpu_dispatch.h); both copies give the same bits.

// Sums the un-normalised face normals into normals[] (3 n, zeroed) and normalises them.
inline void vertex_normals_body(const Mesh& mesh, double* normals) {
  const size_t n = mesh.vertex_count();
  const float* p = mesh.positions.data();
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
}

// Taubin 1995 as SPEC 1 fixes it: H_i = sum_j w_ij k_ij |T_ij|^2, where |T_ij|^2 is 1 unless
// the edge is of zero length or parallel to N_i (then the term adds 0).
inline double vertex_mean_curvature(const Mesh& mesh, const Adjacency& adj,
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

inline void mean_curvature_body(const Mesh& mesh, const Adjacency& adj, const double* normals,
                                size_t begin, size_t end, double* H) {
  for (size_t i = begin; i < end; ++i) H[i] = vertex_mean_curvature(mesh, adj, normals, i);
}

MESHSAL_TARGET_BASELINE void vertex_normals_baseline(const Mesh& mesh, double* normals) {
  vertex_normals_body(mesh, normals);
}
MESHSAL_TARGET_BASELINE void mean_curvature_baseline(const Mesh& mesh, const Adjacency& adj,
                                                     const double* normals, size_t begin,
                                                     size_t end, double* H) {
  mean_curvature_body(mesh, adj, normals, begin, end, H);
}
#if MESHSAL_HAVE_AVX2_COPIES
MESHSAL_TARGET_AVX2 void vertex_normals_avx2(const Mesh& mesh, double* normals) {
  vertex_normals_body(mesh, normals);
}
MESHSAL_TARGET_AVX2 void mean_curvature_avx2(const Mesh& mesh, const Adjacency& adj,
                                             const double* normals, size_t begin, size_t end,
                                             double* H) {
  mean_curvature_body(mesh, adj, normals, begin, end, H);
}
#endif

}  // namespace

std::vector<double> vertex_normals(const Mesh& mesh) {
  std::vector<double> normals(3 * mesh.vertex_count(), 0.0);
  auto body = vertex_normals_baseline;
#if MESHSAL_HAVE_AVX2_COPIES
  if (cpu_path() == CpuPath::avx2) body = vertex_normals_avx2;
#endif
  body(mesh, normals.data());
  return normals;
}

std::vector<double> mean_curvature(const Mesh& mesh, const Adjacency& adjacency,
                                   const std::vector<double>& normals, unsigned threads) {
  std::vector<double> H(mesh.vertex_count(), 0.0);
  auto body = mean_curvature_baseline;
#if MESHSAL_HAVE_AVX2_COPIES
  if (cpu_path() == CpuPath::avx2) body = mean_curvature_avx2;
#endif
  parallel_for(H.size(), threads, 4096, [&](size_t begin, size_t end) {
    body(mesh, adjacency, normals.data(), begin, end, H.data());
  });
  return H;
}

}  // namespace meshsal
