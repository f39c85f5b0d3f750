// A 16384 x 16384 pair: the streaming metrics must give the closed-form numbers without
// allocating per-pixel memory of their own (docs/metrics.md, "Memory").

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cmath>
#include <memory>

#include "giq/metrics/error.h"
#include "giq/metrics/leak.h"
#include "giq/image/srgb.h"
#include "giq/metrics/ssim.h"

using namespace giq;

namespace {

size_t peak_rss_bytes() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return size_t(u.ru_maxrss) * 1024;  // Linux reports KiB
}

}  // namespace

TEST(Extreme, Image16kMemoryBounded) {
  const int n = 16384;
  const size_t px = size_t(n) * n;
  // One plane per image serves as R, G and B (grey images): 2 GiB in all.
  std::unique_ptr<float[]> ref(new float[px]), test(new float[px]);
  for (size_t i = 0; i < px; ++i) {
    ref[i] = (i & 1) ? 0.5f : 0.0f;  // alternate columns lit and black
    test[i] = ref[i] + 0.25f;
  }
  metrics::RgbLayer R, T;
  for (int k = 0; k < 3; ++k) R.c[k] = ref.get(), T.c[k] = test.get();
  R.width = T.width = n;
  R.height = T.height = n;
  const size_t before = peak_rss_bytes();

  const auto e = metrics::error_stats(R, T);
  EXPECT_EQ(e.valid_pixels, px);
  EXPECT_NEAR(e.mse, 0.0625, 1e-12);
  EXPECT_NEAR(e.mae, 0.25, 1e-12);
  // relmse: half the pixels 0.0625 / (0.25 + 0.01), half 0.0625 / 0.01.
  EXPECT_NEAR(e.relmse, 0.5 * (0.0625 / 0.26 + 0.0625 / 0.01), 1e-9);
  const auto l = metrics::leak(R, T, nullptr, nullptr);
  // Dark region: the black columns (Y_R = 0 <= 0.05 x 0.25); each gains 0.25.
  EXPECT_EQ(l.automatic.pixels, px / 2);
  EXPECT_NEAR(l.automatic.leak, (0.25 * double(px / 2)) / (0.5 * double(px / 2)), 1e-9);

  const size_t growth = peak_rss_bytes() - before;
  // Working memory is per chunk of rows, not per pixel: far below one 1 GiB plane.
  EXPECT_LT(growth, size_t(64) << 20) << "peak RSS grew by " << (growth >> 20) << " MiB";
}

TEST(Extreme, SsimOnTallImageUsesBandMemory) {
  // SSIM keeps O(width x band) state whatever the height; checked on a 1024 x 16384 pair
  // (16 Mpx: a 16k x 16k SSIM takes minutes on two cores and belongs in bench/).
  const int w = 1024, h = 16384;
  const size_t px = size_t(w) * h;
  std::unique_ptr<float[]> a(new float[px]), b(new float[px]);
  for (size_t i = 0; i < px; ++i) a[i] = 0.25f, b[i] = 0.5f;
  metrics::RgbLayer A, B;
  for (int k = 0; k < 3; ++k) A.c[k] = a.get(), B.c[k] = b.get();
  A.width = B.width = w;
  A.height = B.height = h;
  const size_t before = peak_rss_bytes();
  const auto s = metrics::ssim(A, B);
  const double x = metrics::display_luma(A, 0), y = metrics::display_luma(B, 0);
  EXPECT_NEAR(s.mean, (2 * x * y + 1e-4) / (x * x + y * y + 1e-4), 1e-9);
  const size_t growth = peak_rss_bytes() - before;
  EXPECT_LT(growth, size_t(64) << 20) << "peak RSS grew by " << (growth >> 20) << " MiB";
}
