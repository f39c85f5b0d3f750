#include "giq/metrics/leak.h"

#include <gtest/gtest.h>

#include <cmath>

#include "synthetic.h"

using namespace giq;
using giq::metrics::rgb_layer;

namespace {
// Reference: left half lit (Y = 1), right half dark (Y = 0.01 < 5% of the mean 0.505).
float ref_value(int x, int) { return x < 8 ? 1.0f : 0.01f; }
}  // namespace

TEST(Leak, DarkerTechniqueHasNoExcess) {
  auto r = test::rgb_image(16, 4, [](int x, int y, int) { return ref_value(x, y); });
  auto t = test::rgb_image(16, 4, [](int x, int y, int) { return 0.5f * ref_value(x, y); });
  const auto res = metrics::leak(rgb_layer(r, "", "r"), rgb_layer(t, "", "t"), nullptr, nullptr);
  EXPECT_EQ(res.automatic.pixels, 32u);
  EXPECT_EQ(res.automatic.excess_sum, 0.0);
  EXPECT_EQ(res.automatic.leak, 0.0);
  EXPECT_EQ(res.automatic.leak_pixels, 0.0);
}

TEST(Leak, AddedEnergyInRegionIsMeasured) {
  // Add grey k to the dark half: Y rises by k (luminance weights sum to 1) on 32 pixels.
  const float k = 0.2f;
  auto r = test::rgb_image(16, 4, [](int x, int y, int) { return ref_value(x, y); });
  auto t = test::rgb_image(16, 4, [&](int x, int y, int) { return ref_value(x, y) + (x >= 8 ? k : 0.0f); });
  const auto R = rgb_layer(r, "", "r"), T = rgb_layer(t, "", "t");
  const double sum_y = 32 * 1.0 + 32 * double(0.01f);
  const auto res = metrics::leak(R, T, nullptr, nullptr);
  // Per pixel the excess is (0.01f + 0.2f) - 0.01f in float luminance maths: 1e-6 relative.
  EXPECT_NEAR(res.automatic.excess_sum, 32 * 0.2, 32 * 0.2 * 1e-6);
  EXPECT_NEAR(res.automatic.leak, 32 * 0.2 / sum_y, 1e-6);
  EXPECT_NEAR(res.automatic.leak_absolute, 32 * 0.2 / 64.0, 1e-6);
  EXPECT_EQ(res.automatic.leak_pixels, 1.0);

  // Declared region through objectId: object 7 covers columns 12..15 only.
  float* id = r.add_channel("objectId", 3.0f);
  for (int y = 0; y < 4; ++y)
    for (int x = 12; x < 16; ++x) id[r.index(x, y)] = 7.0f;
  metrics::LeakOptions o;
  o.declared_object_ids = {7};
  const auto dec = metrics::leak(rgb_layer(r, "", "r"), T, nullptr, r.channel("objectId"), o);
  ASSERT_TRUE(dec.declared.has_value());
  EXPECT_EQ(dec.declared->pixels, 16u);
  EXPECT_NEAR(dec.declared->excess_sum, 16 * 0.2, 16 * 0.2 * 1e-6);
  EXPECT_NEAR(dec.declared->leak, 16 * 0.2 / sum_y, 1e-6);

  // With reference noise sigma = 0.1 per channel (sigma_Y = 0.1), only 0.2 - 3 x 0.1 counts:
  // nothing, since 0.2 < 0.3.
  test::add_layer(r, "variance", [](int, int, int) { return 0.01f; });
  const auto var = rgb_layer(r, "variance", "r");
  EXPECT_EQ(metrics::leak(R, T, &var, nullptr).automatic.excess_sum, 0.0);
  EXPECT_NEAR(metrics::leak_excess(R, T, &var, 15, 1.0), 0.1, 1e-6);  // 0.2 - 1 sigma
}

TEST(Leak, AllBlackReference) {
  auto r = test::rgb_image(4, 4, [](int, int, int) { return 0.0f; });
  auto t = test::rgb_image(4, 4, [](int x, int, int) { return x == 0 ? 0.5f : 0.0f; });
  const auto res = metrics::leak(rgb_layer(r, "", "r"), rgb_layer(t, "", "t"), nullptr, nullptr);
  EXPECT_EQ(res.automatic.pixels, 16u);           // every pixel is "dark"
  EXPECT_TRUE(std::isnan(res.automatic.leak));    // share of zero true light: undefined
  EXPECT_NEAR(res.automatic.leak_absolute, 4 * 0.5 / 16.0, 1e-7);
  EXPECT_NEAR(res.automatic.leak_pixels, 0.25, 1e-12);
  const auto m = metrics::leak_map(rgb_layer(r, "", "r"), rgb_layer(t, "", "t"), nullptr);
  EXPECT_NEAR(m.values[0], 0.5f, 1e-6f);
  EXPECT_EQ(m.values[1], 0.0f);
}
