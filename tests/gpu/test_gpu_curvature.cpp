// The GPU mean curvature (gpu_curvature.h) against its CPU twins, mean_curvature_morton()
// (Morton order, the fast method's) and mean_curvature() over the 1-rings of
// build_adjacency_reference() (input order, the exact method's): the same bits per vertex,
// on synthetic meshes (loose vertices, degenerate and repeated triangles, non-manifold
// edges, a flat plane), a real scan, under forced staging, and the incidence it keeps.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cli/synthetic.h"
#include "core/adjacency.h"
#include "core/mesh_points.h"
#include "gpu/gpu_curvature.h"
#include "gpu/gpu_fast.h"
#include "gpu/gpu_saliency.h"
#include "gpu/gpu_sweep.h"
#include "gpu/vk_compute.h"
#include "gpu/vk_context.h"
#include "meshsal/meshsal.h"
#include "saliency/curvature.h"
#include "saliency/saliency.h"
#include "scoped_value.h"
#include "test_util.h"

using namespace meshsal;

namespace {

std::vector<double> gpu_curvature(vk::Context& ctx, const Mesh& mesh, const BoundingBox& box, bool* complete,
                                  gpu::TriangleOrder triangle_order = gpu::TriangleOrder::morton) {
  const size_t nv = mesh.vertex_count();
  std::vector<float> p32(4 * nv, 0.0f);
  for (size_t v = 0; v < nv; ++v)
    for (int a = 0; a < 3; ++a) p32[4 * v + a] = mesh.positions[3 * v + a];
  std::vector<double> p(4 * nv, 7.0);  // w overwritten with H
  vk::Buffer pos32(ctx, p32.size() * 4, "test"), pos(ctx, p.size() * 8, "test");
  pos32.upload(p32.data(), p32.size() * 4);
  pos.upload(p.data(), p.size() * 8);
  gpu::DeviceCurvature dc(ctx, mesh, pos32, pos, box, triangle_order);
  vk::submit(ctx, "test", [&](VkCommandBuffer cmd) { dc.record(ctx, cmd); });
  *complete = dc.complete();
  pos.download(p.data(), p.size() * 8);
  std::vector<double> H(nv);
  for (size_t v = 0; v < nv; ++v) H[v] = p[4 * v + 3];
  // The incidence: each vertex's entries name triangles that hold it.
  std::vector<uint32_t> start(nv + 1), entry(3 * mesh.triangle_count()), order(mesh.triangle_count());
  dc.start.download(start.data(), start.size() * 4);
  dc.entry().download(entry.data(), entry.size() * 4);
  dc.triangle_order().download(order.data(), order.size() * 4);
  CHECK(start[nv] == 3 * mesh.triangle_count());
  for (size_t v = 0; v < nv; ++v)
    for (uint32_t j = start[v]; j < start[v + 1]; ++j) {
      const uint32_t f = order[entry[j] / 3], c = entry[j] % 3;
      if (mesh.triangles[3 * f + c] != v) FAIL("vertex " << v << " entry " << j << " names another corner");
      // In input order each vertex meets its triangles in index order, corner by corner.
      if (triangle_order == gpu::TriangleOrder::input && j > start[v] && entry[j] <= entry[j - 1])
        FAIL("vertex " << v << " entry " << j << " out of input order");
    }
  return H;
}

// The exact method's H the slow way: the 1-rings from one sorted list of all half-edges.
std::vector<double> rings_oracle(const Mesh& mesh) {
  return mean_curvature(mesh, build_adjacency_reference(mesh), vertex_normals(mesh), 1);
}

void check_same_bits(vk::Context& ctx, const Mesh& mesh, const std::string& what,
                     gpu::TriangleOrder triangle_order = gpu::TriangleOrder::morton) {
  INFO(what << (triangle_order == gpu::TriangleOrder::input ? " (input order)" : " (Morton order)"));
  const uint64_t before = vk::validation_message_count();
  const BoundingBox box = mesh_points_bbox(mesh, referenced_vertices(mesh));
  const std::vector<double> cpu =
      triangle_order == gpu::TriangleOrder::input ? rings_oracle(mesh) : mean_curvature_morton(mesh, box, 2);
  bool complete = false;
  const std::vector<double> gpu = gpu_curvature(ctx, mesh, box, &complete, triangle_order);
  CHECK(complete);
  REQUIRE(gpu.size() == cpu.size());
  size_t differ = 0, first = 0;
  for (size_t v = 0; v < cpu.size(); ++v)
    if (std::memcmp(&cpu[v], &gpu[v], 8) != 0 && differ++ == 0) first = v;
  INFO("first differing vertex " << first << ": cpu " << cpu[first] << " gpu " << gpu[first]);
  CHECK(differ == 0);
  CHECK(vk::validation_message_count() == before);
}

// A cone of n triangles around its apex (vertex 0), its rim at height bump * sin(40 a).
Mesh make_cone(int n, double bump) {
  Mesh m;
  m.positions = {0, 0, 1};
  for (int i = 0; i < n; ++i) {
    const double a = 2 * 3.141592653589793 * i / n;
    m.positions.insert(m.positions.end(), {float(std::cos(a)), float(std::sin(a)), float(bump * std::sin(40 * a))});
  }
  for (int i = 0; i < n; ++i) m.triangles.insert(m.triangles.end(), {0u, uint32_t(1 + i), uint32_t(1 + (i + 1) % n)});
  return m;
}

vk::Context& context() {
  static std::unique_ptr<vk::Context> ctx = std::make_unique<vk::Context>(-1, true);
  return *ctx;
}

}  // namespace

