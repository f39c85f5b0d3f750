// `hybrid` against the CPU reference: with the spatial filter off (iterations = 0), the colour
// averaged with alpha = 0 and the history capped at the frame count, SVGF's temporal
// accumulation of a static scene is exactly the mean of the raw samples; those samples are
// `pt`'s paths from the G-buffer's first hit, so the mean agrees with the reference within
// noise at the same points (the reference's camera rays through the pixel centres, where the
// G-buffer shades: RenderSettings::pixel_centre). The per-pixel variance of the mean comes from
// the raw samples' own spread (reference_agreement.h).
#include <gtest/gtest.h>

#include <cmath>

#include "giq/realtime/renderer.h"
#include "giq/reference/renderer.h"
#include "giq/scenes/scene.h"
#include "reference_agreement.h"
#include "test_scenes.h"

namespace giq::realtime {
namespace {

using test::layer;

class HybridReferenceTest : public test::VulkanTest {
 protected:
  void expect_converges(const scenes::Scene& scene, int size, int frames, bool check_mean_z, const std::string& what) {
    RenderOptions o;
    o.technique = "hybrid";
    o.width = o.height = uint32_t(size);
    o.frames = frames;
    o.parameters = {"iterations=0", "alpha_colour=0", "alpha_moments=0", "history_cap=" + std::to_string(frames),
                    "bounces=64", "seed=11"};
    const size_t n = size_t(size) * size_t(size);
    std::vector<double> sum(3 * n, 0.0), sum2(3 * n, 0.0);
    image::Image last;
    render_sequence(*ctx, *compiler, scene, o, [&](RenderedFrame& f) {
      for (int c = 0; c < 3; ++c)
        for (size_t i = 0; i < n; ++i) {
          const double x = double(f.image.channel(layer("raw_direct", c))[i]) + f.image.channel(layer("raw_indirect", c))[i];
          sum[c * n + i] += x;
          sum2[c * n + i] += x * x;
        }
      last = std::move(f.image);
    });
    // The output is the running mean: `frames` blends of a float mix, each within an ulp or
    // two, so 1e-4 relative bounds it with room (the plain mean is computed in double).
    image::Image mean(size, size);
    for (int c = 0; c < 3; ++c)
      for (size_t i = 0; i < n; ++i) {
        const double m = sum[c * n + i] / frames;
        const double var = std::max(0.0, sum2[c * n + i] / frames - m * m) * frames / (frames - 1.0) / frames;
        ASSERT_NEAR(last.channel(test::kRgb[c])[i], m, 1e-4 * std::abs(m) + 1e-7) << what << " pixel " << i;
        mean.add_channel(test::kRgb[c])[i] = float(m);
        mean.add_channel(std::string("variance.") + test::kRgb[c])[i] = float(var);
      }
    reference::RenderSettings rs;
    rs.width = rs.height = size;
    rs.seed = 3;
    rs.sampler = reference::Sampler::Independent;
    rs.pixel_centre = true;
    reference::Renderer ref(scene, scene.views[0].camera, rs);
    reference::Film film = ref.make_film();
    ref.render(film, uint32_t(frames));
    const image::Image cpu = film.to_image();
    test::expect_agreement(mean, cpu, what, "", check_mean_z);
  }
};

// The built-in Cornell box: its one source (the emissive mesh) is sampled as the reference
// samples it, so the mean z-score is gated too.
TEST_F(HybridReferenceTest, TemporalMeanConvergesToTheReferenceOnTheCornellBox) {
  expect_converges(test::builtin("cornell"), 64, 64, true, "hybrid, cornell");
}

// A point light beside the emitter: next-event estimation picks one of the two sources with
// probability 1/2 at every vertex (the reference samples both), which the MIS weights of
// the emitter must account for.
TEST_F(HybridReferenceTest, OneLightOfTwoConvergesToTheReference) {
  scenes::Scene s = test::builtin("cornell");
  scenes::Light l;
  l.type = scenes::LightType::Point;
  l.position = s.bounds.centre() + s.bounds.extent() * glm::vec3(0.25f, 0.15f, 0.2f);
  l.intensity = 0.5f;
  s.lights.push_back(l);
  s.derive();
  expect_converges(s, 48, 64, false, "hybrid, cornell with a point light");
}

}  // namespace
}  // namespace giq::realtime
