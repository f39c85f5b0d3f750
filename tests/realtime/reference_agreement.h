#pragma once
// Per-pixel agreement of a real-time render with the CPU reference, both carrying the
// variance of their pixel means (`variance.R/G/B`): the z-score (a - b) / sqrt(var_a + var_b)
// of two unbiased estimators of the same pixel is close to standard normal, so beyond 4 sigma
// there should be almost no pixels (6e-5 of a normal population; 0.5% allowed), and the image
// means must agree within 4 standard errors (the sum of the differences against the sum of
// the variances: unbiased whatever the estimators' distributions).
//
// The mean per-pixel z-score is computed too (R, G and B of a pixel share their paths, so z
// is averaged per pixel first and pixels are the independent units; its standard error comes
// from the z-scores' own spread). It is zero in expectation only when both sides draw their
// samples from the same distribution: each side's variance is estimated from its own samples
// and correlates with its own mean, which biases E[z] by O(1/sqrt(spp)) when the two
// distributions differ (e.g. the reference picks one light per vertex by power where `pt`
// evaluates every punctual light). `check_mean_z` gates on it (within 4 standard errors) where
// the two estimators sample alike.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "giq/image/image.h"

namespace giq::test {

struct Agreement {
  size_t outliers = 0, n = 0;
  double diff_sum = 0.0, var_sum = 0.0;
  double mean_z = 0.0, mean_z_se = 0.0;  // over pixels with noise (variance > 0)
};

// `prefix` selects the layer ("" = beauty R,G,B; "direct." = the direct layer, compared with
// the beauty's variance, which bounds it when the indirect part is zero).
inline Agreement expect_agreement(const image::Image& gpu, const image::Image& cpu,
                                  const std::string& what, const std::string& prefix = "",
                                  bool check_mean_z = false) {
  Agreement a;
  std::vector<double> pixel_z(gpu.pixel_count(), 0.0);
  std::vector<int> pixel_noisy(gpu.pixel_count(), 0);
  for (const char* c : {"R", "G", "B"}) {
    const std::string ch = prefix + c, v = std::string("variance.") + c;
    for (size_t i = 0; i < gpu.pixel_count(); ++i) {
      const double x = gpu.channel(ch)[i], y = cpu.channel(ch)[i];
      const double var =
          (gpu.has_channel(v) ? double(gpu.channel(v)[i]) : 0.0) + double(cpu.channel(v)[i]);
      EXPECT_TRUE(std::isfinite(x)) << what << " pixel " << i;
      a.diff_sum += x - y;
      a.var_sum += var;
      ++a.n;
      // Noise-free pixels (emission seen directly, black background) must agree to float
      // rounding; the others by their z-score.
      const double z = std::abs(x - y) / std::sqrt(var + 1e-12 * (x * x + y * y) + 1e-30);
      a.outliers += z > 4.0;
      if (var > 0.0) pixel_z[i] += (x - y) / std::sqrt(var), ++pixel_noisy[i];
    }
  }
  double sum = 0.0, sum2 = 0.0;
  size_t m = 0;
  for (size_t i = 0; i < pixel_z.size(); ++i) {
    if (pixel_noisy[i] == 0) continue;
    const double z = pixel_z[i] / pixel_noisy[i];
    sum += z, sum2 += z * z, ++m;
  }
  if (m > 1) {
    a.mean_z = sum / double(m);
    a.mean_z_se = std::sqrt(std::max(0.0, sum2 / double(m) - a.mean_z * a.mean_z) / double(m - 1));
    if (check_mean_z) {
      EXPECT_LE(std::abs(a.mean_z), 4.0 * a.mean_z_se)
          << what << ": mean z " << a.mean_z << ", se " << a.mean_z_se;
    }
  }
  EXPECT_LE(double(a.outliers), 0.005 * double(a.n))
      << what << ": " << a.outliers << " of " << a.n << " beyond 4 sigma";
  EXPECT_LE(std::abs(a.diff_sum), 4.0 * std::sqrt(a.var_sum))
      << what << ": image mean differs by " << a.diff_sum / double(a.n) << ", se "
      << std::sqrt(a.var_sum) / double(a.n);
  // The measured agreement, for the log (docs/realtime.md quotes these numbers).
  std::printf("%s: %zu of %zu beyond 4 sigma, mean z %.4f (se %.4f), mean difference %.3g (se %.3g)\n", what.c_str(),
              a.outliers, a.n, a.mean_z, a.mean_z_se, a.diff_sum / double(a.n), std::sqrt(a.var_sum) / double(a.n));
  return a;
}

}  // namespace giq::test