TEST_CASE("gpu curvature: the same bits as mean_curvature_morton", "[gpu][curvature]") {
  vk::Context& ctx = context();
  check_same_bits(ctx, make_bumpy_sphere(4), "bumpy sphere");
  check_same_bits(ctx, make_cube(12), "cube");
  check_same_bits(ctx, make_plane_with_bump(2.0, 40, 0.3, 0.2), "plane with bump");
  Mesh odd = make_bumpy_sphere(3);
  odd.positions.insert(odd.positions.end(), {0.1f, 0.2f, 0.3f, 5.0f, 5.0f, 5.0f});  // loose vertices
  odd.triangles.insert(odd.triangles.end(), {0, 0, 5, 1, 2, 1, 3, 4, 5, 3, 4, 5});   // degenerate, repeated
  check_same_bits(ctx, odd, "bumpy sphere with loose vertices, degenerate and repeated triangles");
}

// A mesh whose neighbour order is not its triangle order: the vertices renumbered by a
// fixed shuffle, the triangles listed backwards.
Mesh shuffled(const Mesh& in) {
  const size_t nv = in.vertex_count();
  std::vector<uint32_t> to(nv);
  for (size_t v = 0; v < nv; ++v) to[v] = uint32_t((v * 7919 + 13) % nv);  // 7919 prime: a bijection unless nv divides
  Mesh out;
  out.positions.resize(in.positions.size());
  for (size_t v = 0; v < nv; ++v)
    for (int a = 0; a < 3; ++a) out.positions[3 * to[v] + a] = in.positions[3 * v + a];
  for (size_t f = in.triangle_count(); f-- > 0;)
    for (int c = 0; c < 3; ++c) out.triangles.push_back(to[in.triangles[3 * f + c]]);
  return out;
}

TEST_CASE("gpu curvature in input order: the same bits as mean_curvature over the 1-rings", "[gpu][curvature]") {
  vk::Context& ctx = context();
  const auto input = gpu::TriangleOrder::input;
  check_same_bits(ctx, make_bumpy_sphere(4), "bumpy sphere", input);
  check_same_bits(ctx, make_cube(12), "cube", input);
  check_same_bits(ctx, make_plane_with_bump(2.0, 40, 0.3, 0.2), "plane with bump", input);
  const Mesh sphere = make_bumpy_sphere(3);
  REQUIRE(sphere.vertex_count() % 7919 != 0);
  check_same_bits(ctx, shuffled(sphere), "bumpy sphere, shuffled", input);
  Mesh odd = make_bumpy_sphere(3);
  const uint32_t n = uint32_t(odd.vertex_count());
  odd.positions.insert(odd.positions.end(), {0.1f, 0.2f, 0.3f, 5.0f, 5.0f, 5.0f, 0.5f, 0.5f, 2.0f});
  odd.triangles.insert(odd.triangles.end(), {
      0, 0, 5,  1, 2, 1,  3, 4, 5,  3, 4, 5,  // degenerate, repeated
      5, 4, 3,                                // the same triangle reversed
      6, 7, 7,  8, 8, 8,                      // (v, j, j): two edges v-j; (v, v, v): none
      3, 4, n + 2,                            // a third triangle on edge 3-4
      n + 1, n + 2, 9});                      // far vertices: long, skewed edges
  check_same_bits(ctx, odd, "bumpy sphere with loose vertices, degenerate, repeated and non-manifold triangles",
                  input);
  // Float denormals (which a device may flush when converting) and coordinates near float's
  // largest, whose products need double's range.
  Mesh extreme;
  extreme.positions = {0, 0, 0, 1e-45f, 0, 0, 0, 3e-44f, 0, 0, 0, 1e-40f,
                       3e38f, 0, 0, 0, -3e38f, 0, 0, 0, 2e38f};
  extreme.triangles = {0, 1, 2, 0, 2, 3, 0, 3, 1, 4, 5, 6, 0, 4, 5};
  check_same_bits(ctx, extreme, "denormal and huge coordinates", input);
  // A pair of opposite triangles: the normals cancel at every corner (H 0).
  Mesh flat;
  flat.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0.3f, 0.3f, 0.5f};
  flat.triangles = {0, 1, 2, 0, 2, 1, 0, 1, 3};
  check_same_bits(ctx, flat, "opposite triangles", input);
}

