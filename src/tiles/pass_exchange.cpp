// meshsal (internal): the exchanges of a shared tiled simplification, see pass_exchange.h.
#include "tiles/pass_exchange.h"

#include <algorithm>

#include "tiles/tile_bytes.h"
#include "tiles/tile_reduce.h"

namespace meshsal {
namespace detail {

bool runs_group(const TileExchange* exchange, size_t g) {
  return !exchange || int(g % size_t(exchange->ranks())) == exchange->rank();
}

namespace {

// The rank that runs group g.
size_t owner(const TileExchange* exchange, size_t g) { return exchange ? g % size_t(exchange->ranks()) : 0; }

void check_count(size_t got, size_t want) {
  if (got != want) throw Error("tiled simplification: the processes disagree on the groups");
}

}  // namespace

void share_group_values(TileExchange* exchange, std::vector<uint64_t>& values) {
  if (!exchange) return;
  TileBytes b;
  b.put(values);
  const auto all = tile_gather(exchange, b.data);
  std::vector<std::vector<uint64_t>> by_rank;
  for (const auto& bytes : all) {
    by_rank.push_back(TileBytesReader{bytes}.get_vector<uint64_t>());
    check_count(by_rank.back().size(), values.size());
  }
  for (size_t g = 0; g < values.size(); ++g) values[g] = by_rank[owner(exchange, g)][g];
}

void share_group_levels(TileExchange* exchange, std::vector<std::vector<double>>& levels) {
  if (!exchange) return;
  TileBytes b;
  for (size_t g = 0; g < levels.size(); ++g)
    if (runs_group(exchange, g)) b.put(levels[g]);
  const auto all = tile_gather(exchange, b.data);
  std::vector<TileBytesReader> in;
  for (const auto& bytes : all) in.push_back(TileBytesReader{bytes});
  for (size_t g = 0; g < levels.size(); ++g) levels[g] = in[owner(exchange, g)].get_vector<double>();
}

namespace {

void put_outcome(TileBytes& b, const GroupOutcome& o) {
  const TilePiece& p = o.piece;
  b.put(p.ids);
  b.put(p.mesh.positions);
  b.put(p.mesh.triangles);
  b.put(p.mesh.triangle_material);
  for (const VertexAttribute& a : p.mesh.attributes) b.put(a.values);
  b.put(o.freed);
}

GroupOutcome get_outcome(TileBytesReader& in, size_t attributes) {
  GroupOutcome o;
  TilePiece& p = o.piece;
  p.ids = in.get_vector<uint32_t>();
  p.mesh.positions = in.get_vector<float>();
  p.mesh.triangles = in.get_vector<uint32_t>();
  p.mesh.triangle_material = in.get_vector<uint32_t>();
  for (size_t a = 0; a < attributes; ++a) p.mesh.attributes.push_back({"", in.get_vector<float>()});
  o.freed = in.get_vector<uint32_t>();
  if (p.mesh.positions.size() != 3 * p.ids.size()) throw Error("tiled simplification: a short message");
  p.pinned.assign(p.ids.size(), 0);
  return o;
}

void put_totals(TileBytes& b, const PassTotals& t) {
  b.put(uint64_t(t.collapses));
  b.put(uint64_t(t.refused));
  b.put(t.error);
}

void read_totals(TileBytesReader& in, PassTotals& t) {
  t.collapses += size_t(in.get<uint64_t>());
  t.refused += size_t(in.get<uint64_t>());
  t.error = std::max(t.error, in.get<double>());
}

}  // namespace

void add_totals(PassTotals& into, const PassTotals& more) {
  into.collapses += more.collapses;
  into.refused += more.refused;
  into.error = std::max(into.error, more.error);
}

void share_group_outcomes(TileExchange* exchange, std::vector<GroupOutcome>& outcomes, PassTotals& pass,
                          size_t attributes) {
  if (!exchange) return;
  TileBytes b;
  put_totals(b, pass);
  for (size_t g = 0; g < outcomes.size(); ++g)
    if (runs_group(exchange, g)) {
      put_outcome(b, outcomes[g]);
      outcomes[g] = GroupOutcome{};  // this process's copy comes back below, freed meanwhile
    }
  const auto all = tile_gather(exchange, b.data);
  b = TileBytes{};
  std::vector<TileBytesReader> in;
  pass = PassTotals{};
  for (const auto& bytes : all) {
    in.push_back(TileBytesReader{bytes});
    read_totals(in.back(), pass);
  }
  for (size_t g = 0; g < outcomes.size(); ++g) outcomes[g] = get_outcome(in[owner(exchange, g)], attributes);
}

PassTotals share_totals(TileExchange* exchange, const PassTotals& mine) {
  TileBytes b;
  put_totals(b, mine);
  PassTotals all;
  for (const auto& bytes : tile_gather(exchange, b.data)) {
    TileBytesReader in{bytes};
    read_totals(in, all);
  }
  return all;
}

void share_rank0_values(TileExchange* exchange, std::vector<uint64_t>& values) {
  if (!exchange) return;
  TileBytes b;
  b.put(values);
  values = TileBytesReader{tile_gather(exchange, b.data)[0]}.get_vector<uint64_t>();
}

uint64_t share_rank0_value(TileExchange* exchange, uint64_t value) {
  TileBytes b;
  b.put(value);
  const auto all = tile_gather(exchange, b.data);
  return TileBytesReader{all[0]}.get<uint64_t>();
}

}  // namespace detail
}  // namespace meshsal
