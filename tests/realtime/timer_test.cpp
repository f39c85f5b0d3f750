#include <gtest/gtest.h>

#include "giq/realtime/timer.h"

namespace giq::realtime {
namespace {

TEST(Timings, PercentilesInterpolateBetweenOrderStatistics) {
  // numpy.percentile([1, 2, 3, 4], q) with linear interpolation: 50 -> 2.5, 95 -> 3.85.
  EXPECT_DOUBLE_EQ(percentile({4, 1, 3, 2}, 0.5), 2.5);
  EXPECT_NEAR(percentile({4, 1, 3, 2}, 0.95), 3.85, 1e-12);
  EXPECT_DOUBLE_EQ(percentile({7}, 0.99), 7.0);
}

TEST(Timings, WarmupFramesAreExcludedAndRepeatedPassesSummed) {
  std::vector<FrameTiming> f;
  f.push_back({0, true, 100.0, 120.0, {{"a", 100.0}}});
  for (int i = 1; i <= 3; ++i) f.push_back({i, false, double(i), 2.0 * i, {{"a", 1.0 * i}, {"shadow", 0.5}, {"shadow", 0.25}}});
  const auto j = timings_json(f, {{"technique", "x"}});
  EXPECT_EQ(j["technique"], "x");
  EXPECT_EQ(j["frames"]["warmup"], 1);
  EXPECT_EQ(j["frames"]["measured"], 3);
  EXPECT_DOUBLE_EQ(j["frame_gpu_ms"]["median"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(j["frame_cpu_ms"]["max"].get<double>(), 6.0);
  ASSERT_EQ(j["passes"].size(), 2u);
  EXPECT_EQ(j["passes"][1]["name"], "shadow");
  EXPECT_DOUBLE_EQ(j["passes"][1]["gpu_ms"]["median"].get<double>(), 0.75);
  EXPECT_EQ(j["per_frame"].size(), 4u);
}

}  // namespace
}  // namespace giq::realtime
