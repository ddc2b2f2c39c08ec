#include "saliency/suppression.h"

#include <atomic>

#include "core/parallel.h"

namespace meshsal {

namespace {

// The suppression around a map's local maxima, whichever way they were found: normalise()
// divides by the maximum, then finish() takes mbar over the flagged local maxima in vertex
// order and scales the map. `threads` (0: all cores) share the element-wise passes; the
// maximum and mbar's sum run in vertex order, so the bits are those of one thread.
struct Suppression {
  SuppressionInfo si;
  size_t global;  // lowest-index mesh point attaining the maximum
  std::vector<double> out;
  unsigned threads = 1;

  // False (and out all zero) when the map has no positive maximum. `map` may be `out`
  // itself (moved in): every entry is read before it is written.
  bool normalise(const std::vector<double>& map, const std::vector<uint8_t>& is_point) {
    const size_t n = map.size();
    global = n;
    for (size_t v = 0; v < n; ++v)
      if (is_point[v] && (global == n || map[v] > si.max)) {
        si.max = map[v];
        global = v;
      }
    const bool positive = si.max > 0;
    if (&out != &map) out.resize(n);  // every entry written below
    const double top = si.max;
    parallel_for(n, threads, 1 << 16, [&](size_t begin, size_t end) {
      for (size_t v = begin; v < end; ++v) out[v] = positive && is_point[v] ? map[v] / top : 0.0;
    });
    return positive;
  }

  // mbar averages the local maxima other than the global one (which is 1 after
  // normalisation). is_max(v): whether v is one.
  template <class IsMax>
  void finish(IsMax&& is_max) {
    double sum = 0;
    size_t others = 0;
    for (size_t v = 0; v < out.size(); ++v) {
      if (!is_max(v)) continue;
      si.local_maxima++;
      if (v == global) continue;
      sum += out[v];
      others++;
    }
    si.mbar = others > 0 ? sum / double(others) : 0.0;
    const double factor = (1.0 - si.mbar) * (1.0 - si.mbar);
    parallel_for(out.size(), threads, 1 << 16, [&](size_t begin, size_t end) {
      for (size_t v = begin; v < end; ++v) out[v] *= factor;
    });
  }
};

}  // namespace

std::vector<double> suppress(const std::vector<double>& map, const std::vector<uint8_t>& is_point,
                             const Adjacency& adj, SuppressionInfo* info) {
  Suppression s;
  if (s.normalise(map, is_point)) {
    // Local maxima: strictly greater than every 1-ring neighbour.
    std::vector<uint8_t> is_max(map.size(), 0);
    for (size_t v = 0; v < map.size(); ++v) {
      if (!is_point[v]) continue;
      bool m = true;
      for (uint32_t e = adj.offsets[v]; e < adj.offsets[v + 1] && m; ++e) m = s.out[v] > s.out[adj.neighbors[e]];
      is_max[v] = m;
    }
    s.finish([&](size_t v) { return is_max[v] != 0; });
  }
  if (info) *info = s.si;
  return std::move(s.out);
}

namespace {

// suppress_faces on `s`, whose map is `map` (s.out itself, or another array).
std::vector<double> suppress_faces_into(Suppression& s, const std::vector<double>& map,
                                        const std::vector<uint8_t>& is_point, const Mesh& mesh,
                                        unsigned threads, SuppressionInfo* info) {
  s.threads = threads;
  if (s.normalise(map, is_point)) {
    // Every mesh point is a local maximum until an edge of a triangle shows a neighbour
    // at least as high: the 1-ring's test, edge by edge. Flags are only ever cleared, so
    // threads may clear the same one (relaxed atomics: no order is needed).
    std::vector<std::atomic<uint8_t>> flag(map.size());
    parallel_for(map.size(), threads, 1 << 16, [&](size_t begin, size_t end) {
      for (size_t v = begin; v < end; ++v) flag[v].store(is_point[v], std::memory_order_relaxed);
    });
    // The map rounded to float decides every edge whose ends round apart (rounding keeps
    // the order: float(a) > float(b) only where a > b), the doubles only the rest: the
    // triangles' scattered reads then touch half the bytes (a large scan's map outgrows
    // the caches: 69 MB for 8.6M vertices).
    const uint32_t* t = mesh.triangles.data();
    const double* out = s.out.data();
    std::vector<float> rounded(map.size());
    parallel_for(map.size(), threads, 1 << 16, [&](size_t begin, size_t end) {
      for (size_t v = begin; v < end; ++v) rounded[v] = float(out[v]);
    });
    const float* r = rounded.data();
    parallel_for(mesh.triangle_count(), threads, 1 << 14, [&](size_t begin, size_t end) {
      for (size_t f = begin; f < end; ++f) {
        if (f + 16 < end)  // the corners of the triangles ahead, fetched now
          for (int c = 0; c < 3; ++c) __builtin_prefetch(&r[t[3 * (f + 16) + c]]);
        for (int e = 0; e < 3; ++e) {
          const uint32_t a = t[3 * f + e], b = t[3 * f + (e + 1) % 3];
          if (a == b) continue;
          const float ra = r[a], rb = r[b];
          // a > b, a < b, or (equal floats, or NaN) the doubles' verdict.
          const bool a_higher = ra > rb || (!(ra < rb) && out[a] > out[b]);
          const bool b_higher = rb > ra || (!(rb < ra) && out[b] > out[a]);
          if (!a_higher) flag[a].store(0, std::memory_order_relaxed);
          if (!b_higher) flag[b].store(0, std::memory_order_relaxed);
        }
      }
    });
    s.finish([&](size_t v) { return flag[v].load(std::memory_order_relaxed) != 0; });
  }
  if (info) *info = s.si;
  return std::move(s.out);
}

}  // namespace

std::vector<double> suppress_faces(const std::vector<double>& map, const std::vector<uint8_t>& is_point,
                                   const Mesh& mesh, unsigned threads, SuppressionInfo* info) {
  Suppression s;
  return suppress_faces_into(s, map, is_point, mesh, threads, info);
}

std::vector<double> suppress_faces(std::vector<double>&& map, const std::vector<uint8_t>& is_point,
                                   const Mesh& mesh, unsigned threads, SuppressionInfo* info) {
  Suppression s;
  s.out = std::move(map);
  return suppress_faces_into(s, s.out, is_point, mesh, threads, info);
}

}  // namespace meshsal
