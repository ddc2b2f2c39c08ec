#include "view/render.h"

#include "saliency/curvature.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/vec3.h"
#include "io/colormap.h"
#include "meshsal/meshsal.h"
#include "core/mesh_points.h"

namespace meshsal {

static const double kPi = 3.14159265358979323846;

void check_render_style(const RenderStyle& s) {
  if (s.size < kMinImageSize || s.size > kMaxImageSize)
    throw Error("image size must be between " + std::to_string(kMinImageSize) + " and " +
                std::to_string(kMaxImageSize) + ", got " + std::to_string(s.size));
  if (!(s.margin >= 1.0) || !std::isfinite(s.margin)) throw Error("image margin must be >= 1");
  if (s.supersample < 1 || s.supersample > 4)
    throw Error("supersample must be between 1 and 4, got " + std::to_string(s.supersample));
}

PictureFit fit_picture(const Mesh& mesh, const ViewFrame& frame, const ViewAngles& view) {
  double right[3], up[3], d[3];
  view_basis(frame, view, right, up, d);
  std::vector<uint8_t> is_point = referenced_vertices(mesh);
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  const float* p = mesh.positions.data();
  for (size_t i = 0; i < mesh.vertex_count(); ++i) {
    if (!is_point[i]) continue;
    double q[3] = {p[3 * i] - frame.centre[0], p[3 * i + 1] - frame.centre[1], p[3 * i + 2] - frame.centre[2]};
    double x = q[0] * right[0] + q[1] * right[1] + q[2] * right[2];
    double y = q[0] * up[0] + q[1] * up[1] + q[2] * up[2];
    x0 = std::min(x0, x);
    x1 = std::max(x1, x);
    y0 = std::min(y0, y);
    y1 = std::max(y1, y);
  }
  PictureFit fit;
  if (!(x1 >= x0)) return fit;  // no points: the bounding sphere
  fit.cx = 0.5 * (x0 + x1);
  fit.cy = 0.5 * (y0 + y1);
  fit.half = 0.5 * std::max(x1 - x0, y1 - y0);
  if (!(fit.half > 1e-12 * frame.radius)) fit.half = frame.radius;  // a point or a segment seen end-on
  return fit;
}

// Box average of ss x ss blocks: the anti-aliased picture.
static Image downsample(const Image& big, int ss) {
  if (ss == 1) return big;
  Image out(big.width / ss, big.height / ss);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int k = 0; k < 3; ++k) {
        int sum = 0;
        for (int dy = 0; dy < ss; ++dy)
          for (int dx = 0; dx < ss; ++dx) sum += big.at(x * ss + dx, y * ss + dy)[k];
        out.at(x, y)[k] = uint8_t((sum + ss * ss / 2) / (ss * ss));
      }
  return out;
}

