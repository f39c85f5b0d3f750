#include "giq/metrics/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "synthetic.h"

using namespace giq;
using giq::metrics::error_stats;
using giq::metrics::rgb_layer;

namespace {
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();
}  // namespace

TEST(Error, IdenticalImagesGiveZeroAndInfinitePsnr) {
  auto r = test::rgb_image(17, 9, [](int x, int y, int k) { return test::hash01(x, y, k) * 4.0f; });
  const auto e = error_stats(rgb_layer(r, "", "r"), rgb_layer(r, "", "r"));
  EXPECT_EQ(e.mse, 0.0);
  EXPECT_EQ(e.rmse, 0.0);
  EXPECT_EQ(e.mae, 0.0);
  EXPECT_EQ(e.relmse, 0.0);
  EXPECT_EQ(e.smape, 0.0);
  EXPECT_TRUE(std::isinf(e.psnr) && e.psnr > 0);
  EXPECT_EQ(e.valid_pixels, 17u * 9u);
  EXPECT_FALSE(e.noise.has_value());
}

TEST(Error, ConstantOffsetGivesClosedForm) {
  // R = 0.2 (R), 0.4 (G), 0.6 (B) everywhere; T = R + d.
  const float base[3] = {0.2f, 0.4f, 0.6f};
  const float d = 0.25f;
  auto r = test::rgb_image(8, 5, [&](int, int, int k) { return base[k]; });
  auto t = test::rgb_image(8, 5, [&](int, int, int k) { return base[k] + d; });
  const auto e = error_stats(rgb_layer(r, "", "r"), rgb_layer(t, "", "t"));
  double rel = 0, smape = 0, se_clamped = 0;
  for (int k = 0; k < 3; ++k) {
    const double rv = base[k], tv = float(base[k] + d), dd = tv - rv;
    rel += dd * dd / (rv * rv + 0.01) / 3.0;
    smape += std::abs(dd) / (std::abs(tv) + std::abs(rv) + 1e-4) / 3.0;
    const double dc = std::min(tv, 1.0) - rv;
    se_clamped += dc * dc / 3.0;
  }
  // float inputs: T - R is exact to ~1 ulp of 0.85 (6e-8), so relative 1e-6 is generous.
  EXPECT_NEAR(e.mse, 0.0625, 0.0625 * 1e-6);
  EXPECT_NEAR(e.rmse, 0.25, 0.25 * 1e-6);
  EXPECT_NEAR(e.mae, 0.25, 0.25 * 1e-6);
  EXPECT_NEAR(e.relmse, rel, rel * 1e-6);
  EXPECT_NEAR(e.smape, smape, smape * 1e-6);
  EXPECT_NEAR(e.psnr, 10.0 * std::log10(1.0 / se_clamped), 1e-5);
}

TEST(Error, NonFiniteTestPixelsAreCountedAndExcluded) {
  auto r = test::rgb_image(6, 4, [](int x, int y, int k) { return test::hash01(x, y, k); });
  auto t = test::rgb_image(6, 4, [](int x, int y, int k) { return test::hash01(x, y, k) + 0.5f; });
  t.channel("G")[3] = kNaN;
  t.channel("B")[7] = kInf;
  t.channel("R")[11] = -kInf;
  t.channel("R")[7] = kNaN;  // same pixel as an Inf: still one pixel
  const auto e = error_stats(rgb_layer(r, "", "r"), rgb_layer(t, "", "t"));
  EXPECT_EQ(e.nonfinite_pixels, 3u);
  EXPECT_EQ(e.valid_pixels, 24u - 3u);
  EXPECT_NEAR(e.mse, 0.25, 1e-6);  // every remaining pixel is off by exactly 0.5
  EXPECT_NEAR(e.mae, 0.5, 1e-6);
  EXPECT_TRUE(std::isfinite(e.relmse) && std::isfinite(e.smape) && std::isfinite(e.psnr));
}

TEST(Error, AllNonFiniteGivesUndefinedNotZero) {
  auto r = test::rgb_image(2, 2, [](int, int, int) { return 1.0f; });
  auto t = test::rgb_image(2, 2, [](int, int, int) { return kNaN; });
  const auto e = error_stats(rgb_layer(r, "", "r"), rgb_layer(t, "", "t"));
  EXPECT_EQ(e.nonfinite_pixels, 4u);
  EXPECT_EQ(e.valid_pixels, 0u);
  EXPECT_TRUE(std::isnan(e.mse));
  EXPECT_TRUE(std::isnan(e.psnr));
  EXPECT_TRUE(std::isnan(e.relmse_trimmed));
}

