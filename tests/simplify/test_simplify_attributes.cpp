// Attributes through loading, saliency and simplification: OBJ vt/vn split at UV seams,
// the position-welded saliency, seams kept closed, attributes interpolated and written.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>

#include "meshsal/meshsal.h"
#include "test_util.h"
#include "cli/synthetic.h"
#include "core/welded_view.h"
#include "simplify/simplify.h"
#include "test_io_util.h"
#include "test_simplify_attributes_util.h"
#include "test_simplify_util.h"

using namespace meshsal;
using attr_test::find;

namespace {

Mesh load_text(const std::string& text, const std::string& name, bool attributes) {
  LoadOptions o;
  o.attributes = attributes;
  return load_mesh_bytes(text, name, o);
}

SaliencyOptions cpu_saliency() {
  SaliencyOptions o;
  o.backend = Backend::Cpu;
  o.threads = 2;
  return o;
}

}  // namespace

TEST_CASE("obj attributes: v/vt/vn corners become vertices, split where vt differs", "[io][simplify]") {
  // Two triangles sharing the edge 1-3; vertex 3 is used with two texture coordinates.
  const std::string obj =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
      "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\n"
      "vn 0 0 2\n"
      "f 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/5/1 4/4/1\n";
  const Mesh m = load_text(obj, "quad.obj", true);
  REQUIRE(m.vertex_count() == 5);  // 4 positions + the twin of v 3 (vt 5)
  CHECK(m.triangles == std::vector<uint32_t>{0, 1, 2, 0, 4, 3});
  CHECK(m.position_vertex == std::vector<uint32_t>{0, 1, 2, 3, 2});
  CHECK(meshsal_test::world_floats(m)[12] == 1.f);
  CHECK(meshsal_test::world_floats(m)[13] == 1.f);
  REQUIRE(m.attributes.size() == 5);
  CHECK(m.attributes[0].name == "u");
  CHECK(m.attributes[1].name == "v");
  CHECK(m.attributes[2].name == "nx");
  CHECK(m.attributes[0].values == std::vector<float>{0, 1, 1, 0, 0.5f});
  CHECK(m.attributes[1].values == std::vector<float>{0, 0, 1, 1, 0.5f});
  CHECK(m.attributes[4].values == std::vector<float>{2, 2, 2, 2, 2});  // as in the file
  // Without the option: the file's v lines only, as before.
  const Mesh plain = load_text(obj, "quad.obj", false);
  CHECK(plain.vertex_count() == 4);
  CHECK(plain.attributes.empty());
  CHECK(plain.position_vertex.empty());
  CHECK(plain.triangles == std::vector<uint32_t>{0, 1, 2, 0, 2, 3});
  CHECK(position_welded(m).triangles == plain.triangles);
}