namespace {

// Light slightly above and left of the viewer, two-sided (open scans have no outside).
void light_direction(const double right[3], const double up[3], const double d[3], double light[3]) {
  double ll = 0;
  for (int k = 0; k < 3; ++k) {
    light[k] = d[k] + 0.35 * up[k] - 0.25 * right[k];
    ll += light[k] * light[k];
  }
  for (int k = 0; k < 3; ++k) light[k] /= std::sqrt(ll);
}

// The vertices on the supersampled picture: sx, sy in pixels, sz the depth in [0, 1].
struct PixelVertices {
  std::vector<double> sx, sy, sz;
  // The pixels of a triangle's projected bounding box.
  double box_pixels(uint32_t a, uint32_t b, uint32_t c) const {
    double w = std::max({sx[a], sx[b], sx[c]}) - std::min({sx[a], sx[b], sx[c]}) + 1;
    double h = std::max({sy[a], sy[b], sy[c]}) - std::min({sy[a], sy[b], sy[c]}) + 1;
    return w * h;
  }
};

// Project in double (pictures need no bit-match with the GPU). x and y are framed by the
// projected extent, depth by the bounding sphere.
PixelVertices project_vertices(const Mesh& mesh, const ViewFrame& frame, const double right[3], const double up[3],
                           const double d[3], const PictureFit& fit, double margin, int res) {
  size_t n = mesh.vertex_count();
  PixelVertices pr;
  std::vector<double>&sx = pr.sx, &sy = pr.sy, &sz = pr.sz;
  sx.resize(n), sy.resize(n), sz.resize(n);
  const float* p = mesh.positions.data();
  double half = 0.5 * res, inv_h = 1.0 / (fit.half * margin), inv_r = 1.0 / frame.radius;
  for (size_t i = 0; i < n; ++i) {
    double q[3] = {p[3 * i] - frame.centre[0], p[3 * i + 1] - frame.centre[1], p[3 * i + 2] - frame.centre[2]};
    double x = (q[0] * right[0] + q[1] * right[1] + q[2] * right[2] - fit.cx) * inv_h;
    double y = (q[0] * up[0] + q[1] * up[1] + q[2] * up[2] - fit.cy) * inv_h;
    double z = (q[0] * d[0] + q[1] * d[1] + q[2] * d[2]) * inv_r;
    sx[i] = (x + 1) * half;
    sy[i] = (1 - y) * half;
    sz[i] = (1 - z) * 0.5;
  }
  return pr;
}

// A triangle only wins a pixel with a strictly smaller depth, so an exact copy of an
// earlier triangle (same projected corners in the same order) never draws anything: large
// copies are dropped up front. Large triangles also skip 8x8 tiles already covered no
// deeper than they can reach (Rasteriser). Both keep the picture identical and bound the
// cost of a stack of copies of one large triangle by its pixels once.
const double kLarge = 256;  // box pixels from which a triangle goes through the tile test

// Per triangle: 1 for a large one that copies an earlier one (the first in mesh order is kept).
std::vector<uint8_t> large_copies(const Mesh& mesh, const PixelVertices& pr) {
  const std::vector<double>&sx = pr.sx, &sy = pr.sy, &sz = pr.sz;
  std::vector<uint8_t> copy(mesh.triangle_count(), 0);
  std::vector<uint32_t> large;
  for (size_t f = 0; f < mesh.triangle_count(); ++f) {
    const uint32_t* t = &mesh.triangles[3 * f];
    if (pr.box_pixels(t[0], t[1], t[2]) >= kLarge) large.push_back(uint32_t(f));
  }
  auto key = [&](uint32_t f, int i) {
    const uint32_t v = mesh.triangles[3 * size_t(f) + i / 3];
    return i % 3 == 0 ? sx[v] : i % 3 == 1 ? sy[v] : sz[v];
  };
  std::sort(large.begin(), large.end(), [&](uint32_t f, uint32_t g) {
    for (int i = 0; i < 9; ++i)
      if (key(f, i) != key(g, i)) return key(f, i) < key(g, i);
    return f < g;  // the first in mesh order is the one kept
  });
  for (size_t i = 1; i < large.size(); ++i) {
    bool same = true;
    for (int k = 0; k < 9 && same; ++k) same = key(large[i], k) == key(large[i - 1], k);
    copy[large[i]] = same;
  }
  return copy;
}

// What the pixel loop needs of one triangle.
struct Triangle {
  uint32_t a, b, c;
  double s, inv;     // the winding's sign, 1 / |twice the area|
  double len[3];     // edge lengths in pixels, for the distance of a pixel to each edge
  bool draw_edges;
  double fn[3];      // the face normal (flat shading)
  int x0, x1, y0, y1;  // the pixels of its box on the picture
  bool large;        // goes through the tile test
  double zmin;       // the smallest depth it can give
};

// The z-buffered, shaded picture, one triangle at a time.
class Rasteriser {
 public:
  Rasteriser(const Mesh& mesh, const std::vector<uint8_t>* vertex_rgb, const RenderStyle& style,
             const PixelVertices& pr, const double light[3], int res)
      : mesh_(mesh), vertex_rgb_(vertex_rgb), style_(style), pr_(pr), res_(res), ss_(style.supersample),
        normals_(vertex_normals(mesh)),  // the curvature stage's normals
        img_(res, res, style.background[0], style.background[1], style.background[2]),
        zbuf_(size_t(res) * res, std::numeric_limits<double>::infinity()), tiles_across_((res + 7) / 8),
        tile_filled_(size_t(tiles_across_) * tiles_across_, 0), tile_max_(tile_filled_.size(), 0.0) {
    for (int k = 0; k < 3; ++k) light_[k] = light[k];
  }

