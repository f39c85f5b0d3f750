// `pt` against the CPU reference (`giq_reference`) on every built-in scene: the same camera,
// units, BRDF and light transport must give the same image up to noise. Per pixel, the
// z-score (pt - reference) / sqrt(var_pt + var_reference) uses both renders' variance of the
// pixel mean; with both estimators unbiased it is close to standard normal, so beyond 4 sigma
// there should be almost no pixels (6e-5 of a normal population; the issue allows 0.5%), and
// the image means must agree within 4 standard errors.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "giq/realtime/renderer.h"
#include "giq/reference/renderer.h"
#include "giq/scenes/scene.h"
#include "test_scenes.h"

namespace giq::realtime {
namespace {

class PtReferenceTest : public test::VulkanTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(PtReferenceTest, AgreesWithinNoise) {
  const scenes::Scene loaded = scenes::load(std::filesystem::path(GIQ_SCENES_DIR) / (GetParam() + ".gltf"));
  const scenes::Scene scene = loaded.features.animation ? loaded.at_frame(0) : loaded;
  // 32 x 32 at 256 paths per pixel keeps each scene to seconds on lavapipe; the comparison
  // is per pixel, so the resolution only sets how many pixels are tested.
  const int size = 32;
  const uint32_t spp = 256;

  RenderOptions o;
  o.technique = "pt";
  o.view = "0";
  o.width = o.height = size;
  o.parameters = {"samples_per_frame=" + std::to_string(spp), "seed=7"};
  image::Image gpu;
  render_sequence(*ctx, *compiler, loaded, o, [&](RenderedFrame& f) { gpu = std::move(f.image); });

  reference::RenderSettings rs;
  rs.width = rs.height = size;
  rs.seed = 3;
  reference::Renderer ref(scene, scene.view("0").camera, rs);
  reference::Film film = ref.make_film();
  ref.render(film, spp);
  const image::Image cpu = film.to_image();

  size_t outliers = 0, n = 0;
  double diff_sum = 0.0, var_sum = 0.0;
  for (const char* c : {"R", "G", "B"}) {
    const std::string v = std::string("variance.") + c;
    for (size_t i = 0; i < gpu.pixel_count(); ++i) {
      const double a = gpu.channel(c)[i], b = cpu.channel(c)[i];
      const double var = double(gpu.channel(v)[i]) + double(cpu.channel(v)[i]);
      ASSERT_TRUE(std::isfinite(a)) << GetParam() << " pixel " << i;
      diff_sum += a - b;
      var_sum += var;
      ++n;
      // Noise-free pixels (emission seen directly, black background) must agree to float
      // rounding; the others by their z-score.
      const double z = std::abs(a - b) / std::sqrt(var + 1e-12 * (a * a + b * b) + 1e-30);
      outliers += z > 4.0;
    }
  }
  EXPECT_LE(double(outliers), 0.005 * double(n)) << GetParam() << ": " << outliers << " of " << n << " beyond 4 sigma";
  EXPECT_LE(std::abs(diff_sum), 4.0 * std::sqrt(var_sum)) << GetParam() << ": image mean differs by "
                                                           << diff_sum / double(n) << ", se " << std::sqrt(var_sum) / double(n);
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, PtReferenceTest,
                         ::testing::Values("cornell", "leak", "movinglight", "sunroom"));

}  // namespace
}  // namespace giq::realtime
