// Unbiasedness: light sampling alone, BSDF sampling alone and their MIS combination are three
// estimators of the same integral; their renders must agree within their standard errors.

#include <gtest/gtest.h>

#include "giq/reference/renderer.h"
#include "scene_builder.h"

namespace giq::reference {
namespace {

Film render_with(const scenes::Scene& s, Estimator e, uint32_t spp) {
  RenderSettings rs;
  rs.width = rs.height = 16;
  rs.max_bounces = 6;
  rs.estimator = e;
  rs.seed = 100 + uint64_t(e);  // independent renders
  Renderer r(s, test::glossy_scene_camera(), rs);
  Film f = r.make_film();
  r.render(f, spp);
  EXPECT_EQ(f.nonfinite_samples(), 0u);
  return f;
}

TEST(Estimators, LightOnlyBsdfOnlyAndMisAgree) {
  const scenes::Scene s = test::glossy_scene();
  const Film mis = render_with(s, Estimator::Mis, 64);
  const Film light = render_with(s, Estimator::LightOnly, 64);
  const Film bsdf = render_with(s, Estimator::BsdfOnly, 128);
  for (int y = 0; y < 16; y += 4)
    for (int x = 0; x < 16; x += 4) {
      const test::BlockStat m = test::block_luminance(mis, x, y, 4, 4);
      const test::BlockStat l = test::block_luminance(light, x, y, 4, 4);
      const test::BlockStat b = test::block_luminance(bsdf, x, y, 4, 4);
      EXPECT_NEAR(m.mean, l.mean, 4.5 * std::sqrt(m.variance + l.variance)) << "light-only, block " << x << "," << y;
      EXPECT_NEAR(m.mean, b.mean, 4.5 * std::sqrt(m.variance + b.variance)) << "bsdf-only, block " << x << "," << y;
    }
}

}  // namespace
}  // namespace giq::reference
