#pragma once
// Pooling of a FLIP error map into single numbers, as [FLIP] (pooling section) and the FLIP tool
// report them: the mean, and weighted percentiles where each pixel weighs as much as its error.

#include <cstddef>

namespace giq::metrics::flip {

struct PooledErrors {
  double mean = 0.0;
  double weighted_q1 = 0.0;      // weighted 25th percentile
  double weighted_median = 0.0;  // weighted 50th percentile
  double weighted_q3 = 0.0;      // weighted 75th percentile
  double max = 0.0;
};

// Weighted percentile p: the smallest error e_i (errors sorted ascending) whose running sum
// e_1 + ... + e_i exceeds p times the sum of all errors; 0 when every error is 0. Values must
// lie in [0, 1] (every FLIP value does; others are clamped, NaN counts as 0).
PooledErrors pool_errors(const float* map, size_t count);

}  // namespace giq::metrics::flip
