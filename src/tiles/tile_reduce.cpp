#include "tiles/tile_reduce.h"

#include <algorithm>

#include <exception>
#include <string>

#include "tiles/tile_bytes.h"

namespace meshsal {

std::vector<std::vector<uint8_t>> tile_gather(TileExchange* exchange, const std::vector<uint8_t>& mine) {
  if (!exchange) return {mine};
  return exchange->all_gather(mine);
}

void all_step(TileExchange* exchange, const std::function<void()>& step) {
  if (!exchange) return step();
  std::exception_ptr cancelled;
  std::string message;
  try {
    step();
  } catch (const Cancelled& e) {
    cancelled = std::current_exception();
    message = e.what();
  } catch (const std::exception& e) {
    message = e.what();
    if (message.empty()) message = "a rank failed";
  } catch (...) {
    message = "a rank failed";
  }
  const auto said = tile_gather(exchange, std::vector<uint8_t>(message.begin(), message.end()));
  if (cancelled) std::rethrow_exception(cancelled);
  for (const auto& m : said)
    if (!m.empty()) throw Error(std::string(m.begin(), m.end()));
}

void lead_step(TileExchange* exchange, const std::function<void()>& step) {
  if (!exchange) return step();
  std::exception_ptr failed;
  std::string message;
  if (exchange->rank() == 0) {
    try {
      step();
    } catch (const Error& e) {
      failed = std::current_exception();
      message = e.what();
      if (message.empty()) message = "rank 0 failed";
    }
  }
  TileBytes b;
  b.put(std::vector<uint8_t>(message.begin(), message.end()));
  const std::vector<uint8_t> said = TileBytesReader{tile_gather(exchange, b.data)[0]}.get_vector<uint8_t>();
  if (failed) std::rethrow_exception(failed);
  if (!said.empty()) throw Error(std::string(said.begin(), said.end()));
}

std::vector<uint64_t> whole_mesh_cells(TileExchange* exchange, const TileCells& mine) {
  TileBytes b;
  b.put(mine.inner);
  for (const std::vector<uint64_t>& keys : mine.across) b.put(keys);
  const size_t sigmas = mine.inner.size();
  std::vector<uint64_t> total(sigmas, 0);
  std::vector<std::vector<uint64_t>> across(sigmas);
  for (const auto& bytes : tile_gather(exchange, b.data)) {
    TileBytesReader in{bytes};
    const std::vector<uint64_t> inner = in.get_vector<uint64_t>();
    if (inner.size() != sigmas) throw Error("tiled saliency: the processes disagree on the plan");
    for (size_t k = 0; k < sigmas; ++k) {
      total[k] += inner[k];
      const std::vector<uint64_t> keys = in.get_vector<uint64_t>();
      across[k].insert(across[k].end(), keys.begin(), keys.end());
    }
  }
  for (size_t k = 0; k < sigmas; ++k) {
    std::sort(across[k].begin(), across[k].end());
    total[k] += uint64_t(std::unique(across[k].begin(), across[k].end()) - across[k].begin());
  }
  return total;
}

void reduce_scale_max(TileExchange* exchange, std::vector<ScaleMax>& max, uint64_t& pairs) {
  TileBytes b;
  b.put(max);
  b.put(pairs);
  const size_t scales = max.size();
  max.assign(scales, ScaleMax{});
  pairs = 0;
  for (const auto& bytes : tile_gather(exchange, b.data)) {
    TileBytesReader in{bytes};
    merge_scale_max(max, in.get_vector<ScaleMax>());
    pairs += in.get<uint64_t>();
  }
  if (max.size() != scales) throw Error("tiled saliency: the processes disagree on the scales");
}

std::vector<double> reduce_mbar(TileExchange* exchange, std::vector<std::vector<LocalMax>> mine,
                                const std::vector<ScaleMax>& max) {
  // Rank 0 alone receives every process's local maxima and sums them in vertex order (the
  // sum one process makes); the others get the sums.
  TileBytes b;
  for (const auto& m : mine) b.put(m);
  for (auto& m : mine) std::vector<LocalMax>().swap(m);
  const std::vector<std::vector<uint8_t>> parts = exchange ? exchange->gather(b.data, 0) : std::vector<std::vector<uint8_t>>{b.data};
  b = TileBytes{};
  std::vector<double> mbar(mine.size(), 0.0);
  if (!parts.empty()) {
    for (const auto& bytes : parts) {
      TileBytesReader in{bytes};
      for (auto& m : mine) {
        const std::vector<LocalMax> part = in.get_vector<LocalMax>();
        m.insert(m.end(), part.begin(), part.end());
      }
    }
    for (size_t k = 0; k < mine.size(); ++k) mbar[k] = mbar_of(std::move(mine[k]), max[k]);
    b.put(mbar);
  }
  if (!exchange) return mbar;
  const std::vector<double> shared = TileBytesReader{tile_gather(exchange, b.data)[0]}.get_vector<double>();
  if (shared.size() != mbar.size()) throw Error("tiled saliency: the processes disagree on the scales");
  return shared;
}

}  // namespace meshsal
