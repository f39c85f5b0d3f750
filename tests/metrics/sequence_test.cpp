#include "giq/metrics/sequence.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "giq/metrics/lag.h"
#include "synthetic.h"

using namespace giq;
using giq::metrics::rgb_layer;

TEST(Sequence, KnownBiasAndVariance) {
  // Per pixel p: e_t(p) = mu(p) + s(p) * (+1, -1, +1, -1, ...) over an even number of frames,
  // so mean_t e = mu, Var_t e = s^2 exactly (population variance).
  const int w = 6, h = 5, frames = 8;
  auto mu = [](int x, int y) { return 0.05f * float(x) - 0.1f; };
  auto s = [](int x, int y) { return 0.02f * float(y + 1); };
  auto r = test::rgb_image(w, h, [](int x, int y, int) { return 0.5f + 0.1f * float(x + y); });
  metrics::SequenceAccumulator acc(w, h, false);
  double mse = 0;
  for (int f = 0; f < frames; ++f) {
    const float sign = f % 2 ? -1.0f : 1.0f;
    auto t = test::rgb_image(w, h, [&](int x, int y, int) { return r.at("R", x, y) + mu(x, y) + sign * s(x, y); });
    acc.add(rgb_layer(r, "", "r"), rgb_layer(t, "", "t"), nullptr);
  }
  double bias2 = 0, var = 0, ymean = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      bias2 += double(mu(x, y)) * mu(x, y) / (w * h);
      var += double(s(x, y)) * s(x, y) / (w * h);
      ymean += r.at("R", x, y) / double(w * h);
    }
  mse = bias2 + var;
  const auto st = acc.stats();
  // Inputs are float: e carries ~1e-7 absolute error, so 1e-6 on values of order 1e-2.
  EXPECT_NEAR(st.bias2, bias2, 1e-6);
  EXPECT_NEAR(st.variance, var, 1e-6);
  EXPECT_NEAR(st.mse_seq, mse, 1e-6);
  EXPECT_NEAR(st.mse_seq, st.bias2 + st.variance, 1e-15);  // the decomposition is exact
  EXPECT_NEAR(st.flicker, std::sqrt(var) / ymean, 1e-5);
  EXPECT_EQ(st.variance_corrected, st.variance);  // no variance layer
  const auto map = acc.temporal_stddev_map();
  EXPECT_NEAR(map.values[size_t(2 * w + 3)], s(3, 2), 1e-6);
}

TEST(Sequence, ReferenceNoiseCorrection) {
  // sigma^2 = 0.0004 per channel, so sigma_Y^2 = 0.0004 (weights sum to 1).
  const int w = 4, h = 4;
  auto r = test::rgb_image(w, h, [](int, int, int) { return 1.0f; });
  test::add_layer(r, "variance", [](int, int, int) { return 0.0004f; });
  const auto var = rgb_layer(r, "variance", "r");
  auto t0 = test::rgb_image(w, h, [](int, int, int) { return 1.1f; });
  auto t1 = test::rgb_image(w, h, [](int, int, int) { return 1.05f; });
  // e = 0.1, 0.05: mean 0.075, bias^2 0.005625, variance 0.000625.
  for (bool per_frame : {true, false}) {
    metrics::SequenceAccumulator acc(w, h, per_frame);
    acc.add(rgb_layer(r, "", "r"), rgb_layer(t0, "", "t"), &var);
    acc.add(rgb_layer(r, "", "r"), rgb_layer(t1, "", "t"), &var);
    const auto st = acc.stats();
    EXPECT_NEAR(st.variance, 0.000625, 1e-8);
    EXPECT_NEAR(st.reference_noise, 0.0004, 1e-9);
    if (per_frame) {
      EXPECT_NEAR(st.variance_corrected, 0.000625 - 0.0004, 1e-8);
      EXPECT_NEAR(st.bias2_corrected, 0.005625 - 0.0004 / 2, 1e-8);
    } else {
      EXPECT_NEAR(st.variance_corrected, 0.000625, 1e-8);
      EXPECT_NEAR(st.bias2_corrected, 0.005625 - 0.0004, 1e-8);
    }
  }
}

TEST(Sequence, NonFiniteFramesExcludedPerPixel) {
  auto r = test::rgb_image(2, 1, [](int, int, int) { return 0.0f; });
  metrics::SequenceAccumulator acc(2, 1, false);
  for (int f = 0; f < 3; ++f) {
    auto t = test::rgb_image(2, 1, [&](int x, int, int) { return (x == 1 && f == 1) ? std::nanf("") : 0.3f; });
    acc.add(rgb_layer(r, "", "r"), rgb_layer(t, "", "t"), nullptr);
  }
  const auto st = acc.stats();
  EXPECT_EQ(st.nonfinite_pixel_frames, 1u);
  EXPECT_NEAR(st.bias2, 0.09, 1e-7);
  EXPECT_NEAR(st.variance, 0.0, 1e-12);
  EXPECT_TRUE(std::isnan(st.flicker));  // black reference: relative flicker undefined
}

