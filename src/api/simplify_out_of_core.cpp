// simplify_file(): tiled simplification of a mesh larger than memory. The input goes into
// a TileStore (as for saliency_file), the weights come from the tiles' saliency, and the
// passes of simplify_mesh_tiled run over the mesh on disk (disk_simplify.h); the output
// is streamed in the input's vertex order.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>

#include "api/disk_simplify.h"
#include "core/streamed_percentile.h"
#include "api/tile_saliency.h"
#include "api/tile_store.h"
#include "api/memory_size.h"
#include "core/cancel.h"
#include "core/model_frame.h"
#include "core/stage_clock.h"
#include "core/timer.h"
#include "io/atomic_write.h"
#include "io/output_check.h"
#include "meshsal/meshsal.h"
#include "saliency/saliency.h"
#include "simplify/saliency_weights.h"
#include "simplify/simplify.h"
#include "simplify/simplify_tiled.h"

namespace meshsal {

using namespace simplify_detail;

namespace {

// What one vertex of a tile's piece costs simplify_tile at its peak (the simplifier's
// state, the piece and its copy out), measured on igea_loop1 (README "Out of core").
constexpr double kSimplifyBytesPerVertex = 520;
constexpr size_t kBlock = 1 << 16;  // vertices per block of the streamed steps

// The most mesh points in one cell of `grid`, from the store's histogram (each bin counted
// in the cell of its centre: an estimate, not a bound).
uint64_t largest_cell(const TileStore& store, const TileGrid& grid) {
  const PointHistogram& h = store.histogram;
  const int n = PointHistogram::kBins;
  std::unordered_map<uint64_t, uint64_t> cells;
  uint64_t largest = 0;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const uint32_t c = h.count[(size_t(z) * n + y) * n + x];
        if (c == 0) continue;
        const int i[3] = {x, y, z};
        double p[3];
        for (int a = 0; a < 3; ++a) p[a] = h.box.min[a] + (i[a] + 0.5) * h.bin[a];
        largest = std::max(largest, cells[grid.cell_of(p)] += c);
      }
  return largest;
}

// Triangles without a repeated corner (simplify_mesh_tiled drops the others), from the
// store's to `path`; returns how many.
uint64_t surface_triangles(const TileStore& store, const std::string& path) {
  ScratchWriter out(path);
  std::vector<uint32_t> t(3 * kBlock);
  uint64_t kept = 0;
  for (uint64_t first = 0; first < store.triangles; first += kBlock) {
    const size_t count = size_t(std::min<uint64_t>(kBlock, store.triangles - first));
    read_triangles(store, first, count, t.data());
    for (size_t i = 0; i < count; ++i) {
      const uint32_t* v = &t[3 * i];
      if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) continue;
      out.write(v, 12);
      ++kept;
    }
  }
  out.close();
  return kept;
}