  void draw(size_t f) {
    Triangle t;
    if (!set_up(&mesh_.triangles[3 * f], t)) return;
    if (!t.large) {
      pixels(t, t.x0, t.x1, t.y0, t.y1);
      return;
    }
    for (int ty = t.y0 >> 3; ty <= t.y1 >> 3; ++ty)
      for (int tx = t.x0 >> 3; tx <= t.x1 >> 3; ++tx) {
        const size_t k = size_t(ty) * tiles_across_ + size_t(tx);
        const int pixels_in_tile = std::min(8, res_ - 8 * tx) * std::min(8, res_ - 8 * ty);
        if (tile_filled_[k] == pixels_in_tile && tile_max_[k] <= t.zmin) continue;  // nothing here can win
        pixels(t, std::max(t.x0, 8 * tx), std::min(t.x1, 8 * tx + 7), std::max(t.y0, 8 * ty), std::min(t.y1, 8 * ty + 7));
      }
  }

  const Image& picture() const { return img_; }

 private:
  // The triangle's constants; false when it has no area on the picture.
  bool set_up(const uint32_t* tri, Triangle& t) const {
    const std::vector<double>&sx = pr_.sx, &sy = pr_.sy, &sz = pr_.sz;
    const float* p = mesh_.positions.data();
    uint32_t a = t.a = tri[0], b = t.b = tri[1], c = t.c = tri[2];
    double area = (sx[b] - sx[a]) * (sy[c] - sy[a]) - (sx[c] - sx[a]) * (sy[b] - sy[a]);
    if (!(std::fabs(area) > 1e-12)) return false;
    t.s = area > 0 ? 1 : -1, t.inv = 1.0 / std::fabs(area);
    t.len[0] = std::hypot(sx[c] - sx[b], sy[c] - sy[b]);
    t.len[1] = std::hypot(sx[a] - sx[c], sy[a] - sy[c]);
    t.len[2] = std::hypot(sx[b] - sx[a], sy[b] - sy[a]);
    // Edges only on triangles at least 4 px tall: dense regions stay readable, and the
    // contrast between wireframe and smooth areas shows where triangles were kept.
    t.draw_edges = style_.edges && std::fabs(area) / std::max({t.len[0], t.len[1], t.len[2]}) >= 4.0 * ss_;
    for (double& v : t.fn) v = 0;
    if (!style_.smooth) {
      double e1[3], e2[3];
      for (int k = 0; k < 3; ++k) {
        e1[k] = double(p[3 * b + k]) - p[3 * a + k];
        e2[k] = double(p[3 * c + k]) - p[3 * a + k];
      }
      cross3(e1, e2, t.fn);
      double l = std::sqrt(t.fn[0] * t.fn[0] + t.fn[1] * t.fn[1] + t.fn[2] * t.fn[2]);
      if (l > 0)
        for (double& v : t.fn) v /= l;
    }
    t.x0 = std::max(0, int(std::floor(std::min({sx[a], sx[b], sx[c]}))));
    t.x1 = std::min(res_ - 1, int(std::floor(std::max({sx[a], sx[b], sx[c]}))));
    t.y0 = std::max(0, int(std::floor(std::min({sy[a], sy[b], sy[c]}))));
    t.y1 = std::min(res_ - 1, int(std::floor(std::max({sy[a], sy[b], sy[c]}))));
    t.large = (t.x1 - t.x0 + 1) * double(t.y1 - t.y0 + 1) >= kLarge;
    // The smallest depth the interpolation can give: the smallest corner depth less the
    // worst rounding of the weights (their sum against the area) times the largest depth.
    const double slack = 64 * std::ldexp(1.0, -52) * pr_.box_pixels(a, b, c) * t.inv + 32 * std::ldexp(1.0, -52);
    t.zmin = std::min({sz[a], sz[b], sz[c]}) - slack * std::max({std::fabs(sz[a]), std::fabs(sz[b]), std::fabs(sz[c])});
    return true;
  }

