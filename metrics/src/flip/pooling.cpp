#include "pooling.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

namespace giq::metrics::flip {
namespace {

// A full sort of a 4K map costs more than the whole FLIP evaluation of one exposure, so the
// percentiles are found by a radix select instead: non-negative floats order like their bit
// patterns, so the top bits of the pattern bucket the values in order. One pass sums each
// bucket; the bucket that crosses a threshold is then sorted alone.
constexpr int kBucketShift = 15;  // 1.0f = 0x3F800000 -> bucket 0x7F00
constexpr size_t kBucketCount = (0x3F800000u >> kBucketShift) + 1;

uint32_t bucket_of(float v) { return std::bit_cast<uint32_t>(v) >> kBucketShift; }

// FLIP values lie in [0, 1]; anything else (which FLIP does not produce) is clamped, NaN to 0,
// so that a bucket index is always in range.
float unit(float v) { return v >= 0.0f ? std::min(v, 1.0f) : 0.0f; }

}  // namespace

PooledErrors pool_errors(const float* map, size_t count) {
  PooledErrors out;
  if (count == 0) return out;
  std::vector<double> bucket_sum(kBucketCount, 0.0);
  double total = 0.0;
  float max_value = 0.0f;
  for (size_t i = 0; i < count; ++i) {
    const float v = unit(map[i]);
    bucket_sum[bucket_of(v)] += v;
    total += v;
    max_value = std::max(max_value, v);
  }
  out.mean = total / double(count);
  out.max = max_value;
  if (total <= 0.0) return out;

  const std::array<double, 3> fractions{0.25, 0.5, 0.75};
  std::array<double, 3> results{};
  std::vector<float> members;
  for (size_t q = 0; q < fractions.size(); ++q) {
    const double threshold = fractions[q] * total;
    double before = 0.0;
    size_t bucket = 0;
    while (bucket + 1 < kBucketCount && before + bucket_sum[bucket] <= threshold) before += bucket_sum[bucket++];
    members.clear();
    for (size_t i = 0; i < count; ++i) {
      const float v = unit(map[i]);
      if (bucket_of(v) == bucket) members.push_back(v);
    }
    std::sort(members.begin(), members.end());
    double running = before;
    float value = members.empty() ? 0.0f : members.back();
    for (float v : members) {
      running += v;
      if (running > threshold) {
        value = v;
        break;
      }
    }
    results[q] = value;
  }
  out.weighted_q1 = results[0];
  out.weighted_median = results[1];
  out.weighted_q3 = results[2];
  return out;
}

}  // namespace giq::metrics::flip
