// meshsal (internal): the priority queue of edge collapses used by simplify.cpp.
// Entries carry their order key inline; a bucket queue over the float cost hands the
// entries of one cost range at a time to a small 4-ary heap.
#pragma once
#include <cstdint>
#include <cstring>
#include <new>
#include <vector>

namespace meshsal {
namespace detail {

// 16 bytes, so that the heap stays cache friendly. The order key is the cost rounded to
// float (ties then break on the vertex indices); the exact cost is recomputed on collapse.
// `a` comes first so that (a, cost) read as one little-endian 64-bit word orders by cost,
// then a: costs are never negative, -0 or NaN (Quadric::error clamps to +0), and the bits
// of such floats order like their values.
struct Entry {
  uint32_t a;      // a < b; a survives
  float cost;
  uint32_t b;
  uint32_t stamp;  // collapse count when the cost was computed
};
inline Entry make_entry(double cost, uint32_t a, uint32_t b, uint32_t stamp) {
  return {a, float(cost), b, stamp};
}
inline uint64_t cost_a(const Entry& x) {
  uint64_t k;
  std::memcpy(&k, &x, 8);
  return k;
}

// Orders by (cost, a, b): the deterministic tie-break shared by both simplifiers. No
// branches: the heap compares in random order, and mispredictions were half its time.
inline bool key_less(const Entry& x, const Entry& y) {
  const uint64_t kx = cost_a(x), ky = cost_a(y);
  return (kx < ky) | ((kx == ky) & (x.b < y.b));
}

// Keeps the elements of data[0, n) for which keep() is true, in order, at the front;
// returns how many. No branch on keep(): which entries are stale or dead is a coin toss.
template <class T, class F>
size_t keep_if(T* data, size_t n, F keep) {
  size_t kept = 0;
  for (size_t i = 0; i < n; ++i) {
    const T x = data[i];
    data[kept] = x;
    kept += keep(x);
  }
  return kept;
}

// Allocator with 64-byte (cache line) alignment, for the heap below.
template <class T>
struct LineAlloc {
  using value_type = T;
  LineAlloc() = default;
  template <class U>
  LineAlloc(const LineAlloc<U>&) {}
  T* allocate(size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t(64))); }
  void deallocate(T* p, size_t) { ::operator delete(p, std::align_val_t(64)); }
  template <class U>
  bool operator==(const LineAlloc<U>&) const { return true; }
  template <class U>
  bool operator!=(const LineAlloc<U>&) const { return false; }
};

// 4-ary min-heap of edge entries with the keys inline (16-byte entries, so the four
// children of a node share one 64-byte line). Entries are never updated in place: a collapse
// pushes the survivor's new edges and the old ones are dropped when they surface (stamps).
class EdgeHeap {
 public:
  // Node i lives at s_[i + kPad]: with the storage 64-byte aligned, the four children of a
  // node (4i+1 .. 4i+4) then fill exactly one cache line, so each level of a sift costs one
  // miss, not two.
  static constexpr size_t kPad = 3;
  EdgeHeap() : s_(kPad) {}
  bool empty() const { return s_.size() == kPad; }
  size_t size() const { return s_.size() - kPad; }
  const Entry& top() const { return s_[kPad]; }
  // The heap of the entries in [begin, end) that keep() accepts.
  template <class F>
  void assign(const Entry* begin, const Entry* end, F keep) {
    s_.resize(kPad);
    s_.insert(s_.end(), begin, end);
    filter(keep);
  }
  // Drops the entries for which keep() is false and restores the heap order, O(n).
  template <class F>
  void filter(F keep) {
    s_.resize(kPad + keep_if(s_.data() + kPad, size(), keep));
    heapify();
  }
  void push(const Entry& e) {
    s_.push_back(e);
    Entry* h = s_.data() + kPad;
    size_t i = size() - 1;
    while (i > 0) {
      const size_t parent = (i - 1) / 4;
      if (!key_less(e, h[parent])) break;
      h[i] = h[parent];
      i = parent;
    }
    h[i] = e;
  }
  Entry pop() {
    const Entry top = s_[kPad];
    const Entry last = s_.back();
    s_.pop_back();
    if (!empty()) {
      s_[kPad] = last;
      down(0);
    }
    return top;
  }

