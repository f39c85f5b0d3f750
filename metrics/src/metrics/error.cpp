#include "giq/metrics/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include "parallel.h"

namespace giq::metrics {
namespace {

// The `capacity` pixels of largest relative error seen (a min-heap on it), each with its noise
// floor, and the sums over every other pixel: what relmse_trimmed needs, in memory bounded by
// the number trimmed rather than by the image. Evictions and merges happen in a fixed order,
// so the sums are the same bits on any number of threads.
struct Largest {
  using Pixel = std::pair<double, double>;  // relative squared error summed over RGB, its floor
  size_t capacity = 0;
  std::vector<Pixel> heap;
  double rest = 0, rest_floor = 0;
  static bool greater(const Pixel& a, const Pixel& b) { return a.first > b.first; }
  void add(Pixel p) {
    if (heap.size() < capacity) {
      heap.push_back(p);
      std::push_heap(heap.begin(), heap.end(), greater);
      return;
    }
    if (!heap.empty() && p.first > heap.front().first) {
      std::pop_heap(heap.begin(), heap.end(), greater);
      std::swap(p, heap.back());
      std::push_heap(heap.begin(), heap.end(), greater);
    }
    rest += p.first, rest_floor += p.second;
  }
  Largest& operator+=(const Largest& o) {
    if (capacity == 0) capacity = o.capacity;
    rest += o.rest, rest_floor += o.rest_floor;
    for (const Pixel& p : o.heap) add(p);
    return *this;
  }
};

struct Sums {
  size_t valid = 0, test_bad = 0, ref_bad = 0;
  double se = 0, ae = 0, rel = 0, smape = 0, se_clamped = 0;
  double var = 0, var_rel = 0, sd = 0, sd_smape = 0;
  Largest largest;
  Sums& operator+=(const Sums& o) {
    valid += o.valid, test_bad += o.test_bad, ref_bad += o.ref_bad;
    se += o.se, ae += o.ae, rel += o.rel, smape += o.smape, se_clamped += o.se_clamped;
    var += o.var, var_rel += o.var_rel, sd += o.sd, sd_smape += o.sd_smape;
    largest += o.largest;
    return *this;
  }
};

double clamp01(double v) { return v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v); }

}  // namespace

ErrorStats error_stats(const RgbLayer& ref, const RgbLayer& test, const RgbLayer* variance) {
  const int w = ref.width;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // At most this many pixels are trimmed (kTrimFraction of all of them, valid or not).
  const size_t most_trimmed = size_t(kTrimFraction * double(ref.pixel_count()));
  const Sums s = detail::reduce_rows<Sums>(ref.height, [&](int y0, int y1, Sums& acc) {
    acc.largest.capacity = most_trimmed;
    for (size_t i = size_t(y0) * size_t(w), end = size_t(y1) * size_t(w); i < end; ++i) {
      // A variance is finite and not negative, or the pixel's reference cannot be trusted: it
      // is left out like a non-finite one (and counted with them).
      const bool ref_ok = ref.finite(i) && (!variance || (variance->finite(i) && variance->c[0][i] >= 0.0f &&
                                                          variance->c[1][i] >= 0.0f && variance->c[2][i] >= 0.0f));
      if (!test.finite(i)) {
        ++acc.test_bad;
        if (!ref_ok) ++acc.ref_bad;
        continue;
      }
      if (!ref_ok) {
        ++acc.ref_bad;
        continue;
      }
      ++acc.valid;
      double rel = 0.0, rel_floor = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double r = ref.c[k][i], t = test.c[k][i], d = t - r;
        acc.se += d * d;
        acc.ae += std::abs(d);
        acc.rel += d * d / (r * r + kRelmseEpsilon);
        rel += d * d / (r * r + kRelmseEpsilon);
        acc.smape += std::abs(d) / (std::abs(t) + std::abs(r) + kSmapeEpsilon);
        const double dc = clamp01(t) - clamp01(r);
        acc.se_clamped += dc * dc;
        if (variance) {
          const double v = variance->c[k][i];
          // E|X| = sqrt(2/pi) sigma for X ~ N(0, sigma^2).
          const double sd = std::sqrt(v) * std::sqrt(2.0 / std::numbers::pi);
          acc.var += v;
          acc.var_rel += v / (r * r + kRelmseEpsilon);
          rel_floor += v / (r * r + kRelmseEpsilon);
          acc.sd += sd;
          acc.sd_smape += sd / (2.0 * std::abs(r) + kSmapeEpsilon);
        }
      }
      acc.largest.add({rel, rel_floor});
    }
  });

  ErrorStats e;
  e.pixels = ref.pixel_count();
  e.valid_pixels = s.valid;
  e.nonfinite_pixels = s.test_bad;
  e.reference_nonfinite_pixels = s.ref_bad;
  const double n = 3.0 * double(s.valid);
  auto mean = [&](double sum) { return s.valid ? sum / n : nan; };
  e.mse = mean(s.se);
  e.rmse = std::sqrt(e.mse);
  e.mae = mean(s.ae);
  e.relmse = mean(s.rel);
  // Trimmed: the valid pixels without the k of largest relative error; the heap holds at
  // least k of them (k <= most_trimmed), largest first once sorted.
  e.trimmed_pixels = size_t(kTrimFraction * double(s.valid));
  std::vector<Largest::Pixel> top = s.largest.heap;
  std::sort(top.begin(), top.end(), Largest::greater);
  double kept = s.largest.rest, kept_floor = s.largest.rest_floor;
  for (size_t i = e.trimmed_pixels; i < top.size(); ++i) kept += top[i].first, kept_floor += top[i].second;
  const double kept_n = 3.0 * double(s.valid - e.trimmed_pixels);
  e.relmse_trimmed = s.valid ? kept / kept_n : nan;
  e.smape = mean(s.smape);
  e.mse_clamped = mean(s.se_clamped);
  e.psnr = !s.valid ? nan
           : e.mse_clamped == 0.0 ? std::numeric_limits<double>::infinity()
                                  : 10.0 * std::log10(1.0 / e.mse_clamped);
  if (variance) {
    NoiseFloor nf;
    nf.mean_variance = mean(s.var);
    nf.relmse = mean(s.var_rel);
    nf.mae = mean(s.sd);
    nf.smape = mean(s.sd_smape);
    e.mse_debiased = e.mse - nf.mean_variance;
    e.unresolved_mse = e.mse < kUnresolvedFactor * nf.mean_variance;
    e.unresolved_relmse = e.relmse < kUnresolvedFactor * nf.relmse;
    nf.relmse_trimmed = s.valid ? kept_floor / kept_n : nan;
    e.unresolved_relmse_trimmed = e.relmse_trimmed < kUnresolvedFactor * nf.relmse_trimmed;
    e.unresolved_mae = e.mae < kUnresolvedFactor * nf.mae;
    e.unresolved_smape = e.smape < kUnresolvedFactor * nf.smape;
    e.noise = nf;
  }
  return e;
}

}  // namespace giq::metrics
