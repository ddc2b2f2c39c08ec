// bench_simplify_attributes: the time of simplify_mesh when attributes are kept, against
// meshoptimizer's meshopt_simplify (when built with it) on the same vertex buffer. Each
// mesh gets spherical texture coordinates around its centroid (a UV seam where u wraps,
// each seam vertex split in two) and area-weighted vertex normals, through the OBJ loader
// as a user's file would; meshopt_simplify finds the seam by position itself. Best of 3,
// to 1% and 5% of the faces; also the time without attributes.
//
//   bench_simplify_attributes [MESHES...]   (default: the benchmark meshes)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/timer.h"
#include "data_dir.h"
#include "meshsal/meshsal.h"

#ifdef MESHSAL_HAVE_MESHOPTIMIZER
#include <meshoptimizer.h>
#endif

using namespace meshsal;

namespace {
constexpr double kPi = 3.14159265358979323846;

// The mesh as OBJ text with vt (two per vertex: u and u + 1, the far side of the seam)
// and vn, faces v/vt/vn.
std::string seamed_obj(const Mesh& m) {
  const size_t nv = m.vertex_count();
  double c[3] = {0,0,0};
  for (size_t i = 0; i < nv; ++i) for (int k = 0; k < 3; ++k) c[k] += m.positions[3*i+k] / nv;
  std::vector<double> U(nv), V(nv);
  std::vector<double> N(3*nv, 0);
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const float* p[3]; for (int k=0;k<3;++k) p[k] = &m.positions[3*size_t(m.triangles[3*t+k])];
    double e1[3], e2[3]; for (int k=0;k<3;++k){e1[k]=p[1][k]-p[0][k]; e2[k]=p[2][k]-p[0][k];}
    double n[3] = {e1[1]*e2[2]-e1[2]*e2[1], e1[2]*e2[0]-e1[0]*e2[2], e1[0]*e2[1]-e1[1]*e2[0]};
    for (int k=0;k<3;++k) for (int j=0;j<3;++j) N[3*m.triangles[3*t+k]+j] += n[j];
  }
  std::string s; s.reserve(nv * 120);
  char line[200];
  for (size_t i = 0; i < nv; ++i) {
    const float* p = &m.positions[3*i];
    std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", p[0], p[1], p[2]); s += line;
    double x = p[0]-c[0], y = p[1]-c[1], z = p[2]-c[2], r = std::sqrt(x*x+y*y+z*z) + 1e-30;
    U[i] = std::atan2(z, x) / (2*kPi) + 0.5; V[i] = std::acos(std::max(-1.0,std::min(1.0,y/r)))/kPi;
  }
  for (size_t i = 0; i < nv; ++i) { std::snprintf(line, sizeof line, "vt %.9g %.9g\nvt %.9g %.9g\n", U[i], V[i], U[i]+1, V[i]); s += line; }
  for (size_t i = 0; i < nv; ++i) { double l = std::sqrt(N[3*i]*N[3*i]+N[3*i+1]*N[3*i+1]+N[3*i+2]*N[3*i+2])+1e-30;
    std::snprintf(line, sizeof line, "vn %.6g %.6g %.6g\n", N[3*i]/l, N[3*i+1]/l, N[3*i+2]/l); s += line; }
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    double u[3]; for (int k=0;k<3;++k) u[k] = U[m.triangles[3*t+k]];
    double span = std::max({u[0],u[1],u[2]}) - std::min({u[0],u[1],u[2]});
    s += "f";
    for (int k=0;k<3;++k) { uint32_t i = m.triangles[3*t+k]; bool sh = span > 0.5 && u[k] < 0.5;
      std::snprintf(line, sizeof line, " %u/%u/%u", i+1, 2*i+1+(sh?1:0), i+1); s += line; }
    s += "\n";
  }
  return s;
}
}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> meshes(argv + 1, argv + argc);
  if (meshes.empty())
    for (const char* name : {"bunny_36k.obj", "armadillo_43k.obj", "dragon_50k.ply", "lucy_50k.ply", "igea_134k.ply.gz"})
      meshes.push_back(benchmark_data_dir() + "/" + name);
  for (const std::string& path : meshes) {
    const char* name = path.c_str();
    const Mesh plain = load_mesh(path);
    LoadOptions lo; lo.attributes = true;
    const Mesh split = load_mesh_bytes(seamed_obj(plain), "x.obj", lo);
    size_t twins = 0; for (size_t i = 0; i < split.position_vertex.size(); ++i) twins += split.position_vertex[i] != i;
    for (double ratio : {0.01, 0.05}) {
      const size_t target = size_t(std::llround(ratio * plain.triangle_count()));
      double best_attr = 1e9, best_plain = 1e9, best_mo = 1e9; size_t f_attr=0, f_plain=0, f_mo=0;
      for (int rep = 0; rep < 3; ++rep) {
        SimplifyOptions o; o.target_faces = target;
        Timer t0; Mesh out = simplify_mesh(split, o).mesh; best_attr = std::min(best_attr, t0.seconds()); f_attr = out.triangle_count();
        Timer t1; Mesh out2 = simplify_mesh(plain, o).mesh; best_plain = std::min(best_plain, t1.seconds()); f_plain = out2.triangle_count();
#ifdef MESHSAL_HAVE_MESHOPTIMIZER
        std::vector<unsigned> dst(split.triangles.size());
        Timer t2; size_t n = meshopt_simplify(dst.data(), split.triangles.data(), split.triangles.size(), split.positions.data(),
                                            split.vertex_count(), 12, 3 * target, 1.0f, 0, nullptr);
        best_mo = std::min(best_mo, t2.seconds()); f_mo = n / 3;
#endif
      }
      std::printf("%s %zu faces, %zu seam twins, to %.0f%%: attributes %.4f s (%zu faces), no attributes %.4f s (%zu), "
                  "meshopt_simplify %.4f s (%zu faces) -> %.2fx\n",
                  name, plain.triangle_count(), twins, ratio * 100, best_attr, f_attr, best_plain, f_plain, best_mo, f_mo, best_attr / best_mo);
    }
  }
}