// The output: the vertices the triangles use (all of them with keep_all), in id order,
// then the triangles, as write_ply() writes a mesh with those vertices and attributes.
void write_output(const std::string& output, const TileStore& store, const DiskMesh& mesh, bool keep_all,
                  const std::function<void(double)>& progress, SimplifyReport& report) {
  VertexBits used(mesh.vertices);
  {
    ScratchReader in(mesh.triangles);
    std::vector<uint32_t> t(3 * kBlock);
    for (size_t got; (got = in.read(t.data(), t.size() * 4) / 4) > 0;)
      for (size_t i = 0; i < got; ++i) used.set(t[i]);
  }
  // Output index of a vertex: the used vertices before it (a count per 64 ids).
  const std::vector<uint64_t>& words = used.words();
  std::vector<uint32_t> before(words.size() + 1, 0);
  for (size_t i = 0; i < words.size(); ++i)
    before[i + 1] = before[i] + uint32_t(keep_all ? 64 : __builtin_popcountll(words[i]));
  const uint64_t nv = keep_all ? mesh.vertices : before.back();
  auto index_of = [&](uint32_t v) {
    return keep_all ? v : before[v >> 6] + uint32_t(__builtin_popcountll(words[v >> 6] & ((uint64_t(1) << (v & 63)) - 1)));
  };
  const size_t rec = mesh.record_bytes(), nattr = mesh.attribute_names.size();
  // Every used vertex's local position, attributes and source, a block at a time.
  auto for_each_vertex = [&](const std::function<void(uint64_t, const float*, const double*)>& body) {
    std::vector<uint8_t> state(kBlock * rec);
    std::vector<double> xyz(3 * kBlock);
    ScratchReader in(mesh.state);
    for (uint64_t first = 0; first < mesh.vertices; first += kBlock) {
      const size_t count = size_t(std::min<uint64_t>(kBlock, mesh.vertices - first));
      in.read_exact(state.data(), count * rec);
      read_source_positions(store, first, count, xyz.data());
      for (size_t i = 0; i < count; ++i)
        if (keep_all || used[uint32_t(first + i)])
          body(first + i, reinterpret_cast<const float*>(&state[i * rec]), &xyz[3 * i]);
    }
  };
  // Double where float would move a coordinate (positions_need_double's rule).
  bool wide = store.double_positions;
  if (!wide) {
    BoundingBox box;
    for (int k = 0; k < 3; ++k) box.min[k] = HUGE_VAL, box.max[k] = -HUGE_VAL;
    for_each_vertex([&](uint64_t, const float* p, const double*) {
      for (int k = 0; k < 3; ++k) box.min[k] = std::min(box.min[k], double(p[k])), box.max[k] = std::max(box.max[k], double(p[k]));
    });
    double d2 = 0;
    for (int k = 0; k < 3; ++k)
      if (box.min[k] <= box.max[k]) d2 += (box.max[k] - box.min[k]) * (box.max[k] - box.min[k]);
    const double tolerance = 1e-7 * std::sqrt(d2);
    for_each_vertex([&](uint64_t, const float* p, const double* source) {
      double m[3];
      model_coordinates(source, p, store.origin, m);
      for (int k = 0; k < 3; ++k) wide |= std::fabs(double(float(m[k])) - m[k]) > tolerance;
    });
  }
  std::string header = "ply\nformat binary_little_endian 1.0\ncomment written by meshsal\n";
  header += "element vertex " + std::to_string(nv) + "\n";
  header += wide ? "property double x\nproperty double y\nproperty double z\n"
                 : "property float x\nproperty float y\nproperty float z\n";
  for (const std::string& name : mesh.attribute_names) header += "property float " + name + "\n";
  header += "element face " + std::to_string(mesh.triangle_count) + "\n";
  header += "property list uchar int vertex_indices\nend_header\n";
  write_file_atomically(output, [&](std::FILE* f) {
    write_all(f, header.data(), header.size(), output);
    std::vector<char> buf;
    auto put = [&](const void* p, size_t n) { buf.insert(buf.end(), (const char*)p, (const char*)p + n); };
    for_each_vertex([&](uint64_t v, const float* p, const double* source) {
      if (v % kBlock == 0 && progress) progress(0.5 * double(v) / double(mesh.vertices));
      double m[3];
      model_coordinates(source, p, store.origin, m);
      for (int k = 0; k < 3; ++k) {
        if (wide) put(&m[k], 8);
        else {
          const float x = float(m[k]);
          put(&x, 4);
        }
      }
      put(p + 3, 4 * nattr);
      if (buf.size() >= (1 << 20)) write_all(f, buf.data(), buf.size(), output), buf.clear();
    });
    ScratchReader in(mesh.triangles);
    std::vector<uint32_t> t(3 * kBlock);
    uint64_t done = 0;
    for (size_t got; (got = in.read(t.data(), t.size() * 4) / 12) > 0; done += got) {
      if (progress) progress(0.5 + 0.5 * double(done) / double(std::max<uint64_t>(1, mesh.triangle_count)));
      for (size_t i = 0; i < got; ++i) {
        buf.push_back(3);
        for (int k = 0; k < 3; ++k) {
          const int32_t x = int32_t(index_of(t[3 * i + k]));
          put(&x, 4);
        }
      }
      write_all(f, buf.data(), buf.size(), output);
      buf.clear();
    }
    write_all(f, buf.data(), buf.size(), output);
  });
  report.output_vertices = size_t(nv);
  report.output_faces = size_t(mesh.triangle_count);
}

}  // namespace

