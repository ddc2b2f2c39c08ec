// meshsal batch: the results of a round from every rank (see batch_ranks.h).
#include "batch_ranks.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "mpi_world.h"

namespace meshsal::cli {
namespace {

void put_u64(std::vector<uint8_t>& b, uint64_t v) {
  for (int i = 0; i < 8; ++i) b.push_back(uint8_t(v >> (8 * i)));
}
void put_text(std::vector<uint8_t>& b, const std::string& s) {
  put_u64(b, s.size());
  b.insert(b.end(), s.begin(), s.end());
}

// Reads what put_* wrote, checking every length against what is left.
struct Reader {
  const std::vector<uint8_t>& b;
  size_t at = 0;
  uint64_t u64() {
    if (b.size() - at < 8) throw std::runtime_error("batch: a rank sent a truncated result");
    uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= uint64_t(b[at + size_t(i)]) << (8 * i);
    at += 8;
    return v;
  }
  std::string text() {
    const uint64_t n = u64();
    if (n > b.size() - at) throw std::runtime_error("batch: a rank sent a truncated result");
    std::string s(b.begin() + long(at), b.begin() + long(at + n));
    at += size_t(n);
    return s;
  }
};

}  // namespace

std::vector<uint8_t> pack_results(const std::vector<ModelResult>& results) {
  std::vector<uint8_t> b;
  put_u64(b, results.size());
  for (const ModelResult& r : results) {
    put_u64(b, r.index);
    put_text(b, r.status);
    put_text(b, r.line);
    put_text(b, r.error);
    put_u64(b, r.notes.size());
    for (const std::string& n : r.notes) put_text(b, n);
    put_u64(b, r.has_view);
    uint64_t bits;
    std::memcpy(&bits, &r.seconds, 8);
    put_u64(b, bits);
    put_u64(b, uint64_t(r.rank));
  }
  return b;
}

std::vector<ModelResult> unpack_results(const std::vector<uint8_t>& bytes) {
  Reader in{bytes};
  std::vector<ModelResult> results;
  const uint64_t count = in.u64();
  if (count > bytes.size()) throw std::runtime_error("batch: a rank sent a truncated result");
  for (uint64_t k = 0; k < count; ++k) {
    ModelResult r;
    r.index = in.u64();
    r.status = in.text();
    r.line = in.text();
    r.error = in.text();
    const uint64_t notes = in.u64();
    if (notes > bytes.size()) throw std::runtime_error("batch: a rank sent a truncated result");
    for (uint64_t n = 0; n < notes; ++n) r.notes.push_back(in.text());
    r.has_view = in.u64() != 0;
    const uint64_t bits = in.u64();
    std::memcpy(&r.seconds, &bits, 8);
    r.rank = int(in.u64());
    results.push_back(std::move(r));
  }
  return results;
}

std::vector<ModelResult> gather_results(const std::vector<ModelResult>& mine) {
  const meshsal::cli::MpiWorld& w = meshsal::cli::mpi_world();
  if (!w.active || w.size == 1) return mine;  // one process: nothing to send
  std::vector<ModelResult> own = mine;
  for (ModelResult& r : own) r.rank = w.rank;
  std::vector<ModelResult> all;
  for (const std::vector<uint8_t>& bytes : meshsal::cli::mpi_all_gather(pack_results(own)))
    for (ModelResult& r : unpack_results(bytes)) all.push_back(std::move(r));
  std::sort(all.begin(), all.end(), [](const ModelResult& a, const ModelResult& b) { return a.index < b.index; });
  return all;
}

}  // namespace meshsal::cli
