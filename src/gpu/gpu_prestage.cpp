// meshsal: buffers uploaded ahead of the call that takes them (gpu_prestage.h).
#include "gpu/gpu_prestage.h"

#include <cstring>
#include <memory>
#include <vector>

#include "core/parallel.h"
#include "gpu/gpu_fast.h"

namespace meshsal::gpu {
namespace {

constexpr uint64_t kPrime1 = 0x9E3779B185EBCA87ull, kPrime2 = 0xC2B2AE3D27D4EB4Full;
constexpr size_t kBlock = size_t(1) << 20;

uint64_t rotl(uint64_t x, int r) { return (x << r) | (x >> (64 - r)); }
uint64_t round(uint64_t h, uint64_t w) { return rotl(h + w * kPrime2, 31) * kPrime1; }
uint64_t avalanche(uint64_t h) {
  h ^= h >> 33;
  h *= kPrime2;
  h ^= h >> 29;
  h *= kPrime1;
  return h ^ (h >> 32);
}

// One block: four lanes over its 8-byte words (independent chains, so the multiplies
// overlap), the last partial word zero-padded; its length and index mixed in.
uint64_t block_key(const unsigned char* p, size_t n, uint64_t index) {
  uint64_t lane[4] = {index + kPrime1, index ^ kPrime2, index * kPrime1 + 1, ~index};
  size_t i = 0;
  for (; i + 32 <= n; i += 32)
    for (int k = 0; k < 4; ++k) {
      uint64_t w;
      std::memcpy(&w, p + i + 8 * k, 8);
      lane[k] = round(lane[k], w);
    }
  for (int k = 0; i < n; i += 8, k = (k + 1) & 3) {
    uint64_t w = 0;
    std::memcpy(&w, p + i, std::min<size_t>(8, n - i));
    lane[k] = round(lane[k], w);
  }
  uint64_t h = rotl(lane[0], 1) + rotl(lane[1], 7) + rotl(lane[2], 12) + rotl(lane[3], 18);
  return avalanche(h ^ n);
}

enum class Kind : uint64_t { float_positions = 1, triangles = 2 };

struct Held {
  uint64_t key;
  vk::Buffer buffer;
};

// What vk::Context::prestaged holds.
struct Prestaged {
  std::vector<Held> held;
};

uint64_t key_of(Kind kind, const void* data, size_t count, size_t bytes, unsigned threads) {
  return avalanche(array_key(data, bytes, threads) ^ avalanche(uint64_t(kind) * kPrime1 + count));
}

void hold(vk::Context& ctx, uint64_t key, vk::Buffer buffer) {
  if (!ctx.prestaged) ctx.prestaged = std::make_shared<Prestaged>();
  static_cast<Prestaged*>(ctx.prestaged.get())->held.push_back({key, std::move(buffer)});
}

// The held buffer of `key`, taken off the context; an empty buffer when none is held.
vk::Buffer take(vk::Context& ctx, uint64_t key) {
  auto* p = static_cast<Prestaged*>(ctx.prestaged.get());
  if (!p) return {};
  for (size_t i = 0; i < p->held.size(); ++i)
    if (p->held[i].key == key) {
      vk::Buffer b = std::move(p->held[i].buffer);
      p->held.erase(p->held.begin() + long(i));
      ++ctx.prestaged_taken;
      return b;
    }
  return {};
}

vk::Buffer upload_triangles(vk::Context& ctx, const uint32_t* triangles, size_t triangle_count) {
  vk::Buffer b(ctx, triangle_count * 12, "the triangles");
  b.upload(triangles, triangle_count * 12);
  return b;
}

}  // namespace

uint64_t array_key(const void* data, size_t bytes, unsigned threads) {
  const auto* p = static_cast<const unsigned char*>(data);
  const size_t blocks = (bytes + kBlock - 1) / kBlock;
  std::vector<uint64_t> keys(blocks);
  parallel_for(blocks, threads, 1, [&](size_t begin, size_t end) {
    for (size_t b = begin; b < end; ++b) keys[b] = block_key(p + b * kBlock, std::min(kBlock, bytes - b * kBlock), b);
  });
  uint64_t h = avalanche(bytes + kPrime2);
  for (uint64_t k : keys) h = round(h, k);
  return avalanche(h);
}

void prestage_float_positions(vk::Context& ctx, const float* positions, size_t vertex_count, unsigned threads) {
  const uint64_t key = key_of(Kind::float_positions, positions, vertex_count, vertex_count * 12, threads);
  hold(ctx, key, upload_float_positions(ctx, positions, vertex_count, threads));
}

void prestage_triangles(vk::Context& ctx, const uint32_t* triangles, size_t triangle_count, unsigned threads) {
  const uint64_t key = key_of(Kind::triangles, triangles, triangle_count, triangle_count * 12, threads);
  hold(ctx, key, upload_triangles(ctx, triangles, triangle_count));
}

vk::Buffer float_positions(vk::Context& ctx, const Mesh& mesh, unsigned threads) {
  const size_t nv = mesh.vertex_count();
  if (ctx.prestaged) {
    vk::Buffer b = take(ctx, key_of(Kind::float_positions, mesh.positions.data(), nv, nv * 12, threads));
    if (b.handle()) return b;
  }
  return upload_float_positions(ctx, mesh.positions.data(), nv, threads);
}

vk::Buffer mesh_triangles(vk::Context& ctx, const Mesh& mesh, unsigned threads) {
  const size_t nt = mesh.triangle_count();
  if (ctx.prestaged) {
    vk::Buffer b = take(ctx, key_of(Kind::triangles, mesh.triangles.data(), nt, nt * 12, threads));
    if (b.handle()) return b;
  }
  return upload_triangles(ctx, mesh.triangles.data(), nt);
}

void drop_prestaged(vk::Context& ctx) { ctx.prestaged.reset(); }

uint64_t prestaged_bytes(const vk::Context& ctx) {
  uint64_t bytes = 0;
  if (const auto* p = static_cast<const Prestaged*>(ctx.prestaged.get()))
    for (const Held& h : p->held) bytes += h.buffer.size();
  return bytes;
}

}  // namespace meshsal::gpu