OutOfCoreSimplifyReport simplify_file(const std::string& input, const std::string& output,
                                      const SimplifyOptions& options, const SaliencyWeightOptions* weights,
                                      const SaliencyOptions& saliency_options, const OutOfCoreOptions& ooc,
                                      unsigned tiles) {
  const CancelScope cancel(options.cancel ? options.cancel : saliency_options.cancel);
  if (options.target_error > 0)
    throw Error("simplify: out of core takes a face target (target_faces or ratio), not target_error");
  if (options.record_collapses) throw Error("simplify: out of core does not record the collapses");
  if (tiles > kMaxSimplifyTiles)
    throw Error("simplify: at most " + std::to_string(kMaxSimplifyTiles) + " tiles along the longest axis, got " +
                std::to_string(tiles));
  SaliencyOptions so = saliency_options;
  so.smoothed = true;
  if (so.method == Method::Auto) so.method = Method::Fast;
  if (weights) {
    check_weight_options(*weights);
    if (weights->curve == WeightCurve::Rank)
      throw Error("simplify: the rank curve needs every point's rank at once: out of core takes the threshold and "
                  "continuous curves");
    check_saliency_options(so);
    if (so.backend == Backend::Gpu) throw Error("out of core runs on the CPU: use backend cpu or auto");
    if (so.exchange) throw Error("simplify: out of core runs in one process (no TileExchange)");
  }
  OutOfCoreSimplifyReport report;
  const Timer t0;
  StageClock clock(report.stages);
  auto progress = [&](const char* stage, double f) {
    if (so.progress) so.progress(stage, f);
  };
  // Before the work: a .ply name, never the input (as saliency_file).
  check_ply_output("simplify_file", output, input);

  // The input on disk; with weights its tiles fit the limit for the saliency too.
  TileStore store(ooc.temp_dir);
  if (so.notice && !store.dir.note().empty()) so.notice(store.dir.note());
  build_tile_store(store, input, so, weights ? ooc.memory_limit : 0, weights ? std::max(1u, so.tiles) : 1, progress);
  clock.lap("tiling");
  report.saliency.vertices = store.vertices;
  report.saliency.points = store.points;
  report.saliency.triangles = store.triangles;
  DiskMesh mesh;
  mesh.dir = &store.dir;
  mesh.vertices = store.vertices;
  for (int k = 0; k < 3; ++k) mesh.origin[k] = store.origin[k];
  mesh.triangles = store.dir.file("simplify_tri.u32");
  const uint64_t faces = surface_triangles(store, mesh.triangles);
  mesh.triangle_count = faces;
  if (faces > UINT32_MAX) throw Error(input + ": more than 4294967295 triangles");
  SimplifyReport& rep = report.simplify;
  rep.input_faces = size_t(faces);
  const bool keep = simplify_keeps_mesh(options, size_t(faces));
  const size_t target = keep ? size_t(faces) : resolve_target_faces(options, size_t(faces));
  rep.target_faces = target;
  // A target at or above the face count: the mesh as it was read, every vertex and
  // triangle, no saliency (as simplify_mesh and the command do).
  if (keep) {
    weights = nullptr;
    mesh.triangles = store.dir.file("tri.u32");
    mesh.triangle_count = store.triangles;
  }

  // The vertex state (position, S) and the weights, a block of vertices at a time.
  mesh.state = store.dir.file("state.f32");
  if (weights) {
    mesh.attribute_names = {"quality"};
    tile_saliency(store, so, report.saliency);
    clock.lap("saliency");
  }
  {
    const size_t scales = so.scales.size(), rec = mesh.record_bytes();
    ScratchWriter state(mesh.state), sm(store.dir.file("sm.f64"));
    ScratchReader pos(store.dir.file("pos.f32"));
    std::vector<float> p(3 * kBlock), r(kBlock * rec / 4);
    std::vector<double> values, smooth(kBlock);
    std::vector<uint8_t> point;
    for (uint64_t first = 0; first < store.vertices; first += kBlock) {
      const size_t count = size_t(std::min<uint64_t>(kBlock, store.vertices - first));
      pos.read_exact(p.data(), 12 * count);
      if (weights) read_tile_results(store, scales, first, count, values, point);
      for (size_t i = 0; i < count; ++i) {
        float* out = &r[i * rec / 4];
        for (int k = 0; k < 3; ++k) out[k] = p[3 * i + k];
        if (weights) {
          out[3] = float(values[i * (kResultWidth + scales)]);  // S, as set_vertex_attribute stores it
          smooth[i] = point[i] ? values[i * (kResultWidth + scales) + 1] : NAN;
        }
      }
      state.write(r.data(), count * rec);
      if (weights) sm.write(smooth.data(), count * 8);
    }
    state.close();
    sm.close();
  }
  if (weights && !keep) {
    const std::string sm_path = store.dir.file("sm.f64");
    const ValueStream points = [&](const std::function<void(double)>& take) {
      ScratchReader in(sm_path);
      std::vector<double> buf(kBlock);
      for (size_t got; (got = in.read(buf.data(), buf.size() * 8) / 8) > 0;)
        for (size_t i = 0; i < got; ++i)
          if (!std::isnan(buf[i])) take(buf[i]);
    };
    report.alpha = streamed_percentile(points, store.points, weights->alpha_percentile);
    double sum = 0;
    points([&](double s) { sum += curve_weight(s, report.alpha, *weights); });
    const double floor = weights->floor > 0 && store.points > 0 ? weight_floor(sum, store.points, *weights) : 0;
    mesh.weights = store.dir.file("w.f64");
    ScratchWriter w(mesh.weights);
    ScratchReader in(sm_path);
    std::vector<double> buf(kBlock);
    for (size_t got; (got = in.read(buf.data(), buf.size() * 8) / 8) > 0;) {
      for (size_t i = 0; i < got; ++i)
        buf[i] = std::isnan(buf[i]) ? 0.0 : std::max(curve_weight(buf[i], report.alpha, *weights), floor);
      w.write(buf.data(), got * 8);
    }
    w.close();
    clock.lap("weights");
  }
  std::remove(store.dir.file("sm.f64").c_str());

  // The tiles: the fewest (at least `tiles`) whose largest piece fits beside the bits of
  // the passes (three per vertex) and the bucket buffers (an eighth of the limit).
  const uint64_t fixed = kBaseBytes + 3 * (store.vertices / 8) + ooc.memory_limit / 8;
  unsigned t = std::max(1u, tiles);
  for (;;) {
    report.tile_estimate = uint64_t(double(largest_cell(store, TileGrid(store.box, t, 0))) * kSimplifyBytesPerVertex);
    if (!ooc.memory_limit || fixed + report.tile_estimate <= ooc.memory_limit) break;
    if (t == kMaxSimplifyTiles)
      throw Error("memory limit " + memory_size_text(ooc.memory_limit) + " is too small to simplify " + input +
                  ": the smallest tile needs about " + mib_text(report.tile_estimate) +
                  "; the smallest workable limit is about " + mib_text(fixed + report.tile_estimate));
    t = std::min(kMaxSimplifyTiles, t + std::max(1u, t / 4));
  }
  report.tiles = t;

  // The passes of simplify_mesh_tiled.
  PassTotals totals;
  if (!keep) {
    const size_t buffer = ooc.memory_limit ? size_t(ooc.memory_limit / 8) : size_t(64) << 20;
    VertexBits pending(store.vertices), near1, near2;
    // Rounds, as simplify_mesh_tiled (simplify/tile_pass.h).
    for (uint64_t now = mesh.triangle_count; now > target; now = mesh.triangle_count) {
      const size_t goal = round_target(size_t(now), target);
      for (uint64_t v = 0; v < store.vertices; ++v) pending.set(uint32_t(v));
      DiskPass first{TileGrid(store.box, t, 0), PassBudget{}};
      first.budget.ratio = double(goal) / double(now);
      run_disk_pass(mesh, first, options, pending, totals, buffer, [&](double f) { progress("simplifying", f); });
      unsigned grid_tiles = 0;
      double shift = 0;
      for (int step = 0; mesh.triangle_count > goal && strip_grid(t, step, &grid_tiles, &shift); ++step) {
        const uint64_t strips = strip_vertices(mesh, pending, near1, near2);
        if (strips == 0) break;
        DiskPass pass{TileGrid(store.box, grid_tiles, shift), PassBudget{}};
        pass.budget.rule = Targets::Remaining;
        pass.budget.to_remove = (long long)mesh.triangle_count - (long long)goal;
        pass.selected_near = &near1;
        pass.guard_near = &near2;
        run_disk_pass(mesh, pass, options, pending, totals, buffer, [&](double f) { progress("strips", f); });
      }
      if (mesh.triangle_count >= now) break;  // the round gave up nothing: neither will the next
    }
    clock.lap("simplifying");
  }

  write_output(output, store, mesh, keep, [&](double f) { progress("writing", f); }, rep);
  clock.lap("writing");
  rep.unchanged = keep;
  rep.reached = rep.output_faces == target;
  if (keep)
    rep.note = "the target (" + std::to_string(target) + " faces) is at or above the mesh's " +
               std::to_string(faces) + " faces: the mesh is unchanged";
  else if (!rep.reached)
    rep.note = "tiled simplification stopped at " + std::to_string(rep.output_faces) + " faces (target " +
               std::to_string(target) + "): the strips along the tile cuts could not give up more";
  rep.collapses = totals.collapses;
  rep.refused = totals.refused;
  rep.error = store.box.diagonal() > 0 ? totals.error / store.box.diagonal() : 0;
  rep.seconds = t0.seconds();
  return report;
}

}  // namespace meshsal