 private:
  void heapify() {
    const size_t n = size();
    if (n > 1)
      for (size_t i = (n - 2) / 4 + 1; i-- > 0;) down(i);
  }
  void down(size_t i) {
    Entry* h = s_.data() + kPad;
    const size_t n = size();
    const Entry v = h[i];
    for (;;) {
      const size_t c = 4 * i + 1;
      if (c >= n) break;
      size_t m = c;
      if (c + 4 <= n) {  // all four children: select without branches
        const size_t m01 = key_less(h[c + 1], h[c]) ? c + 1 : c;
        const size_t m23 = key_less(h[c + 3], h[c + 2]) ? c + 3 : c + 2;
        m = key_less(h[m23], h[m01]) ? m23 : m01;
      } else {
        for (size_t j = c + 1; j < n; ++j)
          if (key_less(h[j], h[m])) m = j;
      }
      if (!key_less(h[m], v)) break;
      h[i] = h[m];
      i = m;
    }
    h[i] = v;
  }
  std::vector<Entry, LineAlloc<Entry>> s_;
};

// Bucket queue in front of the heap. Entries are sorted into buckets by the top bits of
// their float cost (16 buckets per power of two); only the lowest bucket sits in the heap.
// Pops are then sifts through a heap of a few thousand entries that stays in cache, not
// through all ~3 entries per vertex; a push above the current bucket is an append; and
// entries that went stale while they waited in a bucket are dropped in one pass when their
// bucket comes up, without ever being sifted. The order of pops is exactly key_less order:
// every waiting bucket only holds keys above those of the current one, and a push at or
// below the current bucket goes straight into the heap.
class EdgeQueue {
 public:
  static constexpr int kShift = 19;  // float bits >> 19: sign, exponent, 4 mantissa bits
  static constexpr size_t kBuckets = size_t(1) << (32 - kShift);
  EdgeQueue() : buckets_(kBuckets) {}
  static uint32_t bucket_of(const Entry& e) {
    uint32_t bits;
    std::memcpy(&bits, &e.cost, 4);
    return bits >> kShift;
  }
  size_t size() const { return size_; }
  void push(const Entry& e) {
    const uint32_t k = bucket_of(e);
    if (k <= current_)
      heap_.push(e);
    else
      buckets_[k].push_back(e);
    ++size_;
  }
  // Makes sure the heap holds the lowest entries: when it is empty, moves the next waiting
  // bucket in, keeping only the entries keep() accepts. False when nothing is left.
  template <class F>
  bool ready(F keep) {
    while (heap_.empty()) {
      size_t k = current_ + 1;
      while (k < kBuckets && buckets_[k].empty()) ++k;
      if (k >= kBuckets) return false;
      current_ = uint32_t(k);
      std::vector<Entry>& b = buckets_[k];
      size_ -= b.size();
      heap_.assign(b.data(), b.data() + b.size(), keep);
      size_ += heap_.size();
      std::vector<Entry>().swap(b);
    }
    return true;
  }
  // The lowest entry; only after ready() returned true.
  const Entry& top() const { return heap_.top(); }
  Entry pop() {
    --size_;
    return heap_.pop();
  }
  // Whether the heap has a next entry to look at (for prefetching), without refilling.
  bool has_top() const { return !heap_.empty(); }
  // Drops every entry for which keep() is false, O(size).
  template <class F>
  void filter(F keep) {
    heap_.filter(keep);
    size_ = heap_.size();
    for (size_t k = current_ + 1; k < kBuckets; ++k) {
      std::vector<Entry>& b = buckets_[k];
      b.resize(keep_if(b.data(), b.size(), keep));
      size_ += b.size();
    }
  }

 private:
  std::vector<std::vector<Entry>> buckets_;
  EdgeHeap heap_;
  uint32_t current_ = 0;  // the bucket in the heap; every lower one is empty
  size_t size_ = 0;       // entries in the heap and the buckets
};

}  // namespace detail
}  // namespace meshsal