TEST_CASE("obj attributes: bad vt/vn references are one-line errors", "[io][simplify]") {
  const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\n";
  auto error_of = [&](const std::string& body) {
    try {
      load_text(head + body, "bad.obj", true);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(error_of("f 1/2 2/1 3/1\n") == "bad.obj: a face uses texture coordinate 2 but the file has 1");
  CHECK(error_of("f 1//1 2//1 3//1\n") == "bad.obj: a face uses normal 1 but the file has 0");
  CHECK(error_of("f 1/x 2/1 3/1\n") == "bad.obj: line 5: bad texture coordinate index '1/x'");
  CHECK(error_of("f 1/0 2/1 3/1\n") == "bad.obj: line 5: texture coordinate index 0 (OBJ indices start at 1)");
  CHECK(error_of("vt 0 nan\n") == "bad.obj: line 5: texture coordinate bad number 'nan'");
  CHECK(error_of("vn 0 1\n") == "bad.obj: line 5: normal needs 3 numbers");
  // The vertex as the file numbers it (from 1), not the 0-based index.
  CHECK(error_of("f 1/1 2/1 9/1\n").find("line 5: face index 9 is beyond the file's") != std::string::npos);
}

TEST_CASE("saliency of a UV-seamed sphere is the saliency of the same sphere without vt",
          "[simplify][saliency]") {
  const Mesh sphere = make_sphere(1.0, 4);
  size_t seam = 0;
  const std::string obj = attr_test::seamed_sphere_obj(sphere, &seam);
  const Mesh split = load_text(obj, "seamed.obj", true);
  const Mesh plain = load_text(obj, "seamed.obj", false);
  REQUIRE(seam > 10);
  REQUIRE(split.vertex_count() == plain.vertex_count() + seam);
  REQUIRE(split.position_vertex.size() == split.vertex_count());
  const SaliencyResult a = compute_saliency(split, cpu_saliency());
  const SaliencyResult b = compute_saliency(plain, cpu_saliency());
  REQUIRE(a.saliency.size() == split.vertex_count());
  CHECK(a.eps == b.eps);
  size_t differ = 0;
  double max_s = 0;
  for (size_t i = 0; i < split.vertex_count(); ++i) {
    const uint32_t p = split.position_vertex[i];
    differ += a.saliency[i] != b.saliency[p] || a.curvature[i] != b.curvature[p] || a.is_point[i] != 1;
    max_s = std::max(max_s, a.saliency[i]);
  }
  CHECK(differ == 0);
  CHECK(max_s > 0);
  // The split mesh taken as it is (the seam an open cut) would differ near the seam.
  Mesh cut = split;
  cut.position_vertex.clear();
  const SaliencyResult c = compute_saliency(cut, cpu_saliency());
  size_t cut_differ = 0;
  for (size_t i = 0; i < split.vertex_count(); ++i) cut_differ += c.curvature[i] != a.curvature[i];
  CHECK(cut_differ > seam);
}

TEST_CASE("simplify keeps a UV seam closed and every texture coordinate on its side", "[simplify]") {
  const Mesh sphere = make_sphere(1.0, 4);  // 5120 faces
  size_t seam = 0;
  const Mesh in = load_text(attr_test::seamed_sphere_obj(sphere, &seam), "seamed.obj", true);
  SimplifyOptions o;
  o.target_faces = 1000;
  const Simplified s = simplify_mesh(in, o);
  const Mesh& out = s.mesh;
  const SimplifyReport& rep = s.report;
  CHECK(out.triangle_count() == 1000);
  CHECK(rep.reached);
  const VertexAttribute* u = find(out, "u");
  const VertexAttribute* v = find(out, "v");
  const VertexAttribute* n[3] = {find(out, "nx"), find(out, "ny"), find(out, "nz")};
  REQUIRE(u);
  REQUIRE(v);
  REQUIRE((n[0] && n[1] && n[2]));
  // Seam vertices stay where they were with their texture coordinates, and go (along the
  // seam) only together with their twin: the seam stays closed.
  std::vector<uint8_t> is_twin(in.vertex_count(), 0);
  for (size_t i = 0; i < in.vertex_count(); ++i)
    if (in.position_vertex[i] != i) is_twin[i] = is_twin[in.position_vertex[i]] = 1;
  size_t twins_in = 0, twins_out = 0, moved = 0, uv_changed = 0;
  for (uint8_t x : is_twin) twins_in += x;
  const VertexAttribute* u_in = find(in, "u");
  for (size_t o2 = 0; o2 < out.vertex_count(); ++o2) {
    const uint32_t src = rep.vertex_origin[o2];
    if (!is_twin[src]) continue;
    ++twins_out;
    for (int k = 0; k < 3; ++k) moved += out.positions[3 * o2 + k] != in.positions[3 * size_t(src) + k];
    uv_changed += u->values[o2] != u_in->values[src];
  }
  CHECK(twins_in == 2 * seam);
  CHECK(twins_out < twins_in);     // some collapsed along the seam
  CHECK(twins_out > twins_in / 2);
  CHECK(moved == 0);
  CHECK(uv_changed == 0);
  // The output's twins point at each other: the seam is one surface.
  REQUIRE(out.position_vertex.size() == out.vertex_count());
  std::vector<size_t> group_size(out.vertex_count(), 0);
  for (uint32_t r : out.position_vertex) ++group_size[r];
  size_t lone_twins = 0;
  for (size_t o2 = 0; o2 < out.vertex_count(); ++o2)
    lone_twins += is_twin[rep.vertex_origin[o2]] && group_size[out.position_vertex[o2]] < 2;
  CHECK(lone_twins == 0);
  const simplify_test::Topology topo = simplify_test::topology(position_welded(out));
  CHECK(topo.border_edges == 0);
  CHECK(topo.nonmanifold_edges == 0);
  CHECK(topo.repeated_directed == 0);
  // No triangle's texture coordinates jump across the seam, and each vertex's
  // coordinates still map to (about) where it is on the sphere.
  double worst_span = 0, worst_u = 0, worst_v = 0, worst_normal = 1;
  for (size_t t = 0; t < out.triangle_count(); ++t) {
    float lo = 10, hi = -10;
    bool polar = false;  // around the poles a triangle may span any longitudes
    for (int k = 0; k < 3; ++k) {
      const float x = u->values[out.triangles[3 * t + k]];
      lo = std::min(lo, x);
      hi = std::max(hi, x);
      polar |= std::fabs(v->values[out.triangles[3 * t + k]] - 0.5) > 0.4;
    }
    if (!polar) worst_span = std::max(worst_span, double(hi - lo));
  }
  for (size_t i = 0; i < out.vertex_count(); ++i) {
    double pu, pv;
    attr_test::sphere_uv(&out.positions[3 * i], &pu, &pv);
    double du = std::fabs(u->values[i] - pu);
    du = std::min({du, std::fabs(du - 1), std::fabs(du + 1)});  // u + 1 on the seam's far side
    if (std::fabs(pv - 0.5) < 0.4) worst_u = std::max(worst_u, du);  // longitude is wild at the poles
    worst_v = std::max(worst_v, std::fabs(v->values[i] - pv));
    const float* p = &out.positions[3 * i];
    const double len = std::sqrt(double(n[0]->values[i]) * n[0]->values[i] + double(n[1]->values[i]) * n[1]->values[i] +
                                 double(n[2]->values[i]) * n[2]->values[i]);
    CHECK(std::fabs(len - 1) < 1e-5);  // renormalised
    const double r = std::sqrt(double(p[0]) * p[0] + double(p[1]) * p[1] + double(p[2]) * p[2]);
    worst_normal = std::min(worst_normal, (n[0]->values[i] * p[0] + n[1]->values[i] * p[1] + n[2]->values[i] * p[2]) / r);
  }
  INFO("span " << worst_span << " u " << worst_u << " v " << worst_v << " normal cos " << worst_normal);
  CHECK(worst_span < 0.2);
  CHECK(worst_u < 0.03);
  CHECK(worst_v < 0.02);
  CHECK(worst_normal > 0.995);
  // Collapsing along the seam, far targets are reached, the welded surface still closed.
  o.target_faces = 20;
  const Simplified small = simplify_mesh(in, o);
  CHECK(small.mesh.triangle_count() == 20);
  CHECK(small.report.reached);
  const simplify_test::Topology small_topo = simplify_test::topology(position_welded(small.mesh));
  CHECK(small_topo.nonmanifold_edges == 0);
  CHECK(small_topo.border_edges == 0);
  CHECK(small_topo.repeated_directed == 0);
  // With --lock-border the seam (a border of each side) is locked whole: the reduction
  // stops there, and the note says so.
  o.lock_border = true;
  const Simplified locked = simplify_mesh(in, o);
  CHECK(locked.mesh.triangle_count() == 96);
  CHECK_FALSE(locked.report.reached);
  CHECK(locked.report.note.find("locked (seam or border) vertices in place; stopped at 96") != std::string::npos);
  CHECK(simplify_test::topology(position_welded(locked.mesh)).nonmanifold_edges == 0);
}

TEST_CASE("simplify with locks and attributes: the heap matches the brute-force oracle", "[simplify]") {
  const Mesh sphere = make_sphere(1.0, 2);
  const Mesh seamed = load_text(attr_test::seamed_sphere_obj(sphere), "seamed.obj", true);
  const Mesh open = make_plane_with_bump(2.0, 10, 0.3, 0.3);
  struct Case {
    const Mesh* mesh;
    size_t faces;
    double error;
    bool lock_border;
  };
  for (const Case& c : {Case{&seamed, 120, 0, false}, Case{&seamed, 0, 0.01, false}, Case{&open, 40, 0, true},
                        Case{&open, 0, 0.002, true}, Case{&open, 0, 0.004, false}}) {
    SimplifyOptions o;
    o.target_faces = c.faces;
    o.target_error = c.error;
    o.lock_border = c.lock_border;
    o.record_collapses = true;
    const Simplified s = simplify_mesh(*c.mesh, o);
    const Mesh& a = s.mesh;
    const SimplifyReport& fast = s.report;
    SimplifyReport brute;
    const Mesh b = simplify_bruteforce(*c.mesh, o, nullptr, &brute);
    INFO("faces " << c.faces << " error " << c.error << " lock " << c.lock_border);
    REQUIRE(fast.sequence.size() == brute.sequence.size());
    CHECK(fast.sequence.size() > 10);
    for (size_t i = 0; i < fast.sequence.size(); ++i) {
      CHECK(fast.sequence[i].kept == brute.sequence[i].kept);
      CHECK(fast.sequence[i].removed == brute.sequence[i].removed);
    }
    CHECK(a.positions == b.positions);
    CHECK(a.triangles == b.triangles);
    CHECK(fast.error == brute.error);
  }
}

TEST_CASE("simplify: PLY vertex properties are interpolated and written back", "[simplify][io]") {
  // A flat grid whose properties are linear in x: interpolation along an edge is exact.
  const Mesh plane = make_plane(2.0, 16);  // 512 faces, in [-1, 1]^2
  Mesh in = plane;
  const size_t nv = in.vertex_count();
  VertexAttribute q{"quality", std::vector<float>(nv)}, red{"red", std::vector<float>(nv)};
  for (size_t i = 0; i < nv; ++i) {
    q.values[i] = 3 * in.positions[3 * i] + 1;
    red.values[i] = std::round(100 * (in.positions[3 * i] + 1));
  }
  in.attributes = {q, red};
  SimplifyOptions o;
  o.target_faces = 60;
  const Mesh out = simplify_mesh(in, o).mesh;
  REQUIRE(out.triangle_count() == 60);
  REQUIRE(out.attributes.size() == 2);
  double worst = 0;
  for (size_t i = 0; i < out.vertex_count(); ++i)
    worst = std::max(worst, double(std::fabs(out.attributes[0].values[i] - (3 * out.positions[3 * i] + 1))));
  CHECK(worst < 1e-5);

  meshsal_test::TempDir dir;
  const std::string path = dir.file("out.ply");
  write_ply(path, out, {});
  LoadOptions lo;
  lo.attributes = true;
  const Mesh back = read_mesh(path, lo).mesh;
  CHECK(back.positions == out.positions);
  CHECK(back.triangles == out.triangles);
  REQUIRE(back.attributes.size() == 2);
  CHECK(back.attributes[0].name == "quality");
  CHECK(back.attributes[0].values == out.attributes[0].values);
  CHECK(back.attributes[1].name == "red");  // uchar: rounded
  for (size_t i = 0; i < out.vertex_count(); ++i)
    CHECK(back.attributes[1].values[i] == std::round(std::min(255.f, std::max(0.f, out.attributes[1].values[i]))));
  const std::string text = meshsal_test::read_file(path);
  CHECK(text.find("property float quality\nproperty uchar red\n") != std::string::npos);
}

TEST_CASE("obj attributes survive write_obj and load_mesh, seams included", "[simplify][io]") {
  const Mesh sphere = make_sphere(1.0, 3);
  const Mesh in = load_text(attr_test::seamed_sphere_obj(sphere), "seamed.obj", true);
  SimplifyOptions o;
  o.target_faces = 400;
  const Mesh out = simplify_mesh(in, o).mesh;
  meshsal_test::TempDir dir;
  const std::string path = dir.file("out.obj");
  write_obj(path, out);
  const std::string text = meshsal_test::read_file(path);
  size_t v_lines = 0, vt_lines = 0, vn_lines = 0, pos = 0;
  for (std::string_view s(text); pos < s.size();) {
    const size_t end = s.find('\n', pos);
    const std::string_view line = s.substr(pos, end - pos);
    v_lines += line.substr(0, 2) == "v ";
    vt_lines += line.substr(0, 3) == "vt ";
    vn_lines += line.substr(0, 3) == "vn ";
    pos = end == std::string_view::npos ? s.size() : end + 1;
  }
  size_t positions = 0;
  for (size_t i = 0; i < out.vertex_count(); ++i) positions += out.position_vertex[i] == i;
  CHECK(v_lines == positions);  // twins share their v line
  CHECK(positions < out.vertex_count());
  CHECK(vt_lines == out.vertex_count());
  CHECK(vn_lines == out.vertex_count());
  LoadOptions lo;
  lo.attributes = true;
  const Mesh back = load_mesh(path, lo);
  REQUIRE(back.vertex_count() == out.vertex_count());
  REQUIRE(back.attributes.size() == out.attributes.size());
  // The reader numbers twins after the v lines: compare through the positions' order.
  std::multiset<std::vector<float>> a, b;
  for (const Mesh* m : {&out, &back})
    for (size_t i = 0; i < m->vertex_count(); ++i) {
      const std::vector<float> world = meshsal_test::world_floats(*m);
      std::vector<float> row(world.begin() + 3 * i, world.begin() + 3 * i + 3);
      for (const VertexAttribute& at : m->attributes) row.push_back(at.values[i]);
      (m == &out ? a : b).insert(row);
    }
  CHECK(a == b);
  CHECK(back.triangle_count() == out.triangle_count());
  CHECK(simplify_test::topology(position_welded(back)).border_edges == 0);
}

TEST_CASE("simplify --target-error: a plane goes to 2 triangles, a sphere keeps detail", "[simplify]") {
  const Mesh plane = make_plane(2.0, 12);  // 288 faces
  for (double e : {1e-4, 0.01, 0.05}) {
    SimplifyOptions o;
    o.target_error = e;
    const Simplified s = simplify_mesh(plane, o);
    const Mesh& out = s.mesh;
    const SimplifyReport& rep = s.report;
    INFO("error " << e);
    CHECK(out.triangle_count() == 2);
    CHECK(rep.error <= e);
    CHECK(rep.error < 1e-6);  // flat: nothing moved off the plane or the border lines
  }
  const Mesh sphere = make_sphere(1.0, 4);  // 5120 faces
  size_t last = 0;
  // Below the first collapse's error nothing happens.
  SimplifyOptions tiny;
  tiny.target_error = 0.0002;
  const Simplified tiny_s = simplify_mesh(sphere, tiny);
  CHECK(tiny_s.mesh.triangle_count() == 5120);
  CHECK(tiny_s.report.error == 0);
  for (double e : {0.0005, 0.002, 0.02}) {
    SimplifyOptions o;
    o.target_error = e;
    const Simplified s = simplify_mesh(sphere, o);
    const Mesh& out = s.mesh;
    const SimplifyReport& rep = s.report;
    INFO("error " << e << ": " << out.triangle_count() << " faces, reached " << rep.error);
    CHECK(rep.error <= e);
    CHECK(rep.error > 0.5 * e);  // it went as far as the bound allows
    CHECK(simplify_test::topology(out).border_edges == 0);
    if (last) CHECK(out.triangle_count() < last);
    last = out.triangle_count();
    if (e == 0.0005) CHECK(out.triangle_count() > 1500);
  }
  CHECK(last < 100);
  // With a face target too, whichever comes first.
  SimplifyOptions both;
  both.target_faces = 4000;
  both.target_error = 0.02;
  const Simplified s = simplify_mesh(sphere, both);
  CHECK(s.mesh.triangle_count() == 4000);
  CHECK(s.report.reached);
  both.target_error = -1;
  CHECK_THROWS_WITH(simplify_mesh(sphere, both).mesh, Catch::Contains("target error must be in [0, 1]"));
}

TEST_CASE("simplify --lock-border: an open grid keeps every border vertex in place", "[simplify]") {
  const Mesh grid = make_plane_with_bump(2.0, 16, 0.3, 0.4);  // 512 faces, 64 border vertices
  // The input's border edges, by input vertex.
  auto border_edges = [](const Mesh& m, const std::vector<uint32_t>* origin) {
    std::map<std::pair<uint32_t, uint32_t>, int> count;
    for (size_t t = 0; t < m.triangle_count(); ++t)
      for (int k = 0; k < 3; ++k) {
        uint32_t a = m.triangles[3 * t + k], b = m.triangles[3 * t + (k + 1) % 3];
        if (origin) a = (*origin)[a], b = (*origin)[b];
        count[{std::min(a, b), std::max(a, b)}]++;
      }
    std::set<std::pair<uint32_t, uint32_t>> out;
    for (auto& [e, n] : count)
      if (n == 1) out.insert(e);
    return out;
  };
  const auto before = border_edges(grid, nullptr);
  REQUIRE(before.size() == 64);
  for (bool lock : {true, false}) {
    SimplifyOptions o;
    o.target_faces = 100;
    o.lock_border = lock;
    const Simplified s = simplify_mesh(grid, o);
    const Mesh& out = s.mesh;
    const SimplifyReport& rep = s.report;
    CHECK(out.triangle_count() == 100);
    size_t kept_in_place = 0;
    std::set<uint32_t> border_vertices;
    for (auto& e : before) border_vertices.insert({e.first, e.second});
    for (size_t i = 0; i < out.vertex_count(); ++i) {
      const uint32_t src = rep.vertex_origin[i];
      if (!border_vertices.count(src)) continue;
      bool same = true;
      for (int k = 0; k < 3; ++k) same &= out.positions[3 * i + k] == grid.positions[3 * size_t(src) + k];
      kept_in_place += same;
    }
    INFO("lock " << lock);
    if (lock) {
      CHECK(kept_in_place == 64);
      CHECK(border_edges(out, &rep.vertex_origin) == before);
    } else {
      CHECK(kept_in_place < 64);  // without the lock the straight borders are simplified
    }
  }
}