TEST(Error, AllBlackReferenceAndAllBlackTest) {
  auto black = test::rgb_image(5, 5, [](int, int, int) { return 0.0f; });
  auto grey = test::rgb_image(5, 5, [](int, int, int) { return 0.5f; });
  const auto same = error_stats(rgb_layer(black, "", "r"), rgb_layer(black, "", "t"));
  EXPECT_EQ(same.mse, 0.0);
  EXPECT_EQ(same.smape, 0.0);  // 0 / (0 + 0 + 1e-4)
  EXPECT_TRUE(std::isinf(same.psnr));
  // Black reference: relmse = d^2 / 0.01, smape = d / (d + 1e-4).
  const auto e = error_stats(rgb_layer(black, "", "r"), rgb_layer(grey, "", "t"));
  EXPECT_NEAR(e.relmse, 0.25 / 0.01, 1e-9);
  EXPECT_NEAR(e.smape, 0.5 / 0.5001, 1e-9);
  EXPECT_NEAR(e.psnr, 10.0 * std::log10(1.0 / 0.25), 1e-9);
  // Black test against a lit reference: smape = R / (R + 1e-4).
  const auto b = error_stats(rgb_layer(grey, "", "r"), rgb_layer(black, "", "t"));
  EXPECT_NEAR(b.smape, 0.5 / 0.5001, 1e-9);
  EXPECT_NEAR(b.relmse, 0.25 / (0.25 + 0.01), 1e-9);
}

TEST(Error, ExtremeReferenceValues) {
  // Half the pixels at 1e6, half at 1e-8; the test is 1% brighter everywhere. Accumulation in
  // double keeps the tiny pixels' contribution (1e-20) next to the huge ones' (1e8).
  auto r = test::rgb_image(4, 4, [](int x, int, int) { return x < 2 ? 1e6f : 1e-8f; });
  auto t = test::rgb_image(4, 4, [](int x, int, int) { return x < 2 ? 1.01e6f : 1.01e-8f; });
  const auto e = error_stats(rgb_layer(r, "", "r"), rgb_layer(t, "", "t"));
  const double dh = double(1.01e6f) - double(1e6f), dl = double(1.01e-8f) - double(1e-8f);
  EXPECT_NEAR(e.mse, (dh * dh + dl * dl) / 2.0, 1e-9 * dh * dh);
  EXPECT_NEAR(e.mae, (dh + dl) / 2.0, 1e-9 * dh);
  // relmse: the huge pixels give ~1e-4 (relative), the tiny ones ~1e-18 (absolute / 0.01).
  const double rel = (dh * dh / (1e12 + 0.01) + dl * dl / (1e-16 + 0.01)) / 2.0;
  EXPECT_NEAR(e.relmse, rel, rel * 1e-6);
  EXPECT_TRUE(std::isfinite(e.psnr));
  EXPECT_NEAR(e.psnr, 10.0 * std::log10(1.0 / (dl * dl / 2.0)), 1e-3);  // clamped: only the tiny ones differ
}

TEST(Error, SinglePixel) {
  auto r = test::rgb_image(1, 1, [](int, int, int k) { return 0.1f * float(k + 1); });
  auto t = test::rgb_image(1, 1, [](int, int, int k) { return 0.1f * float(k + 1) - 0.05f; });
  const auto e = error_stats(rgb_layer(r, "", "r"), rgb_layer(t, "", "t"));
  EXPECT_EQ(e.pixels, 1u);
  EXPECT_NEAR(e.mse, 0.0025, 1e-9);
  EXPECT_NEAR(e.mae, 0.05, 1e-8);
}

TEST(Error, NoiseFloorAndUnresolvedFlags) {
  // Reference variance sigma^2 = 0.01 everywhere: mse noise floor 0.01.
  auto r = test::rgb_image(10, 10, [](int, int, int) { return 0.5f; });
  test::add_layer(r, "variance", [](int, int, int) { return 0.01f; });
  const auto var = rgb_layer(r, "variance", "r");
  auto close = test::rgb_image(10, 10, [](int, int, int) { return 0.6f; });  // mse 0.01 < 3 x 0.01
  auto far = test::rgb_image(10, 10, [](int, int, int) { return 1.0f; });    // mse 0.25 > 0.03
  const auto a = error_stats(rgb_layer(r, "", "r"), rgb_layer(close, "", "t"), &var);
  ASSERT_TRUE(a.noise.has_value());
  EXPECT_NEAR(a.noise->mean_variance, 0.01, 1e-9);  // 0.01f
  EXPECT_EQ(a.mse_debiased, a.mse - a.noise->mean_variance);
  EXPECT_TRUE(a.unresolved_mse);
  // mae floor: sqrt(2/pi) * 0.1 = 0.0798; 0.1 < 3 x 0.0798.
  EXPECT_NEAR(a.noise->mae, std::sqrt(2.0 / M_PI) * 0.1, 1e-7);
  EXPECT_TRUE(a.unresolved_mae);
  const auto b = error_stats(rgb_layer(r, "", "r"), rgb_layer(far, "", "t"), &var);
  EXPECT_FALSE(b.unresolved_mse);
  EXPECT_FALSE(b.unresolved_mae);
  EXPECT_FALSE(b.unresolved_relmse);
  EXPECT_NEAR(b.mse_debiased, 0.25 - 0.01, 1e-7);
  // A zero-variance reference resolves everything, even identical images.
  auto z = test::rgb_image(10, 10, [](int, int, int) { return 0.5f; });
  test::add_layer(z, "variance", [](int, int, int) { return 0.0f; });
  const auto zv = rgb_layer(z, "variance", "z");
  EXPECT_FALSE(error_stats(rgb_layer(z, "", "z"), rgb_layer(z, "", "z"), &zv).unresolved_mse);
}

