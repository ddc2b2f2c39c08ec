// meshsal: a percentile of more values than memory holds, by streaming them a few times
// (Sm's alpha and the collapse-error level of out-of-core simplification).
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace meshsal {

// Calls its argument once per value, in any order, the same values every time.
using ValueStream = std::function<void(const std::function<void(double)>&)>;

// The k-th smallest (0-based, k < the count) of the values of `stream`, all finite: a value
// range narrowed with 65536-bin histograms until at most `cap` values are left, which are
// then selected in memory. Streams the values about twice per narrowing.
double streamed_kth(const ValueStream& stream, uint64_t k, size_t cap = size_t(1) << 20);

// streamed_kth for several k at once: each stream pass serves every k still open (the
// percentiles of a report in the passes of one).
std::vector<double> streamed_kths(const ValueStream& stream, const std::vector<uint64_t>& ks,
                                  size_t cap = size_t(1) << 20);

// percentile() of saliency_weights.h over the `n` values of `stream` (all finite), to the
// bit: the order statistics it interpolates are found by narrowing a value range with
// 65536-bin histograms until at most `cap` values are left, which are then selected in
// memory. Streams the values about twice per narrowing. Throws Error for n == 0 or p
// outside [0, 100].
double streamed_percentile(const ValueStream& stream, uint64_t n, double p, size_t cap = size_t(1) << 20);

}  // namespace meshsal
