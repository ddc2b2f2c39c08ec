// simplify_file(): tiled simplification of a mesh larger than memory. The input goes into
// a TileStore (as for saliency_file), the weights come from the tiles' saliency, and the
// passes of simplify_mesh_tiled run over the mesh on disk (disk_simplify.h); the output
// is streamed in the input's vertex order.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>
#include <utility>

#include "tiles/disk_simplify.h"
#include "tiles/group_workers.h"
#include "core/streamed_percentile.h"
#include "tiles/tile_saliency.h"
#include "tiles/tile_store.h"
#include "tiles/tile_rounds.h"
#include "core/memory_size.h"
#include "core/parallel.h"
#include "core/cancel.h"
#include "core/model_frame.h"
#include "core/stage_clock.h"
#include "core/timer.h"
#include "io/atomic_write.h"
#include "io/output_check.h"
#include "io/ply_types.h"
#include "meshsal/meshsal.h"
#include "saliency/saliency.h"
#include "simplify/saliency_weights.h"
#include "simplify/simplify.h"
#include "tiles/pass_exchange.h"
#include "tiles/simplify_tiled.h"
#include "tiles/tile_reduce.h"

namespace meshsal {

using namespace detail;

namespace {

// What one vertex of a tile's piece costs simplify_tile at its peak (the simplifier's
// state, the piece and its copy out), measured on igea_loop1 (README "Out of core").
constexpr double kSimplifyBytesPerVertex = 520;
constexpr size_t kBlock = 1 << 16;  // vertices per block of the streamed steps

// The store's histogram as its occupied bins: each bin's centre and point count.
struct OccupiedBin {
  double centre[3];
  uint32_t count;
};
std::vector<OccupiedBin> occupied_bins(const TileStore& store) {
  const PointHistogram& h = store.histogram;
  const int n = PointHistogram::kBins;
  std::vector<OccupiedBin> bins;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const uint32_t c = h.count[(size_t(z) * n + y) * n + x];
        if (c == 0) continue;
        const int i[3] = {x, y, z};
        OccupiedBin b;
        for (int a = 0; a < 3; ++a) b.centre[a] = h.box.min[a] + (i[a] + 0.5) * h.bin[a];
        b.count = c;
        bins.push_back(b);
      }
  return bins;
}

// The most mesh points in one cell of `grid`, from the histogram's bins (each counted in
// the cell of its centre: an estimate, not a bound).
uint64_t largest_cell(const std::vector<OccupiedBin>& bins, const TileGrid& grid) {
  std::unordered_map<uint64_t, uint64_t> cells;
  uint64_t largest = 0;
  for (const OccupiedBin& b : bins) largest = std::max(largest, cells[grid.cell_of(b.centre)] += b.count);
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
    write_all(f, buf.data(), buf.size(), output);  // the last vertices
    ScratchReader in(mesh.triangles);
    std::vector<uint32_t> t(3 * kBlock);
    uint64_t done = 0;
    for (size_t got; (got = in.read(t.data(), t.size() * 4) / 12) > 0; done += got) {
      if (progress) progress(0.5 + 0.5 * double(done) / double(std::max<uint64_t>(1, mesh.triangle_count)));
      buf.resize(got * kPlyTriangleBytes);
      char* out = buf.data();
      for (size_t i = 0; i < got; ++i) {
        const uint32_t corner[3] = {index_of(t[3 * i]), index_of(t[3 * i + 1]), index_of(t[3 * i + 2])};
        put_ply_triangle(out, corner);
      }
      write_all(f, buf.data(), buf.size(), output);
    }
  });
  report.output_vertices = size_t(nv);
  report.output_faces = size_t(mesh.triangle_count);
}

