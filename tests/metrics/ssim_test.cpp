#include "giq/metrics/ssim.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "giq/image/srgb.h"
#include "synthetic.h"

using namespace giq;
using giq::metrics::rgb_layer;

namespace {

// Independent evaluation in double, straight from Wang et al. 2004 eq. 13 with the 2D
// Gaussian window written out (no separability), renormalised over the valid pixels it covers.
std::vector<double> brute_ssim(const std::vector<float>& x, const std::vector<float>& y, int w, int h) {
  const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
  std::vector<double> out(size_t(w) * size_t(h), std::numeric_limits<double>::quiet_NaN());
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      const size_t c = size_t(py) * size_t(w) + size_t(px);
      if (std::isnan(x[c]) || std::isnan(y[c])) continue;
      double m = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
      for (int dy = -5; dy <= 5; ++dy)
        for (int dx = -5; dx <= 5; ++dx) {
          const int qx = px + dx, qy = py + dy;
          if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
          const size_t q = size_t(qy) * size_t(w) + size_t(qx);
          if (std::isnan(x[q]) || std::isnan(y[q])) continue;
          const double g = std::exp(-(dx * dx + dy * dy) / (2 * 1.5 * 1.5));
          m += g, sx += g * x[q], sy += g * y[q], sxx += g * x[q] * x[q], syy += g * y[q] * y[q], sxy += g * x[q] * y[q];
        }
      const double mx = sx / m, my = sy / m;
      const double vx = sxx / m - mx * mx, vy = syy / m - my * my, cxy = sxy / m - mx * my;
      out[c] = ((2 * mx * my + c1) * (2 * cxy + c2)) / ((mx * mx + my * my + c1) * (vx + vy + c2));
    }
  return out;
}

}  // namespace

TEST(Ssim, ImageWithItselfIsOne) {
  auto r = test::rgb_image(40, 23, [](int x, int y, int k) { return test::hash01(x, y, k) * 2.0f; });
  const auto s = metrics::ssim(rgb_layer(r, "", "r"), rgb_layer(r, "", "r"), true);
  // (2 mu^2 + c1)(2 var + c2) / ((2 mu^2 + c1)(2 var + c2)) = 1 up to double rounding.
  EXPECT_NEAR(s.mean, 1.0, 1e-12);
  for (float v : s.map) EXPECT_NEAR(v, 1.0f, 1e-6f);
}

TEST(Ssim, ConstantImagesClosedForm) {
  // Constant display-referred lumas a, b: the variances vanish, so SSIM = (2ab + c1)/(a^2+b^2+c1).
  const float la = 0.2f, lb = 0.6f;
  auto r = test::rgb_image(13, 7, [&](int, int, int) { return la; });
  auto t = test::rgb_image(13, 7, [&](int, int, int) { return lb; });
  const double a = metrics::display_luma(rgb_layer(r, "", "r"), 0);
  const double b = metrics::display_luma(rgb_layer(t, "", "t"), 0);
  EXPECT_NEAR(a, image::srgb_encode(0.2f), 1e-6);  // grey: luma weights sum to 1
  const double c1 = 1e-4;
  const auto s = metrics::ssim(rgb_layer(r, "", "r"), rgb_layer(t, "", "t"));
  EXPECT_NEAR(s.mean, (2 * a * b + c1) / (a * a + b * b + c1), 1e-9);
}

TEST(Ssim, ShiftedImageMatchesDirectEvaluation) {
  // A random texture against itself shifted right by one pixel.
  const int w = 31, h = 19;
  std::vector<float> x(size_t(w) * h), y(size_t(w) * h);
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      x[size_t(py) * w + px] = test::hash01(px, py, 0);
      y[size_t(py) * w + px] = test::hash01(std::max(px - 1, 0), py, 0);
    }
  const auto s = metrics::ssim_planes(x.data(), y.data(), w, h, true);
  const auto ref = brute_ssim(x, y, w, h);
  double mean = 0;
  for (size_t i = 0; i < ref.size(); ++i) {
    EXPECT_NEAR(s.map[i], ref[i], 1e-6) << i;  // map stored as float
    mean += ref[i];
  }
  mean /= double(ref.size());
  EXPECT_NEAR(s.mean, mean, 1e-10);
  EXPECT_LT(s.mean, 0.5);  // a one-pixel shift of white noise destroys the structure
}

TEST(Ssim, NonFinitePixelsAreExcludedAndDoNotSpread) {
  const int w = 20, h = 20;
  std::vector<float> x(size_t(w) * h), y(size_t(w) * h);
  for (size_t i = 0; i < x.size(); ++i) x[i] = test::hash01(int(i), 1, 0), y[i] = 0.9f * x[i] + 0.05f;
  y[5 * w + 5] = std::numeric_limits<float>::quiet_NaN();
  y[12 * w + 3] = std::numeric_limits<float>::infinity();
  const auto s = metrics::ssim_planes(x.data(), y.data(), w, h, true);
  EXPECT_EQ(s.valid_pixels, size_t(w * h - 2));
  EXPECT_TRUE(std::isfinite(s.mean));
  std::vector<float> yc = y;
  yc[12 * w + 3] = std::numeric_limits<float>::quiet_NaN();  // the brute force marks invalid with NaN
  const auto ref = brute_ssim(x, yc, w, h);
  for (size_t i = 0; i < ref.size(); ++i) {
    if (std::isnan(ref[i])) EXPECT_TRUE(std::isnan(s.map[i]));
    else EXPECT_NEAR(s.map[i], ref[i], 1e-6);
  }
}

TEST(Ssim, SinglePixelAndAllBlack) {
  auto r = test::rgb_image(1, 1, [](int, int, int) { return 0.5f; });
  auto t = test::rgb_image(1, 1, [](int, int, int) { return 0.25f; });
  const double a = metrics::display_luma(rgb_layer(r, "", "r"), 0), b = metrics::display_luma(rgb_layer(t, "", "t"), 0);
  const auto s = metrics::ssim(rgb_layer(r, "", "r"), rgb_layer(t, "", "t"));
  EXPECT_NEAR(s.mean, (2 * a * b + 1e-4) / (a * a + b * b + 1e-4), 1e-9);
  // Black against black: (0 + c1)(0 + c2) / ((0 + c1)(0 + c2)) = 1.
  auto k = test::rgb_image(9, 9, [](int, int, int) { return 0.0f; });
  EXPECT_NEAR(metrics::ssim(rgb_layer(k, "", "k"), rgb_layer(k, "", "k")).mean, 1.0, 1e-12);
  // Black against white: c1 / (1 + c1).
  auto wh = test::rgb_image(9, 9, [](int, int, int) { return 1.0f; });
  EXPECT_NEAR(metrics::ssim(rgb_layer(k, "", "k"), rgb_layer(wh, "", "w")).mean, 1e-4 / (1.0 + 1e-4), 1e-9);
}