TEST_CASE("gpu curvature: a real scan, and under forced staging", "[gpu][curvature]") {
  MESHSAL_REQUIRE_MESH(path, "bunny_36k.obj");
  const Mesh bunny = load_mesh(path);
  check_same_bits(context(), bunny, "bunny_36k");
  vk::Context ctx(-1, true);
  ctx.use_staging = true;
  check_same_bits(ctx, make_bumpy_sphere(3), "bumpy sphere, staged");
  check_same_bits(context(), bunny, "bunny_36k", gpu::TriangleOrder::input);
  check_same_bits(ctx, make_bumpy_sphere(3), "bumpy sphere, staged", gpu::TriangleOrder::input);
}

TEST_CASE("gpu curvature: a vertex of more triangles than an invocation may visit is flagged", "[gpu][curvature]") {
  // A fan of 20000 triangles around vertex 0: its H is left to the host.
  const Mesh fan = make_cone(20000, 0.0);
  const BoundingBox box = mesh_points_bbox(fan, referenced_vertices(fan));
  bool complete = true;
  const std::vector<double> gpu = gpu_curvature(context(), fan, box, &complete);
  CHECK(!complete);
  const std::vector<double> cpu = mean_curvature_morton(fan, box, 2);
  CHECK(gpu[1] == cpu[1]);  // the rim's are computed
  CHECK(gpu[0] == 0.0);
}

TEST_CASE("gpu curvature in input order: a vertex of more than 64 corners is flagged", "[gpu][curvature]") {
  // Each neighbour costs a pass over the vertex's corners: past 64 the host takes it.
  const Mesh fan = make_cone(65, 0.02);
  const BoundingBox box = mesh_points_bbox(fan, referenced_vertices(fan));
  bool complete = true;
  const std::vector<double> gpu = gpu_curvature(context(), fan, box, &complete, gpu::TriangleOrder::input);
  CHECK(!complete);
  const std::vector<double> cpu = rings_oracle(fan);
  CHECK(gpu[1] == cpu[1]);  // the rim's are computed
  CHECK(gpu[0] == 0.0);
  check_same_bits(context(), make_cone(64, 0.02), "a fan of 64 triangles", gpu::TriangleOrder::input);
  // The most loop steps a vertex may take: 64 triangles that share no other corner, so 128
  // distinct neighbours (a wrong bound would have lavapipe end the loops early).
  Mesh bow_tie;
  bow_tie.positions = {0, 0, 0};
  for (int i = 0; i < 128; ++i) {
    const double a = 2 * 3.141592653589793 * i / 128;
    bow_tie.positions.insert(bow_tie.positions.end(),
                             {float(std::cos(a)), float(std::sin(a)), float(0.1 * std::sin(7 * a))});
  }
  for (uint32_t i = 0; i < 64; ++i) bow_tie.triangles.insert(bow_tie.triangles.end(), {0u, 2 * i + 1, 2 * i + 2});
  check_same_bits(context(), bow_tie, "64 triangles, 128 neighbours", gpu::TriangleOrder::input);
}