// The passes over the mesh on disk, for run_rounds (disk_simplify.h).
class DiskPasses final : public TilePasses {
 public:
  DiskPasses(DiskMesh& mesh, const SimplifyOptions& options, size_t buffer_bytes, unsigned concurrent,
             PassTotals& totals, std::function<void(const char*, double)> progress)
      : mesh_(mesh), options_(options), buffer_(buffer_bytes), concurrent_(concurrent), totals_(totals),
        progress_(std::move(progress)), pending_(mesh.vertices) {}
  uint64_t triangles() const override { return mesh_.triangle_count; }
  void first_pass(const TileGrid& grid, const PassBudget& budget) override {
    for (uint64_t v = 0; v < mesh_.vertices; ++v) pending_.set(uint32_t(v));
    run_disk_pass(mesh_, DiskPass{grid, budget}, options_, pending_, totals_, buffer_, concurrent_,
                  [&](double f) { progress_("simplifying", f); });
  }
  bool strip_pass(const TileGrid& grid, const PassBudget& budget) override {
    // (Shared: rank 0 keeps the pending vertices and selects the strips; every process
    // takes them to bucket its share of the pass.)
    TileExchange* exchange = options_.exchange;
    uint64_t selected = 0;
    lead_step(exchange, [&] { selected = strip_vertices(mesh_, pending_, near1_, near2_); });
    if (share_rank0_value(exchange, selected) == 0) return false;
    share_vertex_bits(mesh_, exchange, near1_, "near1.bits");  // (every process buckets its share)
    share_vertex_bits(mesh_, exchange, near2_, "near2.bits");
    DiskPass pass{grid, budget};
    pass.selected_near = &near1_;
    pass.guard_near = &near2_;
    run_disk_pass(mesh_, pass, options_, pending_, totals_, buffer_, concurrent_,
                  [&](double f) { progress_("strips", f); });
    return true;
  }

 private:
  DiskMesh& mesh_;
  const SimplifyOptions& options_;
  size_t buffer_;
  unsigned concurrent_;
  PassTotals& totals_;
  std::function<void(const char*, double)> progress_;
  VertexBits pending_, near1_, near2_;
};

// The saliency options of simplify_file: S and its smoothed map, the fast method where
// Auto; refuses what out of core cannot do.
SaliencyOptions checked_options(const SimplifyOptions& options, const SaliencyWeightOptions* weights,
                                const SaliencyOptions& saliency_options, unsigned tiles, bool computes_s) {
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
  }
  if (computes_s) {
    check_saliency_options(so);
    if (so.model != Model::Lee2005)
      throw Error(std::string("model ") + model_name(so.model) +
                  " computes S in memory, in one piece: simplify_file takes the paper's model only");
    if (so.backend == Backend::Gpu) throw Error("out of core runs on the CPU: use backend cpu or auto");
  }
  if (so.exchange && options.exchange && so.exchange != options.exchange)
    throw Error("simplify: the saliency and the simplification name different TileExchanges");
  if (!so.exchange) so.exchange = options.exchange;
  return so;
}