  // The pixels [xa, xb] x [ya, yb] the triangle covers nearer than what is there.
  void pixels(const Triangle& t, int xa, int xb, int ya, int yb) {
    const std::vector<double>&sx = pr_.sx, &sy = pr_.sy, &sz = pr_.sz;
    const uint32_t a = t.a, b = t.b, c = t.c;
    const double s = t.s, inv = t.inv;
    for (int y = ya; y <= yb; ++y) {
      double cy = y + 0.5;
      for (int x = xa; x <= xb; ++x) {
        double cx = x + 0.5;
        double w0 = s * ((sx[c] - sx[b]) * (cy - sy[b]) - (sy[c] - sy[b]) * (cx - sx[b]));
        double w1 = s * ((sx[a] - sx[c]) * (cy - sy[c]) - (sy[a] - sy[c]) * (cx - sx[c]));
        double w2 = s * ((sx[b] - sx[a]) * (cy - sy[a]) - (sy[b] - sy[a]) * (cx - sx[a]));
        if (w0 < 0 || w1 < 0 || w2 < 0) continue;
        double z = (w0 * sz[a] + w1 * sz[b] + w2 * sz[c]) * inv;
        double& dst = zbuf_[size_t(y) * res_ + x];
        if (!(z < dst)) continue;
        if (t.large) {
          const size_t k = size_t(y >> 3) * tiles_across_ + size_t(x >> 3);
          tile_filled_[k] += std::isinf(dst);
          tile_max_[k] = std::max(tile_max_[k], z);
        }
        dst = z;
        double nn[3];
        if (style_.smooth) {
          double l = 0;
          for (int k = 0; k < 3; ++k) {
            nn[k] = (w0 * normals_[3 * a + k] + w1 * normals_[3 * b + k] + w2 * normals_[3 * c + k]) * inv;
            l += nn[k] * nn[k];
          }
          l = std::sqrt(l);
          for (double& v : nn) v = l > 0 ? v / l : 0;
        } else {
          for (int k = 0; k < 3; ++k) nn[k] = t.fn[k];
        }
        double shade = 0.18 + 0.82 * std::fabs(nn[0] * light_[0] + nn[1] * light_[1] + nn[2] * light_[2]);
        if (t.draw_edges) {
          double dist = std::min({w0 / t.len[0], w1 / t.len[1], w2 / t.len[2]});
          if (dist < 0.55 * ss_) shade *= 0.45;
        }
        uint8_t* out = img_.at(x, y);
        for (int k = 0; k < 3; ++k) {
          double col = vertex_rgb_ ? (w0 * (*vertex_rgb_)[3 * a + k] + w1 * (*vertex_rgb_)[3 * b + k] +
                                      w2 * (*vertex_rgb_)[3 * c + k]) * inv
                                   : double(style_.base[k]);
          out[k] = uint8_t(std::clamp(col * shade + 0.5, 0.0, 255.0));
        }
      }
    }
  }

  const Mesh& mesh_;
  const std::vector<uint8_t>* vertex_rgb_;
  const RenderStyle& style_;
  const PixelVertices& pr_;
  double light_[3];
  const int res_, ss_;
  const std::vector<double> normals_;
  Image img_;
  std::vector<double> zbuf_;
  const int tiles_across_;
  std::vector<uint8_t> tile_filled_;  // per 8x8 tile: its pixels drawn by a large triangle
  std::vector<double> tile_max_;      // and the largest depth they hold
};

}  // namespace

