#include "giq/metrics/maps.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "giq/image/io.h"
#include "giq/image/srgb.h"
#include "giq/metrics/colormap.h"
#include "giq/metrics/error.h"
#include "synthetic.h"

using namespace giq;
using giq::metrics::rgb_layer;
namespace fs = std::filesystem;

TEST(Maps, MeansEqualTheScalarMetrics) {
  auto r = test::rgb_image(23, 11, [](int x, int y, int k) { return test::hash01(x, y, k) * 3.0f; });
  auto t = test::rgb_image(23, 11, [](int x, int y, int k) { return test::hash01(x, y, k, 7) * 3.0f; });
  t.channel("R")[4] = std::nanf("");
  const auto R = rgb_layer(r, "", "r"), T = rgb_layer(t, "", "t");
  const auto e = metrics::error_stats(R, T);
  auto mean = [](const metrics::Map& m) {
    double s = 0;
    size_t n = 0;
    for (float v : m.values)
      if (std::isfinite(v)) s += v, ++n;
    return s / double(n);
  };
  const auto abs_map = metrics::abs_error_map(R, T);
  EXPECT_TRUE(std::isnan(abs_map.values[4]));
  // Per-pixel values are rounded to float (relative 6e-8).
  EXPECT_NEAR(mean(abs_map), e.mae, e.mae * 1e-6);
  EXPECT_NEAR(mean(metrics::relative_error_map(R, T)), e.relmse, e.relmse * 1e-6);
  const auto s = metrics::signed_luminance_map(R, T);
  EXPECT_TRUE(s.is_signed);
  EXPECT_NEAR(s.values[7], T.luminance(7) - R.luminance(7), 1e-6);
}

TEST(Maps, ColourMapsEndPoints) {
  const auto m0 = metrics::magma(0.0f), m1 = metrics::magma(1.0f), mh = metrics::magma(0.5f);
  EXPECT_EQ(m0.r, 0); EXPECT_EQ(m0.g, 0); EXPECT_EQ(m0.b, 4);
  EXPECT_EQ(m1.r, 252); EXPECT_EQ(m1.g, 253); EXPECT_EQ(m1.b, 191);
  EXPECT_EQ(mh.r, 0xB6); EXPECT_EQ(mh.g, 0x36); EXPECT_EQ(mh.b, 0x79);
  // Monotonic in lightness: the sum of channels grows along the map.
  int prev = -1;
  for (int i = 0; i <= 64; ++i) {
    const auto c = metrics::magma(float(i) / 64.0f);
    EXPECT_GT(c.r + c.g + c.b, prev);
    prev = c.r + c.g + c.b;
  }
  const auto w = metrics::diverging(0.0f), b = metrics::diverging(-1.0f), r = metrics::diverging(1.0f);
  EXPECT_EQ(w.r, 255); EXPECT_EQ(w.g, 255); EXPECT_EQ(w.b, 255);
  EXPECT_EQ(b.r, 59); EXPECT_EQ(b.g, 76); EXPECT_EQ(b.b, 192);
  EXPECT_EQ(r.r, 180); EXPECT_EQ(r.g, 4); EXPECT_EQ(r.b, 38);
  const auto bad = metrics::magma(std::nanf(""));
  EXPECT_EQ(bad.g, 255);
}

TEST(Maps, AutoRangeAndWrittenHeatMap) {
  metrics::Map m{"abs_error", "mean_c |T_c - R_c|", "radiance", false, 100, 1, {}};
  for (int i = 0; i < 100; ++i) m.values.push_back(float(i + 1));  // 1..100
  const auto range = metrics::auto_range(m);
  EXPECT_EQ(range.lo, 0.0f);
  EXPECT_EQ(range.hi, 99.0f);  // the 99th of 100 sorted values
  metrics::Map zero{"z", "", "1", true, 3, 1, {0.0f, 0.0f, 0.0f}};
  EXPECT_EQ(metrics::auto_range(zero).hi, 1.0f);
  EXPECT_EQ(metrics::auto_range(zero).lo, -1.0f);

  fs::path d = fs::temp_directory_path() / ("giq_maps_" + std::to_string(::getpid()));
  fs::remove_all(d);
  const auto w = metrics::write_map(m, d, range);
  const auto exr = image::read_image(w.exr);
  EXPECT_EQ(exr.channel("Y")[41], 42.0f);
  EXPECT_EQ(exr.metadata.at("giq:definition"), "mean_c |T_c - R_c|");
  const auto png = image::read_image(w.png);
  EXPECT_EQ(png.metadata.at("giq:colormap"), "magma");
  EXPECT_EQ(png.metadata.at("giq:range_max"), "99");
  EXPECT_EQ(png.metadata.at("giq:range_min"), "0");
  // The last pixel (100 > 99) saturates at magma(1) = (252, 253, 191).
  EXPECT_NEAR(png.channel("B")[99], image::srgb_decode(191.0f / 255.0f), 1e-6);
  fs::remove_all(d);
}
