#include <gtest/gtest.h>

#include <cmath>

#include "giq/scenes/light.h"

namespace giq::scenes {
namespace {

TEST(Light, RangeWindowFollowsKhrLightsPunctual) {
  EXPECT_FLOAT_EQ(range_window(3.0f, 0.0f), 1.0f);  // no range: no window
  EXPECT_FLOAT_EQ(range_window(0.0f, 4.0f), 1.0f);
  EXPECT_FLOAT_EQ(range_window(2.0f, 4.0f), 1.0f - 1.0f / 16.0f);  // 1 - (1/2)^4
  EXPECT_FLOAT_EQ(range_window(4.0f, 4.0f), 0.0f);
  EXPECT_FLOAT_EQ(range_window(9.0f, 4.0f), 0.0f);  // clamped, not negative
}

TEST(Light, SpotAttenuationIsSquaredLinearRampInCosine) {
  const float inner = 0.2f, outer = 0.5f;
  EXPECT_FLOAT_EQ(spot_attenuation(1.0f, inner, outer), 1.0f);
  EXPECT_NEAR(spot_attenuation(std::cos(inner), inner, outer), 1.0f, 1e-5f);
  EXPECT_NEAR(spot_attenuation(std::cos(outer), inner, outer), 0.0f, 1e-5f);
  EXPECT_FLOAT_EQ(spot_attenuation(std::cos(1.0f), inner, outer), 0.0f);
  // Half-way in cosine: (1/2)^2.
  const float mid = 0.5f * (std::cos(inner) + std::cos(outer));
  EXPECT_NEAR(spot_attenuation(mid, inner, outer), 0.25f, 1e-5f);
}

TEST(Light, RadiantIsColourTimesIntensity) {
  Light l;
  l.color = {0.5f, 1.0f, 0.25f};
  l.intensity = 4.0f;
  EXPECT_EQ(l.radiant(), glm::vec3(2.0f, 4.0f, 1.0f));
}

}  // namespace
}  // namespace giq::scenes
