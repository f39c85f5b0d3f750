// `hybrid` (realtime/techniques/hybrid/): the a-trous filter leaves a constant image unchanged
// and never mixes across a depth discontinuity (a synthetic surface); with alpha = 1 and no
// iterations the output is the raw sample; reprojection keeps the history of surfaces that
// stay in view, follows moving geometry and drops the history of disoccluded pixels; every
// built-in scene renders finite layers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "giq/realtime/renderer.h"
#include "giq/realtime/resources.h"
#include "giq/realtime/scene_gpu.h"
#include "giq/realtime/timer.h"
#include "passes/gbuffer.h"
#include "techniques/hybrid/svgf.h"
#include "octahedral_map.h"
#include "test_scenes.h"

namespace giq::realtime {
namespace {

using test::layer;

using test::oct_encode;

float hash01(uint32_t i) {
  i = (i ^ 61u) ^ (i >> 16);
  i *= 9u;
  i ^= i >> 4;
  i *= 0x27d4eb2du;
  i ^= i >> 15;
  return float(i >> 8) / float(1u << 24);
}

class SvgfTest : public test::VulkanTest {
 protected:
  static constexpr uint32_t kSize = 32;
  Image image() {
    return Image(*ctx, {kSize, kSize, 1, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT});
  }
  // One a-trous iteration of `colour` (the same for both signals) over `surface` (svgf_shared.h).
  std::vector<float> atrous(const std::vector<float>& surface, const std::vector<float>& colour, int step) {
    Svgf svgf(*ctx, *compiler, kSize, kSize, SvgfSettings{});
    Image s = image(), in_d = image(), in_i = image(), out_d = image(), out_i = image();
    s.write_floats(surface);
    in_d.write_floats(colour);
    in_i.write_floats(colour);
    ctx->submit_and_wait([&](VkCommandBuffer cmd) {
      out_d.transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
      out_i.transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
      svgf.record_atrous(cmd, s, in_d, in_i, out_d, out_i, step);
    });
    const std::vector<float> d = out_d.read_floats(), i = out_i.read_floats();
    EXPECT_EQ(d, i);  // the two signals are filtered alike
    return d;
  }
};

// The weights are normalised, so any surface and any variance leave a constant colour
// constant: a sum of w c over a sum of w, 25 products of values below 1, is c to a few ulps.
TEST_F(SvgfTest, AtrousLeavesAConstantImageUnchanged) {
  std::vector<float> surface(4 * kSize * kSize), colour(4 * kSize * kSize);
  for (uint32_t i = 0; i < kSize * kSize; ++i) {
    const glm::vec3 n = glm::normalize(glm::vec3(hash01(3 * i) - 0.5f, hash01(3 * i + 1) - 0.5f, 1.0f));
    const glm::vec2 e = oct_encode(n);
    surface[4 * i + 0] = e.x, surface[4 * i + 1] = e.y;
    surface[4 * i + 2] = 1.0f + hash01(3 * i + 2);  // depth from 1 to 2
    surface[4 * i + 3] = 0.01f;
    colour[4 * i + 0] = 0.3f, colour[4 * i + 1] = 0.5f, colour[4 * i + 2] = 0.7f;
    colour[4 * i + 3] = 0.05f * hash01(7 * i);  // variance
  }
  for (int step : {1, 2, 4, 8}) {
    const std::vector<float> out = atrous(surface, colour, step);
    for (uint32_t i = 0; i < kSize * kSize; ++i)
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(out[4 * i + c], colour[4 * i + c], 1e-6f) << "step " << step << " pixel " << i;
  }
}

// Two planes facing the camera at depths 1 and 1.5, their depth changing by 1e-4 per pixel;
// colours 1..2 on the near one and 10..11 on the far one, with so large a variance that the
// luminance term lets everything through. The depth term's weight across the step,
// exp(-0.5 / (1e-4 x 8 x 2 sqrt 2)) at the widest tap, is 0 in float: every output pixel stays
// within its own plane's range, while the filter does smooth each plane.
TEST_F(SvgfTest, AtrousNeverMixesAcrossADepthDiscontinuity) {
  std::vector<float> surface(4 * kSize * kSize), colour(4 * kSize * kSize);
  const glm::vec2 e = oct_encode({0.0f, 0.0f, 1.0f});
  auto near_plane = [](uint32_t x, uint32_t y) { return x < kSize / 2 || (x < kSize / 2 + 4 && y < 8); };
  for (uint32_t y = 0; y < kSize; ++y)
    for (uint32_t x = 0; x < kSize; ++x) {
      const uint32_t i = y * kSize + x;
      const bool near = near_plane(x, y);
      surface[4 * i + 0] = e.x, surface[4 * i + 1] = e.y;
      surface[4 * i + 2] = near ? 1.0f : 1.5f;
      surface[4 * i + 3] = 1e-4f;
      const float v = (near ? 1.0f : 10.0f) + hash01(i);
      colour[4 * i + 0] = colour[4 * i + 1] = colour[4 * i + 2] = v;
      colour[4 * i + 3] = 1e6f;
    }
  for (int step : {1, 2, 4, 8}) {
    const std::vector<float> out = atrous(surface, colour, step);
    double spread_in = 0.0, spread_out = 0.0;
    for (uint32_t y = 0; y < kSize; ++y)
      for (uint32_t x = 0; x < kSize; ++x) {
        const uint32_t i = y * kSize + x;
        const float lo = near_plane(x, y) ? 1.0f : 10.0f;
        for (int c = 0; c < 3; ++c) {
          ASSERT_GE(out[4 * i + c], lo - 1e-5f) << "step " << step << " at " << x << "," << y;
          ASSERT_LE(out[4 * i + c], lo + 1.0f + 1e-5f) << "step " << step << " at " << x << "," << y;
        }
        spread_in += std::abs(colour[4 * i] - lo - 0.5f);
        spread_out += std::abs(out[4 * i] - lo - 0.5f);
      }
    EXPECT_LT(spread_out, 0.5 * spread_in) << "step " << step << ": the filter did not smooth";
  }
}

// The history as the filter sees it over a sequence of poses of the test Cornell box: each
// pose's G-buffer (with motion vectors), constant raw light, and the history layer read back.
class ReprojectionTest : public test::VulkanTest {
 protected:
  struct Frame {
    std::vector<float> position, history;
  };
  std::vector<Frame> run(const std::vector<scenes::Scene>& poses, uint32_t size) {
    const scenes::Camera cam = poses[0].views[0].camera;
    SceneGpu gpu(*ctx, *compiler, poses[0]);
    GBufferPass gbuffer(*ctx, *compiler, gpu, poses[0].features, size, size);
    gbuffer.enable_motion_vectors();
    Svgf svgf(*ctx, *compiler, size, size, SvgfSettings{});
    auto image = [&] { return Image(*ctx, {size, size, 1, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT}); };
    Image direct = image(), indirect = image(), unfiltered = image(), albedo = image(), out_d = image(),
          out_i = image(), history = image();
    const float one[4] = {1, 1, 1, 1}, zero[4] = {0, 0, 0, 0};
    GpuTimer timer(*ctx);
    std::vector<Frame> frames;
    for (size_t f = 0; f < poses.size(); ++f) {
      if (f > 0) gpu.update(poses[f]);
      ctx->submit_and_wait([&](VkCommandBuffer cmd) {
        timer.reset(cmd);
        gbuffer.record(cmd, cam, timer);
        direct.clear(cmd, one);
        indirect.clear(cmd, one);
        albedo.clear(cmd, one);
        unfiltered.clear(cmd, zero);
        full_barrier(cmd);
        svgf.record(cmd, {direct, indirect, unfiltered, albedo, out_d, out_i, history}, gbuffer, cam, f == 0, timer);
      });
      frames.push_back({gbuffer.position().read_floats(), history.read_floats()});
    }
    return frames;
  }
};

// Five frames of the box, then its tall block moves sideways by 0.15 (about 5 pixels at 64 x
// 64). A pixel whose surface did not move keeps its whole history (6 frames: its one tap has
// weight 1); a pixel that now sees the wall where in the previous frame the block covered
// its whole 3x3 neighbourhood is disoccluded: no tap is the same surface, history 1; and the
// block's own pixels follow it through the motion vectors.
TEST_F(ReprojectionTest, KeepsStaticHistoryFollowsMotionAndDropsDisocclusions) {
  const scenes::Scene box = test::cornell_box();
  scenes::Scene moved = box;
  const glm::vec3 v(0.15f, 0.0f, 0.0f);
  constexpr size_t kTallBlockFirstMesh = 7;  // as sequence_test.cpp
  for (size_t m = kTallBlockFirstMesh; m < kTallBlockFirstMesh + 6; ++m)
    for (auto& p : moved.meshes[m].positions) p += v;
  moved.derive();
  const uint32_t size = 64;
  const std::vector<Frame> f = run({box, box, box, box, box, moved}, size);
  const Frame &before = f[4], &after = f[5];
  auto pos = [&](const Frame& fr, int x, int y) {
    const float* p = &fr.position[4 * (size_t(y) * size + size_t(x))];
    return glm::vec4(p[0], p[1], p[2], p[3]);
  };
  EXPECT_EQ(before.history[4 * (size_t(size / 2) * size + size / 2)], 5.0f);
  int unchanged = 0, disoccluded = 0, on_block = 0, block_kept = 0;
  for (int y = 1; y + 1 < int(size); ++y)
    for (int x = 1; x + 1 < int(size); ++x) {
      const glm::vec4 now = pos(after, x, y);
      if (now.w == 0.0f) continue;
      const float h = after.history[4 * (size_t(y) * size + size_t(x))];
      if (glm::length(glm::vec3(now - pos(before, x, y))) < 1e-6f) {
        EXPECT_EQ(h, 6.0f) << "unchanged surface at " << x << "," << y;
        ++unchanged;
        continue;
      }
      // On the block now: where it was one frame ago (by the motion) is the block too.
      const glm::vec3 was = glm::vec3(now) - v;
      bool on_block_now = false;
      for (int yy = 0; yy < int(size) && !on_block_now; ++yy)
        for (int xx = 0; xx < int(size) && !on_block_now; ++xx)
          on_block_now = glm::length(glm::vec3(pos(before, xx, yy)) - was) < 0.02f;
      if (on_block_now) {
        ++on_block;
        block_kept += h == 6.0f;
        continue;
      }
      // Did the previous frame show other surfaces all round (the block in front)? Points of
      // the same surface one pixel apart are at most 0.06 apart here (the side walls at
      // grazing angles); the block's front is 0.4 or more in front of the wall.
      bool was_covered = true;
      for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
          const glm::vec4 b = pos(before, x + i, y + j);
          was_covered &= b.w != 0.0f && glm::length(glm::vec3(b - now)) > 0.1f;
        }
      if (was_covered) {
        EXPECT_EQ(h, 1.0f) << "disoccluded at " << x << "," << y;
        ++disoccluded;
      }
    }
  EXPECT_GT(unchanged, int(size * size / 2));
  EXPECT_GT(disoccluded, 10) << "the test must see disoccluded pixels";
  EXPECT_GT(on_block, 50);
  EXPECT_GT(block_kept, on_block * 8 / 10) << "the moving block's history did not follow it";
}

class HybridTest : public test::VulkanTest {};

// alpha = 1 takes only the new sample, and no a-trous iteration leaves it alone once the
// history is 4 frames long (shorter histories get the 7x7 variance estimate's spatial
// filter, as in Falcor): the output is the raw sample, up to the float rounding of dividing
// by the albedo and multiplying back (a few ulps).
TEST_F(HybridTest, WithAlphaOneAndNoIterationsTheOutputIsTheRawSample) {
  RenderOptions o;
  o.technique = "hybrid";
  o.width = o.height = 48;
  o.frames = 1;
  o.warmup = 5;
  o.parameters = {"alpha_colour=1", "alpha_moments=1", "iterations=0"};
  const image::Image img = render_last(test::cornell_box(), o);
  int lit = 0;
  for (int c = 0; c < 3; ++c)
    for (const char* l : {"direct", "indirect"}) {
      const std::string raw = std::string("raw_") + l;
      for (size_t i = 0; i < img.pixel_count(); ++i) {
        const float want = img.channel(layer(raw, c))[i], got = img.channel(layer(l, c))[i];
        ASSERT_NEAR(got, want, 1e-5f * std::abs(want) + 1e-30f) << l << " pixel " << i;
        lit += want > 0.0f;
      }
    }
  EXPECT_GT(lit, 48 * 48);
}

// The denoiser's contribution can be measured: with it off the output is a new noisy sample
// every frame and no raw layers are added; with it on the noise is far lower.
TEST_F(HybridTest, TheDenoiserReducesNoise) {
  RenderOptions o;
  o.technique = "hybrid";
  o.width = o.height = 48;
  o.frames = 2;
  o.warmup = 8;
  auto frame_difference = [&](const std::vector<std::string>& params, bool expect_raw) {
    o.parameters = params;
    std::vector<image::Image> frames;
    render_sequence(*ctx, *compiler, test::cornell_box(), o, [&](RenderedFrame& f) { frames.push_back(std::move(f.image)); });
    EXPECT_EQ(frames[1].has_channel("raw_indirect.G"), expect_raw);
    double d = 0.0, s = 0.0;
    for (size_t i = 0; i < frames[1].pixel_count(); ++i) {
      d += std::abs(frames[1].channel("indirect.G")[i] - frames[0].channel("indirect.G")[i]);
      s += frames[1].channel("indirect.G")[i];
    }
    return d / s;
  };
  const double raw = frame_difference({"denoise=0"}, false), denoised = frame_difference({}, true);
  EXPECT_LT(denoised, 0.2 * raw) << "relative frame-to-frame change, raw " << raw << ", denoised " << denoised;
}

TEST_F(HybridTest, EveryBuiltinSceneRendersFiniteLayers) {
  for (const char* name : {"cornell", "leak", "movinglight", "sunroom", "atrium"}) {
    SCOPED_TRACE(name);
    RenderOptions o;
    o.technique = "hybrid";
    o.width = o.height = 32;
    o.frames = 1;
    o.warmup = 4;
    const image::Image img = render_last(test::builtin(name), o);
    for (const auto& ch : img.channel_names())
      for (size_t i = 0; i < img.pixel_count(); ++i) ASSERT_TRUE(std::isfinite(img.channel(ch)[i])) << ch << " " << i;
    // The leak scene's view looks into the room that no light reaches: black in truth.
    if (std::string(name) != "leak") {
      EXPECT_GT(test::mean(img, "G"), 0.0);
    }
  }
}

}  // namespace
}  // namespace giq::realtime
