#pragma once
// Whether two independent Monte Carlo renders of the same view agree within their noise: the
// per-pixel two-sample z-score of their difference,
//
//   z = (a - b) / sqrt(s2 / n_a + s2 / n_b + q_a + q_b),
//
// with s2 the pooled per-sample variance of both renders' variance layers (each layer is the
// variance of its pixel mean, so n_a var_a is its per-sample variance; pooled with weights
// n_a and n_b as in the two-sample test), n the per-pixel sample counts (`spp` channel), and q
// the variance of storage rounding (float16 colour layers: a uniform rounding error of one
// half-precision ulp has variance ulp^2 / 12; zero is exact). Pooling matters for a low-spp
// render: its own variance estimate is noisy and correlated with its mean (a pixel that missed
// a rare bright path is both too dark and too certain), which alone would bias z; the pooled
// estimate is dominated by the far larger golden. The sum test D = sum(a - b) / sqrt(sum of
// the same variances) per channel is the image-wide mean difference in units of its standard
// deviation. Used by the golden re-render test.

#include <cmath>
#include <cstdint>
#include <string>

#include "giq/image/image.h"

namespace giq::test {

struct Agreement {
  size_t values = 0;    // pixel-channel values compared (both variances finite)
  size_t exact = 0;     // of them, zero variance on both sides and equal values (e.g. black)
  size_t beyond_4 = 0;  // |z| > 4, including values that differ with zero variance
  double mean_z = 0.0;  // mean z over the values with a non-zero variance
  double sum_z2 = 0.0;
  size_t with_variance = 0;
  double sum_test[3] = {0.0, 0.0, 0.0};  // D per channel R, G, B
};

// One half-precision ulp at |v| (normal range: 2^(e - 10); subnormal: 2^-24).
inline double half_ulp(double v) {
  const double a = std::fabs(v);
  if (a < 6.103515625e-05) return std::ldexp(1.0, -24);
  return std::ldexp(1.0, int(std::floor(std::log2(a))) - 10);
}

// Compares the beauty R, G, B of `a` and `b`; `scale_b` multiplies b and its standard error
// (a deliberately changed renderer, to show the check can fail). `a_half`/`b_half`: whether
// that file's colour channels were stored as float16.
inline Agreement agreement(const image::Image& a, const image::Image& b, bool a_half, bool b_half,
                           double scale_b = 1.0) {
  Agreement r;
  double sum_z = 0.0;
  const float *na = a.channel("spp"), *nb = b.channel("spp");
  int ci = 0;
  for (const char* c : {"R", "G", "B"}) {
    const std::string var = std::string("variance.") + c;
    const float *va = a.channel(c), *vb = b.channel(c), *sa = a.channel(var), *sb = b.channel(var);
    double diff = 0.0, diff_var = 0.0;
    for (size_t i = 0; i < a.pixel_count(); ++i) {
      const double x = va[i], y = double(vb[i]) * scale_b;
      const double n_a = na[i], n_b = nb[i];
      const double pooled =
          (n_a * n_a * double(sa[i]) + n_b * n_b * double(sb[i]) * scale_b * scale_b) / (n_a + n_b);
      double s2 = pooled / n_a + pooled / n_b;
      if (a_half && x != 0.0) s2 += half_ulp(x) * half_ulp(x) / 12.0;
      if (b_half && y != 0.0) s2 += half_ulp(y) * half_ulp(y) / 12.0;
      if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(s2) || !(n_a > 0.0 && n_b > 0.0))
        continue;
      ++r.values;
      if (!(s2 > 0.0)) {
        if (x == y)
          ++r.exact;
        else
          ++r.beyond_4;
        continue;
      }
      const double z = (x - y) / std::sqrt(s2);
      ++r.with_variance;
      sum_z += z;
      r.sum_z2 += z * z;
      diff += x - y;
      diff_var += s2;
      if (std::fabs(z) > 4.0) ++r.beyond_4;
    }
    r.sum_test[ci++] = diff_var > 0.0 ? diff / std::sqrt(diff_var) : 0.0;
  }
  r.mean_z = r.with_variance ? sum_z / double(r.with_variance) : 0.0;
  return r;
}

}  // namespace giq::test
