#pragma once
// Internal: deterministic parallel reductions. Rows are cut into fixed chunks whatever the
// thread count, each chunk is summed in double, and the chunk sums are added in order, so a
// metric gives the same bits on 1 or 64 threads (TBB's parallel_reduce splits by load).

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <limits>
#include <vector>

namespace giq::metrics::detail {

constexpr int kRowsPerChunk = 16;

// A sum and a count, for means reduced with reduce_rows.
struct MeanSum {
  double sum = 0;
  size_t n = 0;
  MeanSum& operator+=(const MeanSum& o) {
    sum += o.sum, n += o.n;
    return *this;
  }
  double mean() const { return n ? sum / double(n) : std::numeric_limits<double>::quiet_NaN(); }
};

// Chunks summed at once before their sums are added: bounds the partial sums kept, which
// matters when an Acc holds more than a few numbers (error_stats' largest errors).
constexpr int kChunksPerBatch = 32;

// body(y0, y1, Acc& acc) accumulates rows [y0, y1) into acc; Acc needs operator+=.
template <class Acc, class Body>
Acc reduce_rows(int height, const Body& body) {
  const int chunks = (height + kRowsPerChunk - 1) / kRowsPerChunk;
  Acc total{};
  for (int b0 = 0; b0 < chunks; b0 += kChunksPerBatch) {
    const int b1 = std::min(chunks, b0 + kChunksPerBatch);
    std::vector<Acc> partial(size_t(b1 - b0));
    tbb::parallel_for(tbb::blocked_range<int>(b0, b1), [&](const tbb::blocked_range<int>& r) {
      for (int k = r.begin(); k != r.end(); ++k)
        body(k * kRowsPerChunk, std::min(height, (k + 1) * kRowsPerChunk), partial[size_t(k - b0)]);
    });
    for (const auto& p : partial) total += p;
  }
  return total;
}

// body(y0, y1) processes rows [y0, y1).
template <class Body>
void for_rows(int height, const Body& body) {
  tbb::parallel_for(tbb::blocked_range<int>(0, height, kRowsPerChunk),
                    [&](const tbb::blocked_range<int>& r) { body(r.begin(), r.end()); });
}

}  // namespace giq::metrics::detail