Image render_mesh(const Mesh& mesh, const std::vector<uint8_t>* vertex_rgb, const ViewFrame& frame,
                  const ViewAngles& view, const RenderStyle& style, const PictureFit* fit_in) {
  check_render_style(style);
  if (vertex_rgb && vertex_rgb->size() != 3 * mesh.vertex_count())
    throw Error("internal: vertex colours do not match the mesh");
  const int ss = style.supersample;
  const int res = style.size * ss;
  const PictureFit fit = fit_in ? *fit_in : fit_picture(mesh, frame, view);
  double right[3], up[3], d[3];
  view_basis(frame, view, right, up, d);
  double light[3];
  light_direction(right, up, d, light);
  const PixelVertices pr = project_vertices(mesh, frame, right, up, d, fit, style.margin, res);
  const std::vector<uint8_t> copy = large_copies(mesh, pr);
  Rasteriser raster(mesh, vertex_rgb, style, pr, light, res);
  for (size_t f = 0; f < mesh.triangle_count(); ++f)
    if (!copy[f]) raster.draw(f);
  return downsample(raster.picture(), ss);
}

std::vector<uint8_t> score_colours(const Mesh& mesh, const std::vector<double>& score,
                                   const ColorRange& range, ColorLimits* limits) {
  if (score.size() != mesh.vertex_count())
    throw Error("score has " + std::to_string(score.size()) + " values for " +
                std::to_string(mesh.vertex_count()) + " vertices");
  std::vector<uint8_t> is_point = referenced_vertices(mesh);
  ColorLimits l = colour_limits(score, is_point, range);
  if (limits) *limits = l;
  return colormap_values(score, is_point, l);
}

void view_map_pixel(const ViewAngles& a, int width, int* x, int* y) {
  int h = width / 2;
  *x = std::clamp(int(std::floor((a.theta + kPi) / (2 * kPi) * width)), 0, width - 1);
  *y = std::clamp(int(std::floor((kPi / 2 - a.phi) / kPi * h)), 0, h - 1);
}