TEST(Lag, ExponentialStepResponse) {
  // r_t = A exp(-(t - t0)/tau) for t >= t0 (A before the step is irrelevant), F frames.
  const double A = 2.0, tau = 4.0;
  const int frames = 60, t0 = 10;
  std::vector<double> r(frames);
  for (int t = 0; t < frames; ++t) r[size_t(t)] = t < t0 ? 0.0 : A * std::exp(-(t - t0) / tau);
  // r_inf: mean over the last 15 frames (t = 45..59), a geometric series.
  double r_inf = 0;
  for (int t = 45; t < 60; ++t) r_inf += A * std::exp(-(t - t0) / tau) / 15.0;
  const double threshold = r_inf + 0.1 * (A - r_inf);
  // First t - t0 with A exp(-(t-t0)/tau) <= threshold: ceil(tau ln(A / threshold)).
  const int expected = int(std::ceil(tau * std::log(A / threshold)));
  EXPECT_EQ(expected, 10);  // tau ln 10 = 9.21 -> 10 frames
  const auto lag = metrics::lag90(r, t0, 16.5);
  EXPECT_NEAR(lag.r_inf, r_inf, 1e-15);
  ASSERT_TRUE(lag.lag_frames.has_value());
  EXPECT_EQ(*lag.lag_frames, expected);
  EXPECT_DOUBLE_EQ(*lag.lag_ms, expected * 16.5);
}

TEST(Lag, NoResponseAndImmediateResponse) {
  std::vector<double> flat{1, 1, 5, 5, 5, 5, 5, 5};
  // r stays at its final level: r_t0 = r_inf, threshold = r_inf, reached at once.
  EXPECT_EQ(*metrics::lag90(flat, 2).lag_frames, 0);
  // Error grows after the step: r_inf = (4 + 5) / 2, threshold 4.5 + 0.1 (1 - 4.5) = 4.15 >= r_t0.
  std::vector<double> rising{0, 0, 0, 1, 2, 3, 4, 5};
  EXPECT_EQ(*metrics::lag90(rising, 3).lag_frames, 0);
  // Last 25% of 8 frames = 2 frames (5.05 and 4.95): r_inf = 5, s = 0.0707, threshold
  // 5 + max(0.1 (9 - 5), 2 s) = 5.4, first reached at t = 6.
  std::vector<double> slow{0, 9, 9, 9, 9, 9, 5.05, 4.95};
  const auto s = metrics::lag90(slow, 1);
  EXPECT_DOUBLE_EQ(s.r_inf, 5.0);
  EXPECT_NEAR(s.r_inf_stddev, 0.05 * std::sqrt(2.0), 1e-12);
  EXPECT_DOUBLE_EQ(s.threshold, 5.4);
  EXPECT_EQ(*s.lag_frames, 5);
  EXPECT_FALSE(s.lag_ms.has_value());  // no frame time given
  EXPECT_THROW(metrics::lag90(slow, 8), std::invalid_argument);
}

// Other content moving after the step: the settled error fluctuates by +-0.1 frame to frame.
TEST(Lag, FluctuatingSettledError) {
  const int frames = 16, t0 = 2;
  auto sequence = [&](double response) {
    std::vector<double> r(frames, 0.0);
    for (int t = t0; t < frames; ++t) r[size_t(t)] = 1.0 + response * std::pow(0.5, t - t0) + ((t - t0) % 2 ? -0.1 : 0.1);
    return r;
  };
  // No response beyond the fluctuation: r_t0 = 1.1 against r_inf = 1.0000 and s = 0.1155
  // (the last 4 frames: 1.1, 0.9, 1.1, 0.9). 10 % of the excess would put the
  // threshold at 1.01 and read the first dip, a frame later, as a lag of 1; within 2 s of
  // r_inf the step frame is already settled.
  const auto none = metrics::lag90(sequence(0.0), t0);
  EXPECT_NEAR(none.r_inf_stddev, 0.1 * std::sqrt(4.0 / 3.0), 1e-3);
  EXPECT_EQ(*none.lag_frames, 0);
  // A response of 2, halving every frame, on the same fluctuation: r_t = 3.1, 1.9, 1.6, 1.15, ...;
  // r_inf = 1.0009, s = 0.1158, threshold 1.0009 + max(0.21, 0.2316) = 1.2326, first reached
  // 3 frames after the step.
  const auto halving = metrics::lag90(sequence(2.0), t0);
  EXPECT_NEAR(halving.threshold, 1.2326, 1e-4);
  EXPECT_EQ(*halving.lag_frames, 3);
}

TEST(Lag, ChangedRegion) {
  auto before = test::rgb_image(4, 1, [](int, int, int) { return 1.0f; });
  auto after = test::rgb_image(4, 1, [](int x, int, int) { return x < 2 ? 1.0f : 1.0f + 0.1f * float(x); });
  test::add_layer(before, "variance", [](int, int, int) { return 0.0005f; });
  test::add_layer(after, "variance", [](int, int, int) { return 0.0005f; });
  // 3 sqrt(0.0005 + 0.0005) = 0.0949: x = 2 (change 0.2) and x = 3 (0.3) are in the region.
  const auto vb = rgb_layer(before, "variance", "b"), va = rgb_layer(after, "variance", "a");
  const auto region = metrics::changed_region(rgb_layer(before, "", "b"), &vb, rgb_layer(after, "", "a"), &va);
  EXPECT_EQ(region, (std::vector<uint8_t>{0, 0, 1, 1}));
  EXPECT_NEAR(metrics::region_abs_error(rgb_layer(before, "", "b"), rgb_layer(after, "", "a"), region), 0.25, 1e-6);
}
