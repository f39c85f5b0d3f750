// `gi1` against the CPU reference on the Cornell box, still camera, static scene.
//
// What it converges to. With `feedback=0` a probe ray's hit carries the light sources' exact
// irradiance and nothing else, so the technique estimates one bounce of indirect light: the
// reference's `indirect` layer with at most two scattering events (max_bounces = 2). With the
// feedback on (the default) it adds the bounces last frame's image saw, never more than the
// truth has, so the default lies between the one-bounce truth and the full truth.
//
// Its remaining bias, and the bound. After the caches converge the estimate still differs from
// the one-bounce truth by
//  - the irradiance's spherical-harmonic band limit (§2.4.2): bands 0-2 of the cosine lobe
//    leave an error of at most 9 % of the irradiance for any incident light (Ramamoorthi and
//    Hanrahan 2001, §3), which bounds the image mean's error too;
//  - the world cache's spatial average over a cell and the probes' interpolation between tiles:
//    the rays that fill a cell are the rays that read it and the interpolation weights sum to
//    one, so both move light between neighbouring pixels and cancel in the image mean to
//    first order;
//  - the hard shadow of an emitter towards its representative point at each hit
//    (passes/hit_irradiance.glsl), which moves a penumbra's light from one side of it to the
//    other, again nearly cancelling in the mean.
// The near field (section 3) is off for this check: it swaps the probes' light in the directions
// its occluders hide for the occluders' own, through a cone that approximates the visible set,
// which has no such bound. The defaults, near field included, are checked against the bracket.
// So each channel's image mean is within 9 % of the one-bounce truth's, plus the noise of the
// estimate: the world cache's moving average keeps the image mean drifting by about 2 % over
// ten frames, so the mean over frames 33-64 is compared, and its standard error is estimated
// from 4 batches of 8 frames (each longer than the drift's correlation) and allowed 4 times;
// the reference's own noise (1024 samples) is far below either.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "giq/realtime/renderer.h"
#include "giq/reference/renderer.h"
#include "giq/scenes/scene.h"
#include "test_scenes.h"

namespace giq::realtime {
namespace {

using test::layer;

constexpr double kBandLimitBias = 0.09;  // Ramamoorthi and Hanrahan 2001, §3
constexpr int kFrames = 64, kFirstConverged = 33, kBatches = 4;

class Gi1ReferenceTest : public test::VulkanTest {
 protected:
  static constexpr int kSize = 64;

  // Each channel's image mean of the reference's `indirect` layer, at the pixel centres the
  // G-buffer shades.
  static std::array<double, 3> truth(const scenes::Scene& s, int max_bounces) {
    reference::RenderSettings rs;
    rs.width = rs.height = kSize;
    rs.seed = 3;
    rs.pixel_centre = true;
    rs.max_bounces = max_bounces;
    reference::Renderer ref(s, s.views[0].camera, rs);
    reference::Film film = ref.make_film();
    ref.render(film, 1024);
    const image::Image img = film.to_image();
    std::array<double, 3> m{};
    for (int c = 0; c < 3; ++c) {
      for (size_t i = 0; i < img.pixel_count(); ++i) m[c] += img.channel(layer("indirect", c))[i];
      m[c] /= double(img.pixel_count());
    }
    return m;
  }

  struct Estimate {
    std::array<double, 3> mean{}, standard_error{};
  };

  // Each channel's image mean of gi1's `indirect` layer over the converged frames, and its
  // standard error from batch means.
  Estimate gi1(const scenes::Scene& s, std::vector<std::string> params) {
    RenderOptions o;
    o.technique = "gi1";
    o.width = o.height = kSize;
    o.frames = kFrames;
    o.parameters = std::move(params);
    o.parameters.insert(o.parameters.end(), {"shadow_map_size=256", "cache_buckets_log2=8"});
    const int per_batch = (kFrames - kFirstConverged + 1) / kBatches;
    std::array<std::array<double, kBatches>, 3> batch{};
    int frame = 0;
    render_sequence(*ctx, *compiler, s, o, [&](RenderedFrame& f) {
      if (++frame < kFirstConverged) return;
      for (int c = 0; c < 3; ++c) {
        double sum = 0.0;
        for (size_t i = 0; i < f.image.pixel_count(); ++i)
          sum += f.image.channel(layer("indirect", c))[i];
        batch[c][(frame - kFirstConverged) / per_batch] +=
            sum / double(f.image.pixel_count()) / per_batch;
      }
    });
    Estimate e;
    for (int c = 0; c < 3; ++c) {
      double sum = 0.0, sum2 = 0.0;
      for (double b : batch[c]) sum += b, sum2 += b * b;
      e.mean[c] = sum / kBatches;
      e.standard_error[c] =
          std::sqrt(std::max(0.0, sum2 / kBatches - e.mean[c] * e.mean[c]) / (kBatches - 1.0));
    }
    return e;
  }
};

TEST_F(Gi1ReferenceTest, OneBounceConvergesToTheTruthWithinTheBandLimit) {
  const scenes::Scene s = test::builtin("cornell");
  const std::array<double, 3> one_bounce = truth(s, 2), full = truth(s, 64);
  const Estimate single = gi1(s, {"feedback=0", "near_field=0"}), fed = gi1(s, {});
  for (int c = 0; c < 3; ++c) {
    SCOPED_TRACE("channel " + std::to_string(c));
    const double noise = 4.0 * single.standard_error[c];
    std::printf(
        "gi1 on cornell, channel %d: one bounce %.4f of the one-bounce truth (se %.4f); with "
        "feedback %.4f of it "
        "and %.4f of the full truth (se %.4f)\n",
        c, single.mean[c] / one_bounce[c], single.standard_error[c] / one_bounce[c],
        fed.mean[c] / one_bounce[c], fed.mean[c] / full[c], fed.standard_error[c] / full[c]);
    EXPECT_NEAR(single.mean[c], one_bounce[c], kBandLimitBias * one_bounce[c] + noise);
    // The feedback adds light (the truth's further bounces carry about as much as its first) and
    // never more than the truth has.
    EXPECT_GT(fed.mean[c], (1.0 + kBandLimitBias) * one_bounce[c] + 4.0 * fed.standard_error[c]);
    EXPECT_LT(fed.mean[c], (1.0 + kBandLimitBias) * full[c] + 4.0 * fed.standard_error[c]);
  }
}

}  // namespace
}  // namespace giq::realtime
