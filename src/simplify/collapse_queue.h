// meshsal (internal): the order of collapses in simplify_mesh. The edge queue (lowest cost
// first, stale entries dropped lazily) and the refused edges: an edge the check refused
// waits in the lists of both its ends until a collapse changes the 1-ring of one of them,
// then goes back into the queue.
#pragma once
#include <cstdint>
#include <vector>

#include "simplify/edge_queue.h"

namespace meshsal {
namespace detail {

class CollapseQueue {
 public:
  explicit CollapseQueue(size_t vertex_count)
      : refused_(vertex_count), has_refused_(vertex_count, 0) {}

  EdgeQueue& edges() { return edges_; }
  void push(const Entry& e) { edges_.push(e); }
  // Call once the initial edges are in.
  void start() { sweep_at_ = 2 * edges_.size() + 4096; }

  // Stale entries waiting in the queue only cost memory (they are dropped when their
  // bucket comes up): sweeps them out in one pass whenever the queue has doubled since the
  // last sweep, so that sweeping costs O(1) per push and memory stays within 2x.
  template <class Current>
  void sweep_if_grown(Current current) {
    if (edges_.size() <= sweep_at_) return;
    edges_.filter(current);
    sweep_at_ = 2 * edges_.size() + 4096;
  }

  // A refused edge: kept by both its ends.
  void refuse(const Entry& e) {
    refused_[e.a].push_back(e);
    refused_[e.b].push_back(e);
    has_refused_[e.a] = has_refused_[e.b] = 1;
  }
  // w's neighbourhood changed: its refused edges go back into the queue, those still
  // current; both ends' lists forget them.
  template <class Current>
  void release(uint32_t w, Current current) {
    if (!has_refused_[w]) return;  // one byte per vertex stays in cache, the vectors not
    has_refused_[w] = 0;
    for (const Entry& e : refused_[w]) {
      const uint32_t z = e.a ^ e.b ^ w;
      std::vector<Entry>& l = refused_[z];
      for (size_t i = 0; i < l.size(); ++i)
        if (l[i].a == e.a && l[i].b == e.b) {
          l[i] = l.back();
          l.pop_back();
          break;
        }
      has_refused_[z] = !l.empty();
      if (current(e)) edges_.push(e);
    }
    refused_[w].clear();
  }
  // v collapsed away: its refused edges are stale, dropped with their memory. (Their
  // entries in the other ends' lists are dropped when those are released.)
  void forget(uint32_t v) {
    if (!has_refused_[v]) return;
    std::vector<Entry>().swap(refused_[v]);
    has_refused_[v] = 0;
  }
  size_t refused_at(uint32_t v) const { return refused_[v].size(); }

 private:
  EdgeQueue edges_;
  std::vector<std::vector<Entry>> refused_;  // per vertex: its refused edges
  std::vector<uint8_t> has_refused_;         // per vertex: refused_[v] is not empty
  size_t sweep_at_ = 0;                      // queue size that triggers the next sweep
};

}  // namespace detail
}  // namespace meshsal