TEST(Error, AVarianceLayerThatCannotBeOneIsNotTrusted) {
  // One pixel of negative variance (impossible): that pixel is left out and counted with the
  // non-finite reference pixels, not read as 0. The other 99 pixels: mse 0.25 exactly.
  auto r = test::rgb_image(10, 10, [](int, int, int) { return 0.5f; });
  test::add_layer(r, "variance", [](int x, int y, int) { return x == 3 && y == 4 ? -1.0f : 0.0f; });
  const auto var = rgb_layer(r, "variance", "r");
  auto t = test::rgb_image(10, 10, [](int x, int y, int) { return x == 3 && y == 4 ? 100.0f : 1.0f; });
  const auto e = error_stats(rgb_layer(r, "", "r"), rgb_layer(t, "", "t"), &var);
  EXPECT_EQ(e.reference_nonfinite_pixels, 1u);
  EXPECT_EQ(e.valid_pixels, 99u);
  EXPECT_DOUBLE_EQ(e.mse, 0.25);
  // A variance of 1e38 (finite, but larger than any error): the debiased mse goes negative and
  // the error is flagged as below the reference's noise, not reported as resolved.
  auto huge = test::rgb_image(10, 10, [](int, int, int) { return 0.5f; });
  test::add_layer(huge, "variance", [](int, int, int) { return 1e38f; });
  const auto hv = rgb_layer(huge, "variance", "h");
  const auto h = error_stats(rgb_layer(huge, "", "h"), rgb_layer(t, "", "t"), &hv);
  EXPECT_LT(h.mse_debiased, 0.0);
  EXPECT_TRUE(h.unresolved_mse);
}

TEST(Error, TrimmedRelmseLeavesOutTheHottestPixelsOnly) {
  // 200 x 100 = 20000 pixels: floor(1e-4 x 20000) = 2 are trimmed. Every pixel is 0.1 off
  // a reference of 1, and two "fireflies" are 1e4 off: relmse is theirs, the trimmed mean is
  // the rest's closed form exactly (within the float inputs' rounding).
  auto r = test::rgb_image(200, 100, [](int, int, int) { return 1.0f; });
  auto t = test::rgb_image(200, 100, [](int x, int y, int) {
    return (x == 7 && y == 3) || (x == 150 && y == 90) ? 1.0e4f : 1.1f;
  });
  const auto e = error_stats(rgb_layer(r, "", "r"), rgb_layer(t, "", "t"));
  const double d = double(1.1f) - 1.0, hot = 1.0e4 - 1.0;
  const double body = d * d / 1.01;
  EXPECT_EQ(e.trimmed_pixels, 2u);
  EXPECT_NEAR(e.relmse, (19998.0 * body + 2.0 * hot * hot / 1.01) / 20000.0, 1e-9 * e.relmse);
  EXPECT_GT(e.relmse, 1e3 * body);
  EXPECT_NEAR(e.relmse_trimmed, body, 1e-12);
  // Under 10000 valid pixels nothing is trimmed: the two means are the same number.
  auto small_r = test::rgb_image(50, 40, [](int x, int y, int k) { return test::hash01(x, y, k); });
  auto small_t = test::rgb_image(50, 40, [](int x, int y, int k) { return test::hash01(x, y, k) * 1.5f; });
  const auto s = error_stats(rgb_layer(small_r, "", "r"), rgb_layer(small_t, "", "t"));
  EXPECT_EQ(s.trimmed_pixels, 0u);
  EXPECT_NEAR(s.relmse_trimmed, s.relmse, 1e-12 * s.relmse);
}