Image render_view_map(const ViewMap& map, int width, const ViewAngles* ring, const ViewAngles* cross) {
  if (width < kMinMapWidth || width > kMaxImageSize)
    throw Error("map width must be between " + std::to_string(kMinMapWidth) + " and " + std::to_string(kMaxImageSize));
  if (map.views.empty() || map.U.size() != map.views.size()) throw Error("internal: empty view map");
  const int h = width / 2;
  const size_t n = map.views.size();
  std::vector<double> dirs(3 * n);
  for (size_t i = 0; i < n; ++i) view_direction(map.views[i], &dirs[3 * i]);
  double lo = *std::min_element(map.U.begin(), map.U.end());
  double hi = *std::max_element(map.U.begin(), map.U.end());
  // Gaussian smoothing over neighbours at about the spacing of the directions.
  double spacing = std::sqrt(4 * kPi / double(n));
  double sigma = 0.6 * spacing, cut = std::cos(std::min(kPi, 3 * sigma));
  // Candidates of a row: directions whose latitude is within the cut (angle >= |dphi|).
  std::vector<size_t> order(n);
  for (size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return map.views[a].phi < map.views[b].phi; });
  std::vector<double> sorted_phi(n);
  for (size_t i = 0; i < n; ++i) sorted_phi[i] = map.views[order[i]].phi;
  const double window = std::acos(cut);
  Image img(width, h);
  for (int y = 0; y < h; ++y) {
    ViewAngles a;
    a.phi = kPi / 2 - (y + 0.5) / h * kPi;
    size_t lo_i = size_t(std::lower_bound(sorted_phi.begin(), sorted_phi.end(), a.phi - window) - sorted_phi.begin());
    size_t hi_i = size_t(std::upper_bound(sorted_phi.begin(), sorted_phi.end(), a.phi + window) - sorted_phi.begin());
    for (int x = 0; x < width; ++x) {
      a.theta = -kPi + (x + 0.5) / width * 2 * kPi;
      double q[3];
      view_direction(a, q);
      double ws = 0, us = 0;
      for (size_t k = lo_i; k < hi_i; ++k) {
        size_t i = order[k];
        double dot = q[0] * dirs[3 * i] + q[1] * dirs[3 * i + 1] + q[2] * dirs[3 * i + 2];
        if (dot < cut) continue;
        double ang = std::acos(std::min(1.0, dot));
        double w = std::exp(-ang * ang / (2 * sigma * sigma));
        ws += w;
        us += w * map.U[i];
      }
      if (!(ws > 0)) {  // no direction nearby (a sparse map): the nearest one
        double best_dot = -2;
        for (size_t i = 0; i < n; ++i) {
          double dot = q[0] * dirs[3 * i] + q[1] * dirs[3 * i + 1] + q[2] * dirs[3 * i + 2];
          if (dot > best_dot) {
            best_dot = dot;
            us = map.U[i];
          }
        }
        ws = 1;
      }
      double u = us / ws;
      // The one colour scale (square-root position), as the map's colour bar shows it.
      double t = hi > lo ? colour_position(u, ColorLimits{lo, hi}) : 0.5;
      uint8_t* px = img.at(x, y);
      colormap_rgb(t, px);
      // Grid lines every 30 degrees of longitude and latitude.
      bool grid = (x * 12) % width < 12 || (y * 6) % h < 6;
      if (grid)
        for (int k = 0; k < 3; ++k) px[k] = uint8_t((px[k] + 255) / 2);
    }
  }
  auto put = [&](int x, int y, uint8_t v) {
    if (x < 0 || y < 0 || x >= width || y >= h) return;
    uint8_t* px = img.at(x, y);
    px[0] = px[1] = px[2] = v;
  };
  // Markers in black and white together, so they show on any colour of the map.
  int r = std::max(4, width / 100);
  if (ring) {
    int cx, cy;
    view_map_pixel(*ring, width, &cx, &cy);
    for (int dy = -r - 2; dy <= r + 2; ++dy)
      for (int dx = -r - 2; dx <= r + 2; ++dx) {
        double dd = std::sqrt(double(dx * dx + dy * dy));
        if (std::fabs(dd - r) < 1.0) put((cx + dx + width) % width, cy + dy, 255);
        else if (dd - r >= 1.0 && dd - r < 2.0) put((cx + dx + width) % width, cy + dy, 0);  // outside
      }
  }
  if (cross) {
    int cx, cy;
    view_map_pixel(*cross, width, &cx, &cy);
    for (int k = -r - 1; k <= r + 1; ++k)
      for (int w = -2; w <= 1; ++w) {
        put((cx + k + width) % width, cy + w, 255);
        put((cx + w + width) % width, cy + k, 255);
      }
    for (int k = -r; k <= r; ++k)
      for (int w = -1; w <= 0; ++w) {
        put((cx + k + width) % width, cy + w, 0);
        put((cx + w + width) % width, cy + k, 0);
      }
  }
  return img;
}

Image render_side_by_side(const std::vector<const Mesh*>& meshes,
                          const std::vector<const std::vector<uint8_t>*>& colours,
                          const ViewFrame& frame, const ViewAngles& view, const RenderStyle& style) {
  if (meshes.empty() || colours.size() != meshes.size()) throw Error("internal: nothing to compare");
  const int gap = 4, n = int(meshes.size());
  Image out(n * style.size + (n - 1) * gap, style.size, 128, 128, 128);
  const PictureFit fit = fit_picture(*meshes[0], frame, view);  // one camera for every panel
  for (int i = 0; i < n; ++i)
    blit(out, render_mesh(*meshes[size_t(i)], colours[size_t(i)], frame, view, style, &fit), i * (style.size + gap), 0);
  return out;
}

}  // namespace meshsal
