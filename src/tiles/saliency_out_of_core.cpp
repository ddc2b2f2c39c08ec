// saliency_file(): the phases of saliency_tiles.h over a TileStore on disk, a tile at a
// time, each tile's state kept on disk between phases; the output streamed in the input's
// vertex order.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "tiles/tile_saliency.h"
#include "tiles/tile_store.h"
#include "core/cancel.h"
#include "core/parallel.h"
#include "core/stage_clock.h"
#include "io/atomic_write.h"
#include "io/colormap.h"
#include "io/output_check.h"
#include "io/ply_types.h"
#include "meshsal/meshsal.h"
#include "saliency/saliency.h"
#include "tiles/tile_bytes.h"
#include "tiles/tile_reduce.h"

namespace meshsal {

namespace {

// The output's PLY header: positions as read, S, with dump_scales the curvature and each
// raw map, the colours; then the faces.
std::string output_header(const TileStore& store, size_t scales, bool dump_scales) {
  std::string header = "ply\nformat binary_little_endian 1.0\ncomment written by meshsal\n";
  header += "element vertex " + std::to_string(store.vertices) + "\n";
  header += store.double_positions ? "property double x\nproperty double y\nproperty double z\n"
                                   : "property float x\nproperty float y\nproperty float z\n";
  header += "property float quality\n";
  if (dump_scales) {
    header += "property float curvature\n";
    for (size_t k = 0; k < scales; ++k) header += "property float saliency_raw_" + std::to_string(k) + "\n";
  }
  header += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  header += "element face " + std::to_string(store.triangles) + "\n";
  header += "property list uchar int vertex_indices\nend_header\n";
  return header;
}

}  // namespace

void write_saliency_output(const std::string& output, const TileStore& store, const SaliencyOptions& options,
                           const OutOfCoreOptions& ooc, const OutOfCoreReport& report,
                           const std::function<void(const char*, double)>& progress) {
  const bool wide = store.double_positions;
  const size_t scales = options.scales.size();
  const std::string header = output_header(store, scales, ooc.dump_scales);
  const ColorLimits limits = colour_limits({report.saliency_min, report.saliency_max}, {1, 1}, ColorRange{});
  // Fixed-size records, so each thread formats its own range of the block in place.
  const size_t vertex_bytes = (wide ? 24 : 12) + 4 + (ooc.dump_scales ? 4 * (1 + scales) : 0) + 3;
  // A block of output vertices holds their results (8 bytes each), positions as read and
  // records: a quarter of the limit.
  const size_t per_vertex = 8 * (kResultWidth + scales) + 24 + 1 + vertex_bytes;
  const size_t block = size_t(std::min<uint64_t>(
      store.vertices, ooc.memory_limit ? std::max<uint64_t>(65536, ooc.memory_limit / 4 / per_vertex) : store.vertices));
  const unsigned threads = options.threads;
  write_file_atomically(output, [&](std::FILE* f) {
    write_all(f, header.data(), header.size(), output);
    std::vector<char> buf;
    TileResultReader results(store, scales, ooc.dump_scales);
    const size_t width = kResultWidth + scales;
    std::vector<double> values, xyz;
    std::vector<uint8_t> point;
    for (uint64_t first = 0; first < store.vertices; first += block) {
      const size_t count = size_t(std::min<uint64_t>(block, store.vertices - first));
      progress("writing", double(first) / double(store.vertices));
      results.read(first, count, values, point);
      xyz.resize(3 * count);
      read_source_positions(store, first, count, xyz.data());
      buf.resize(count * vertex_bytes);
      parallel_for(count, threads, 1 << 14, [&](size_t lo, size_t hi) {
        for (size_t v = lo; v < hi; ++v) {
          char* out = &buf[v * vertex_bytes];
          for (int a = 0; a < 3; ++a) {
            if (wide) put_le(out, xyz[3 * v + a]);
            else put_le(out, float(xyz[3 * v + a]));
          }
          put_le(out, float(values[v * width]));
          if (ooc.dump_scales)
            for (size_t k = 0; k < 1 + scales; ++k) put_le(out, float(values[v * width + 2 + k]));
          uint8_t rgb[3];
          colormap_rgb(point[v] ? colour_position(values[v * width], limits) : 0.0, rgb);
          std::memcpy(out, rgb, 3);
        }
      });
      write_all(f, buf.data(), buf.size(), output);
    }
    constexpr size_t kFaces = 1 << 18;
    std::vector<uint32_t> tri(3 * kFaces);
    for (uint64_t first = 0; first < store.triangles; first += kFaces) {
      const size_t count = size_t(std::min<uint64_t>(kFaces, store.triangles - first));
      read_triangles(store, first, count, tri.data());
      buf.resize(count * kPlyTriangleBytes);
      parallel_for(count, threads, 1 << 14, [&](size_t lo, size_t hi) {
        char* out = &buf[lo * kPlyTriangleBytes];
        for (size_t i = lo; i < hi; ++i) put_ply_triangle(out, &tri[3 * i]);
      });
      write_all(f, buf.data(), buf.size(), output);
    }
  });
}


OutOfCoreReport saliency_file(const std::string& input, const std::string& output,
                              const SaliencyOptions& options_in, const OutOfCoreOptions& ooc) {
  const CancelScope cancel(options_in.cancel);
  check_saliency_options(options_in);
  if (options_in.model != Model::Lee2005)
    throw Error(std::string("model ") + model_name(options_in.model) +
                " computes S in memory, in one piece: saliency_file takes the paper's model only");
  if (options_in.backend == Backend::Gpu) throw Error("out of core runs on the CPU: use backend cpu or auto");
  SaliencyOptions options = options_in;
  if (options.method == Method::Auto) options.method = Method::Fast;
  TileExchange* exchange = options.exchange;
  const int rank = exchange ? exchange->rank() : 0, ranks = exchange ? exchange->ranks() : 1;
  OutOfCoreReport report;
  report.ranks = ranks;
  StageClock clock(report.stages);
  auto progress = [&](const char* stage, double f) {
    if (options.progress) options.progress(stage, f);
  };
  // Before the work: a .ply name (PLY bytes in a .obj would mislead), never the input
  // (through a link either: the rename would replace it).
  lead_step(exchange, [&] { check_ply_output("saliency_file", output, input); });

  TileStore store(ooc.temp_dir);
  if (options.notice && !store.dir.note().empty()) options.notice(store.dir.note());
  share_tile_store(store, input, options, ooc.memory_limit, options.tiles, progress);
  clock.lap("tiling");
  tile_saliency(store, options, report, ooc.dump_scales);  // laps its own stages
  clock.resume();
  lead_step(exchange, [&] { write_saliency_output(output, store, options, ooc, report, progress); });
  if (rank == 0) clock.lap("writing");
  // Every rank done before rank 0's store (and its folder) goes.
  tile_gather(exchange, {});
  return report;
}

}  // namespace meshsal