// The vertex state (position, then S with weights) to mesh.state, and with weights each
// vertex's smoothed saliency to sm.f64 (NaN where it is no mesh point), a block at a time.
void write_vertex_state(const TileStore& store, const DiskMesh& mesh, bool weights, size_t scales, bool kept_scales) {
  const size_t rec = mesh.record_bytes();
  ScratchWriter state(mesh.state), sm(store.dir.file("sm.f64"));
  ScratchReader pos(store.dir.file("pos.f32"));
  std::vector<float> p(3 * kBlock), r(kBlock * rec / 4);
  std::vector<double> values, smooth(kBlock);
  std::vector<uint8_t> point;
  TileResultReader results(store, scales, kept_scales);
  for (uint64_t first = 0; first < store.vertices; first += kBlock) {
    const size_t count = size_t(std::min<uint64_t>(kBlock, store.vertices - first));
    pos.read_exact(p.data(), 12 * count);
    if (weights) results.read(first, count, values, point);
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

// The weight of every vertex (simplify_with_saliency's rule, streamed) from sm.f64 to
// mesh.weights; returns alpha.
double write_weights(const TileStore& store, DiskMesh& mesh, const SaliencyWeightOptions& weights) {
  const std::string sm_path = store.dir.file("sm.f64");
  const ValueStream points = [&](const std::function<void(double)>& take) {
    ScratchReader in(sm_path);
    std::vector<double> buf(kBlock);
    for (size_t got; (got = in.read(buf.data(), buf.size() * 8) / 8) > 0;)
      for (size_t i = 0; i < got; ++i)
        if (!std::isnan(buf[i])) take(buf[i]);
  };
  const double alpha = streamed_percentile(points, store.points, weights.alpha_percentile);
  double sum = 0;
  points([&](double s) { sum += curve_weight(s, alpha, weights); });
  const double floor = weights.floor > 0 && store.points > 0 ? weight_floor(sum, store.points, weights) : 0;
  mesh.weights = store.dir.file("w.f64");
  ScratchWriter w(mesh.weights);
  ScratchReader in(sm_path);
  std::vector<double> buf(kBlock);
  for (size_t got; (got = in.read(buf.data(), buf.size() * 8) / 8) > 0;) {
    for (size_t i = 0; i < got; ++i)
      buf[i] = std::isnan(buf[i]) ? 0.0 : std::max(curve_weight(buf[i], alpha, weights), floor);
    w.write(buf.data(), got * 8);
  }
  w.close();
  return alpha;
}

// The pieces a tile count is sized for: that many of the largest fit the limit at once,
// whatever the machine (the tiles, so the bytes written, must not depend on the thread
// count: one process and mpirun ranks with the same limit write the same file). Smaller
// pieces also simplify faster: 2.1M vertices to 10% in memory on the 2-core VM, 7.6 s with
// 2 tiles, 6.1 s with 3, 5.4 s with 4, 5.1 s with 6 and 8.
constexpr unsigned kPiecesAtOnce = 4;

// The tiles, and how many groups may run at once (`concurrent`; 0 = no cap, without a
// limit). Each group at work holds its piece and a bit per vertex (its mark), beside the
// bits of the passes (three per vertex) and the bucket buffers (an eighth of the limit):
// the fewest tiles (at least `tiles`) whose largest pieces fit kPiecesAtOnce at a time, or
// one at a time where no tile count fits that many.
unsigned simplify_tiles(const TileStore& store, const std::string& input, uint64_t memory_limit, unsigned tiles,
                        uint64_t& estimate, unsigned& concurrent) {
  const uint64_t fixed = kBaseBytes + 3 * (store.vertices / 8) + memory_limit / 8, mark = store.vertices / 8;
  const std::vector<OccupiedBin> bins = occupied_bins(store);
  auto piece = [&](unsigned t) {
    return uint64_t(double(largest_cell(bins, TileGrid(store.box, t, 0))) * kSimplifyBytesPerVertex);
  };
  concurrent = 0;
  if (!memory_limit) {
    estimate = piece(std::max(1u, tiles));
    return std::max(1u, tiles);
  }
  for (const unsigned pieces : {kPiecesAtOnce, 1u}) {
    for (unsigned t = std::max(1u, tiles);; t = std::min(kMaxSimplifyTiles, t + std::max(1u, t / 4))) {
      estimate = piece(t);
      if (fixed + pieces * (estimate + mark) <= memory_limit) {
        concurrent = unsigned(std::min<uint64_t>(kMaxThreads, (memory_limit - fixed) / (estimate + mark)));
        return t;
      }
      if (t == kMaxSimplifyTiles) break;
    }
  }
  throw Error("memory limit " + memory_size_text(memory_limit) + " is too small to simplify " + input +
              ": the smallest tile needs about " + mib_text(estimate + mark) +
              "; the smallest workable limit is about " + mib_text(fixed + estimate + mark));
}

// The report's outcome once the output is written.
void finish_report(SimplifyReport& rep, bool keep, uint64_t faces, size_t target, const PassTotals& totals,
                   double diagonal) {
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
  rep.error = diagonal > 0 ? totals.error / diagonal : 0;
}

}  // namespace

OutOfCoreSimplifyReport simplify_file(const std::string& input, const std::string& output,
                                      const SimplifyOptions& options,
                                      const std::optional<SaliencyWeightOptions>& weight_options,
                                      const SaliencyOptions& saliency_options, const OutOfCoreOptions& ooc) {
  const CancelScope cancel(options.cancel ? options.cancel : saliency_options.cancel);
  const SaliencyWeightOptions* weights = weight_options ? &*weight_options : nullptr;  // null once unused
  const unsigned tiles = std::max(1u, options.tiles);
  const bool saliency_output = !ooc.saliency_output.empty();
  const bool computes_s = weights || saliency_output;  // (a target that keeps the mesh: S for the file alone)
  SaliencyOptions so = checked_options(options, weights, saliency_options, tiles, computes_s);
  // Shared by processes (SimplifyOptions::exchange): the saliency's tiles and the passes'
  // groups over them all; rank 0, the lead, builds the store, writes the files between the
  // steps and the output, in the one folder they all reach.
  TileExchange* exchange = so.exchange;
  const bool lead = !exchange || exchange->rank() == 0;
  SimplifyOptions opt = options;
  opt.exchange = exchange;
  OutOfCoreSimplifyReport report;
  report.saliency.ranks = exchange ? exchange->ranks() : 1;
  const Timer t0;
  StageClock clock(report.stages);
  auto progress = [&](const char* stage, double f) {
    if (so.progress) so.progress(stage, f);
  };
  // Before the work: a .ply name, never the input (as saliency_file).
  if (saliency_output && ooc.saliency_output == output)
    throw Error("simplify_file: the saliency and the simplified mesh cannot both go to " + output);
  lead_step(exchange, [&] {
    check_ply_output("simplify_file", output, input);
    if (saliency_output) check_ply_output("simplify_file", ooc.saliency_output, input);
  });

  // The input on disk; with weights its tiles fit the limit for the saliency too.
  TileStore store(ooc.temp_dir);
  if (so.notice && !store.dir.note().empty()) so.notice(store.dir.note());
  share_tile_store(store, input, so, ooc.memory_limit, computes_s ? std::max(1u, so.tiles) : 1, progress,
                   computes_s ? StoreUse::SaliencyTiles : StoreUse::FilesOnly);
  clock.lap("tiling");
  report.saliency.vertices = store.vertices;
  report.saliency.points = store.points;
  report.saliency.triangles = store.triangles;
  DiskMesh mesh;
  mesh.dir = &store.dir;
  mesh.vertices = store.vertices;
  for (int k = 0; k < 3; ++k) mesh.origin[k] = store.origin[k];
  mesh.triangles = store.dir.file("simplify_tri.u32");
  uint64_t faces = 0;
  lead_step(exchange, [&] { faces = surface_triangles(store, mesh.triangles); });
  faces = share_rank0_value(exchange, faces);
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
  if (weights) mesh.attribute_names = {"quality"};
  if (weights || saliency_output) {
    tile_saliency(store, so, report.saliency, ooc.dump_scales);
    clock.lap("saliency");
  }
  if (saliency_output) {
    lead_step(exchange, [&] { write_saliency_output(ooc.saliency_output, store, so, ooc, report.saliency, progress); });
    clock.lap("writing S");
  }
  // Rank 0 writes the state and the weights and picks the tiles from its histogram.
  if (weights && !keep) mesh.weights = store.dir.file("w.f64");
  unsigned simplify_tile_count = 0, concurrent = 0;
  lead_step(exchange, [&] {
    write_vertex_state(store, mesh, weights != nullptr, so.scales.size(), ooc.dump_scales);
    if (weights && !keep) report.alpha = write_weights(store, mesh, *weights);
    std::remove(store.dir.file("sm.f64").c_str());
    simplify_tile_count = simplify_tiles(store, input, ooc.memory_limit, tiles, report.tile_estimate, concurrent);
  });
  if (weights && !keep) clock.lap("weights");
  report.tiles = unsigned(share_rank0_value(exchange, simplify_tile_count));
  concurrent = unsigned(share_rank0_value(exchange, concurrent));
  report.groups_at_once = group_workers(options.threads, concurrent, SIZE_MAX).workers;

  // The passes of simplify_mesh_tiled.
  PassTotals totals;
  if (!keep) {
    const size_t buffer = ooc.memory_limit ? size_t(ooc.memory_limit / 8) : size_t(64) << 20;
    DiskPasses passes(mesh, opt, buffer, concurrent, totals, progress);
    run_rounds(passes, store.box, report.tiles, target);
    clock.lap("simplifying");
  }

  lead_step(exchange, [&] { write_output(output, store, mesh, keep, [&](double f) { progress("writing", f); }, rep); });
  if (lead) clock.lap("writing");
  // (Every process's report says what rank 0 wrote.)
  rep.output_faces = size_t(share_rank0_value(exchange, rep.output_faces));
  rep.output_vertices = size_t(share_rank0_value(exchange, rep.output_vertices));
  finish_report(rep, keep, faces, target, totals, store.box.diagonal());
  rep.seconds = t0.seconds();
  tile_gather(exchange, {});  // every process done before rank 0's folder goes
  return report;
}

}  // namespace meshsal