// The exact method on the GPU against the CPU: the curvature bit for bit, the maps as
// test_gpu_saliency.cpp holds them.
void check_exact(const Mesh& mesh, const std::string& what) {
  INFO(what);
  SaliencyOptions opt;
  opt.method = Method::Exact;
  opt.precision = Precision::Double;
  opt.threads = 2;
  const uint64_t before = vk::validation_message_count();
  SaliencyResult gpu;
  {
    // lavapipe, a CPU device, would take the host's
    const meshsal_test::ScopedValue<int> on_device(context().exact_curvature_on_device, 1);
    gpu = compute_saliency_gpu(context(), mesh, opt);
  }
  const SaliencyResult cpu = compute_saliency_cpu(mesh, opt);
  CHECK(vk::validation_message_count() == before);
  REQUIRE(gpu.curvature.size() == cpu.curvature.size());
  CHECK(std::memcmp(gpu.curvature.data(), cpu.curvature.data(), 8 * cpu.curvature.size()) == 0);
  meshsal_test::check_maps_match(cpu, gpu, opt.scales, 1e-4, 1e-4);
}

TEST_CASE("gpu exact saliency: vertices past the limits take the host's curvature", "[gpu][curvature]") {
  // Past 64 triangles: that vertex's H from the host, the rest from the device.
  check_exact(make_cone(1500, 0.05), "a fan of 1500 triangles");
  // Past 16,384: the host's H and the suppression over the 1-rings.
  check_exact(make_cone(20000, 0.05), "a fan of 20000 triangles");
}

TEST_CASE("gpu fast saliency: a vertex past the limit takes the host's curvature and the 1-rings", "[gpu][curvature]") {
  // A cone of 20000 triangles around its apex, with a ring of bumps: the apex is flagged.
  const Mesh fan = make_cone(20000, 0.05);
  SaliencyOptions opt;
  opt.method = Method::Fast;
  opt.threads = 2;
  const uint64_t before = vk::validation_message_count();
  const SaliencyResult gpu = compute_saliency_gpu(context(), fan, opt);
  const SaliencyResult cpu = compute_saliency_cpu(fan, opt);
  CHECK(vk::validation_message_count() == before);
  CHECK(gpu.curvature == cpu.curvature);  // the host's H, the CPU fast path's bits
  meshsal_test::check_maps_match(cpu, gpu, opt.scales, 1e-4, 1e-4);
}

TEST_CASE("gpu exact saliency: where the device curvature's sorts do not fit, the host computes H", "[gpu][curvature]") {
  // bumpy sphere 5 (10k vertices), exact in double: about 9 MiB with the host's curvature
  // and 1-rings, about 12 with the device's (more with a staging area). The device's memory
  // grows a MiB at a time: refused, then the host's H (64 bytes a vertex uploaded: positions
  // in double with H, flags, 1-rings), then the device's (40: float positions, triangles).
  const Mesh m = make_bumpy_sphere(5);
  SaliencyOptions opt;
  opt.precision = Precision::Double;
  opt.threads = 2;
  std::vector<int> seen;  // bytes a vertex of each run that fitted, rounded
  SaliencyResult host, device;
  for (int mib = 4; mib <= 32 && (seen.empty() || seen.back() != 40); ++mib) {
    vk::Context ctx(-1, true);
    ctx.exact_curvature_on_device = 1;
    ctx.info.device_local_bytes = uint64_t(mib) << 20;
    const uint64_t sent = ctx.uploaded_bytes;
    SaliencyResult r;
    try {
      r = compute_saliency_gpu(ctx, m, opt);
    } catch (const Error& e) {
      CHECK(seen.empty());  // only below the first that fits
      CHECK_THAT(e.what(), Catch::Contains("mesh too large"));
      continue;
    }
    seen.push_back(int(std::lround(double(ctx.uploaded_bytes - sent) / double(m.vertex_count()))));
    (seen.back() == 64 ? host : device) = std::move(r);
  }
  REQUIRE(seen.size() >= 2);
  CHECK(seen.front() == 64);
  CHECK(seen.back() == 40);
  REQUIRE(host.curvature.size() == m.vertex_count());
  REQUIRE(device.curvature.size() == m.vertex_count());
  CHECK(std::memcmp(host.curvature.data(), device.curvature.data(), 8 * m.vertex_count()) == 0);
  CHECK(host.saliency == device.saliency);
}

