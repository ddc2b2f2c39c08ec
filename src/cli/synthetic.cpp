#include "cli/synthetic.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

namespace meshsal {

namespace {

struct Vec3 {
  double x, y, z;
};

Vec3 normalized(Vec3 v) {
  double l = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  return {v.x / l, v.y / l, v.z / l};
}

// Unit icosphere as doubles (positions) and triangles, counter-clockwise seen from outside.
void unit_icosphere(int subdivisions, std::vector<Vec3>& pos, std::vector<uint32_t>& tri) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  pos = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
         {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (auto& p : pos) p = normalized(p);
  tri = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2,
         10, 7, 6, 7, 1, 8, 3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11,
         6, 2, 10, 8, 6, 7, 9, 8, 1};
  for (int s = 0; s < subdivisions; ++s) {
    std::unordered_map<uint64_t, uint32_t> mid;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      uint64_t key = (uint64_t(std::min(a, b)) << 32) | std::max(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      Vec3 m = normalized({pos[a].x + pos[b].x, pos[a].y + pos[b].y, pos[a].z + pos[b].z});
      pos.push_back(m);
      return mid[key] = uint32_t(pos.size() - 1);
    };
    std::vector<uint32_t> next;
    next.reserve(tri.size() * 4);
    for (size_t f = 0; f < tri.size(); f += 3) {
      uint32_t a = tri[f], b = tri[f + 1], c = tri[f + 2];
      uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    tri.swap(next);
  }
}

Mesh to_mesh(const std::vector<Vec3>& pos, std::vector<uint32_t> tri) {
  Mesh m;
  m.positions.reserve(pos.size() * 3);
  for (const Vec3& p : pos) m.positions.insert(m.positions.end(), {float(p.x), float(p.y), float(p.z)});
  m.triangles = std::move(tri);
  return m;
}

// Regular grid of (n+1)^2 vertices on [-size/2, size/2]^2 with height z = f(x, y).
template <class F>
Mesh height_field(double size, int n, F f) {
  std::vector<Vec3> pos;
  std::vector<uint32_t> tri;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      double x = size * (double(i) / n - 0.5), y = size * (double(j) / n - 0.5);
      pos.push_back({x, y, f(x, y)});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      uint32_t a = j * (n + 1) + i, b = a + 1, c = a + (n + 1), d = c + 1;
      tri.insert(tri.end(), {a, b, d, a, d, c});
    }
  return to_mesh(pos, std::move(tri));
}

}  // namespace

Mesh make_sphere(double radius, int subdivisions) {
  std::vector<Vec3> pos;
  std::vector<uint32_t> tri;
  unit_icosphere(subdivisions, pos, tri);
  for (auto& p : pos) p = {p.x * radius, p.y * radius, p.z * radius};
  return to_mesh(pos, std::move(tri));
}

Mesh make_plane(double size, int n) {
  return height_field(size, n, [](double, double) { return 0.0; });
}

Mesh make_plane_with_bump(double size, int n, double height, double width) {
  return height_field(size, n, [=](double x, double y) {
    return height * std::exp(-(x * x + y * y) / (2 * width * width));
  });
}

Mesh make_cube(int n) {
  // Lattice points (i,j,k) in [0,n]^3 on the surface, shared between faces.
  std::map<std::tuple<int, int, int>, uint32_t> index;
  std::vector<Vec3> pos;
  std::vector<uint32_t> tri;
  auto vertex = [&](int i, int j, int k) {
    auto key = std::make_tuple(i, j, k);
    auto it = index.find(key);
    if (it != index.end()) return it->second;
    pos.push_back({2.0 * i / n - 1, 2.0 * j / n - 1, 2.0 * k / n - 1});
    return index[key] = uint32_t(pos.size() - 1);
  };
  // Each face: axis a fixed at 0 or n; (u, v) the other two axes, ordered so the normal
  // points outwards.
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      int u = (a + 1) % 3, v = (a + 2) % 3;
      for (int p = 0; p < n; ++p)
        for (int q = 0; q < n; ++q) {
          uint32_t c[4];
          int uv[4][2] = {{p, q}, {p + 1, q}, {p + 1, q + 1}, {p, q + 1}};
          for (int m = 0; m < 4; ++m) {
            int ijk[3];
            ijk[a] = side * n;
            ijk[u] = uv[m][0];
            ijk[v] = uv[m][1];
            c[m] = vertex(ijk[0], ijk[1], ijk[2]);
          }
          if (side == 1)
            tri.insert(tri.end(), {c[0], c[1], c[2], c[0], c[2], c[3]});
          else
            tri.insert(tri.end(), {c[0], c[2], c[1], c[0], c[3], c[2]});
        }
    }
  return to_mesh(pos, std::move(tri));
}

Mesh make_bumpy_sphere(int subdivisions, std::vector<uint8_t>* feature_mask,
                       std::vector<uint8_t>* bump_mask) {
  std::vector<Vec3> pos;
  std::vector<uint32_t> tri;
  unit_icosphere(subdivisions, pos, tri);

  // One unique feature, larger than the bumps but of lower peak curvature; its size matches
  // the coarse saliency scales (sigma 4-6 eps, eps ~ 0.0105 here).
  const Vec3 feature = normalized({0.3, 0.4, 1.0});
  const double feature_width = 0.08, feature_height = 0.06;
  // Many identical small bumps at the points of a Fibonacci sphere (spacing ~0.12 rad),
  // away from the feature: sharper, so mean curvature rates them higher, but repeated.
  // Sizes were tuned so both contrasts hold from 5 subdivisions (10k vertices) up.
  const int bumps = 900;
  const double bump_width = 0.03, bump_height = 0.011;
  std::vector<Vec3> centres;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < bumps; ++i) {
    double z = 1.0 - 2.0 * (i + 0.5) / bumps, r = std::sqrt(1 - z * z);
    Vec3 c{r * std::cos(golden * i), r * std::sin(golden * i), z};
    double angle = std::acos(std::clamp(c.x * feature.x + c.y * feature.y + c.z * feature.z, -1.0, 1.0));
    if (angle > 4 * feature_width) centres.push_back(c);
  }
  if (feature_mask) feature_mask->assign(pos.size(), 0);
  if (bump_mask) bump_mask->assign(pos.size(), 0);
  for (size_t v = 0; v < pos.size(); ++v) {
    Vec3 p = pos[v];
    auto angle_to = [&](const Vec3& c) {
      return std::acos(std::clamp(p.x * c.x + p.y * c.y + p.z * c.z, -1.0, 1.0));
    };
    double a = angle_to(feature);
    double r = 1.0 + feature_height * std::exp(-a * a / (2 * feature_width * feature_width));
    if (feature_mask && a < 1.5 * feature_width) (*feature_mask)[v] = 1;
    for (const Vec3& c : centres) {
      double b = angle_to(c);
      if (b > 5 * bump_width) continue;
      r += bump_height * std::exp(-b * b / (2 * bump_width * bump_width));
      if (bump_mask && b < 1.5 * bump_width) (*bump_mask)[v] = 1;
    }
    pos[v] = {p.x * r, p.y * r, p.z * r};
  }
  return to_mesh(pos, std::move(tri));
}

}  // namespace meshsal