TEST_CASE("gpu mixed sweep: the near ties found over the triangles are those over the 1-rings", "[gpu][curvature]") {
  // The same run with the host's curvature and 1-rings (near_tie.comp) and with the
  // device's and its incidence (near_tie_faces.comp): the same points swept again, so the
  // same bits everywhere.
  std::vector<std::pair<Mesh, std::string>> meshes;
  meshes.emplace_back(make_bumpy_sphere(4), "bumpy sphere");
  meshes.emplace_back(make_plane_with_bump(2.0, 40, 0.3, 0.2), "plane with bump: ties on its flat part");
  const std::string fandisk = meshsal_test::shared_mesh("fandisk_6k.obj");
  if (!fandisk.empty()) meshes.emplace_back(load_mesh(fandisk), "fandisk_6k");
  for (const auto& [mesh, what] : meshes) {
    INFO(what);
    SaliencyOptions opt;
    opt.precision = Precision::Mixed;
    opt.threads = 2;
    SaliencyResult rings, faces;
    {
      const meshsal_test::ScopedValue<int> host(context().exact_curvature_on_device, 0);
      rings = compute_saliency_gpu(context(), mesh, opt);
    }
    {
      const meshsal_test::ScopedValue<int> device(context().exact_curvature_on_device, 1);
      faces = compute_saliency_gpu(context(), mesh, opt);
    }
    CHECK(rings.mixed_precision);
    CHECK(faces.mixed_precision);
    CHECK(rings.rechecked > 0);
    CHECK(faces.rechecked == rings.rechecked);
    CHECK(faces.curvature == rings.curvature);
    CHECK(faces.saliency == rings.saliency);
  }
}

TEST_CASE("gpu near ties over the triangles: both ends of a tied edge are marked, whichever corner it is", "[gpu][curvature]") {
  // One open fan: triangles (0, 1, 2), (0, 2, 3), (0, 3, 4). Every raw value apart (bound 0)
  // but two neighbours' equal: each tied pair marks its two ends, whether the other end
  // follows the vertex in its triangle or comes before it (boundary edges have one each).
  Mesh fan;
  fan.positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, -1, 1, 0};
  fan.triangles = {0, 1, 2, 0, 2, 3, 0, 3, 4};
  const uint32_t nv = 5, nmaps = 2;
  vk::Context& ctx = context();
  const vk::Buffer pos32 = gpu::upload_float_positions(ctx, fan);
  vk::Buffer pos(ctx, size_t(nv) * 32, "test");
  const BoundingBox box = mesh_points_bbox(fan, referenced_vertices(fan));
  gpu::DeviceCurvature dc(ctx, fan, pos32, pos, box, gpu::TriangleOrder::input);
  vk::submit(ctx, "test", [&](VkCommandBuffer cmd) { dc.record(ctx, cmd); });
  const std::vector<uint32_t> flags(nv, 1);
  const std::vector<float> bound(nmaps * nv, 0.0f);
  vk::Buffer raw(ctx, size_t(nmaps) * nv * 8, "test"), is_point(ctx, nv * 4, "test"), err(ctx, bound.size() * 4, "test");
  is_point.upload(flags.data(), flags.size() * 4);
  err.upload(bound.data(), bound.size() * 4);
  vk::DescriptorPool pool(ctx, 8, 32);
  gpu::NearTieBuffers nb{&raw, &is_point, &err, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr};
  nb.start = &dc.start;
  nb.entry = &dc.entry();
  nb.order = &dc.triangle_order();
  nb.triangles = &dc.triangles;
  const meshsal_test::ScopedValue<bool> marks_only(gpu::test_skip_recheck, true);
  auto marked = [&](uint32_t a, uint32_t b, int map) {  // how many points one tie marks
    std::vector<double> values(nmaps * nv);
    for (size_t i = 0; i < values.size(); ++i) values[i] = 10.0 * double(i);
    values[map * nv + b] = values[map * nv + a];
    raw.upload(values.data(), values.size() * 8);
    return gpu::recheck_near_ties(ctx, pool, nb, nv, nmaps, gpu::SweepPush{});
  };
  CHECK(marked(0, 1, 0) == 2);  // 1 follows 0 in (0, 1, 2), 0 follows 1 nowhere
  CHECK(marked(0, 4, 1) == 2);  // 4 comes before 0 in (0, 3, 4)
  CHECK(marked(1, 2, 0) == 2);
  CHECK(marked(3, 4, 1) == 2);
  CHECK(marked(1, 3, 0) == 0);  // not neighbours
  CHECK(marked(0, 2, 1) == 2);  // an inner edge
}
