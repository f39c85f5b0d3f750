#include <gtest/gtest.h>

#include "giq/base/error.h"
#include "giq/realtime/renderer.h"
#include "giq/realtime/technique.h"
#include "test_scenes.h"

namespace giq::realtime {
namespace {

TEST(Techniques, RegistryListsDirectAndPtWithTheirParameters) {
  std::vector<std::string> names;
  for (const auto& t : techniques()) {
    names.push_back(t.name);
    for (const auto& p : t.parameters) {
      EXPECT_LE(p.min_value, p.default_value) << t.name << "." << p.name;
      EXPECT_LE(p.default_value, p.max_value) << t.name << "." << p.name;
      EXPECT_FALSE(p.description.empty());
    }
  }
  EXPECT_EQ(names, (std::vector<std::string>{"direct", "pt", "rsm", "lpv", "vct"}));
  EXPECT_THROW(find_technique("rtx"), InputError);
}

TEST(Techniques, ParametersAreValidated) {
  const std::vector<Parameter> declared = {{"size", 8, 1, 64, true, "a size"}, {"alpha", 0.5, 0, 1, false, "a fraction"}};
  const ParameterValues defaults(declared, {});
  EXPECT_EQ(defaults.get("size"), 8);
  const ParameterValues set(declared, {"size=16", "alpha=0.25"});
  EXPECT_EQ(set.get_int("size"), 16);
  EXPECT_EQ(set.get("alpha"), 0.25);
  for (const char* bad : {"size", "=3", "colour=1", "size=abc", "size=1.5", "size=65", "alpha=-0.1", "alpha=nan", "size=8x"})
    EXPECT_THROW(ParameterValues(declared, {bad}), InputError) << bad;
}

class RendererTest : public test::VulkanTest {};

TEST_F(RendererTest, TimingsHaveEveryPassAndExcludeWarmup) {
  const scenes::Scene s = test::cornell_box();
  RenderOptions o;
  o.technique = "direct";
  o.parameters = {"shadow_map_size=128"};
  o.width = o.height = 16;
  o.frames = 3;
  o.warmup = 2;
  std::vector<int> frames;
  const auto j = render_sequence(*ctx, *compiler, s, o, [&](RenderedFrame& f) {
    frames.push_back(f.frame);
    EXPECT_EQ(f.image.metadata.at("giq.technique"), "direct");
    EXPECT_EQ(f.image.metadata.at("giq.device"), ctx->info().name);
    EXPECT_TRUE(f.image.has_channel("direct.R") && f.image.has_channel("indirect.B") && f.image.has_channel("G"));
  });
  EXPECT_EQ(frames, (std::vector<int>{2, 3, 4}));
  EXPECT_EQ(j["frames"]["warmup"], 2);
  EXPECT_EQ(j["frames"]["measured"], 3);
  EXPECT_EQ(j["device"]["name"], ctx->info().name);
  EXPECT_EQ(j["resolution"], nlohmann::json::array({16, 16}));
  std::vector<std::string> passes;
  for (const auto& p : j["passes"]) {
    passes.push_back(p["name"]);
    EXPECT_GE(p["gpu_ms"]["median"].get<double>(), 0.0);
  }
  EXPECT_EQ(passes, (std::vector<std::string>{"shadow_maps", "gbuffer", "direct_lighting"}));
  EXPECT_GT(j["frame_gpu_ms"]["median"].get<double>(), 0.0);
  // The frame spans its passes.
  double sum = 0.0;
  for (const auto& p : j["passes"]) sum += p["gpu_ms"]["median"].get<double>();
  EXPECT_GE(j["frame_gpu_ms"]["max"].get<double>() * 1.0001, j["passes"][2]["gpu_ms"]["min"].get<double>());
  EXPECT_GT(sum, 0.0);
}

TEST_F(RendererTest, GpuTimeCoversComputeOnlyFrames) {
  // On a CPU device the GPU work happens inside the frame's CPU time: a compute-only frame
  // that takes a while must not be timed as nearly free (lavapipe writes an opening
  // timestamp late unless it is fenced by barriers; GpuTimer does that).
  const scenes::Scene s = test::cornell_box();
  RenderOptions o;
  o.technique = "pt";
  o.parameters = {"samples_per_frame=8"};
  o.width = o.height = 32;
  o.frames = 2;
  o.read_back = false;
  const auto j = render_sequence(*ctx, *compiler, s, o, [](RenderedFrame&) {});
  if (ctx->info().type != "cpu") GTEST_SKIP() << "only meaningful where GPU work runs on the CPU";
  EXPECT_GT(j["frame_gpu_ms"]["median"].get<double>(), 0.3 * j["frame_cpu_ms"]["median"].get<double>());
}

TEST_F(RendererTest, PtDoesNotDependOnHowSamplesAreSplitIntoFrames) {
  // Samples 0..255 per pixel in one frame or in four frames of 64: the same samples, so the
  // same bits. (lavapipe ends shader loops after 65535 iterations per invocation; a pt that
  // traced many paths in one invocation lost the rest silently and came out darker.)
  const scenes::Scene s = test::cornell_box();
  auto render = [&](int frames, int spp) {
    RenderOptions o;
    o.technique = "pt";
    o.width = o.height = 8;
    o.frames = frames;
    o.parameters = {"samples_per_frame=" + std::to_string(spp)};
    image::Image last;
    render_sequence(*ctx, *compiler, s, o, [&](RenderedFrame& f) { last = std::move(f.image); });
    return last;
  };
  const image::Image a = render(1, 256), b = render(4, 64);
  for (size_t i = 0; i < a.pixel_count(); ++i) ASSERT_EQ(a.channel("G")[i], b.channel("G")[i]) << i;
}

TEST_F(RendererTest, BadViewResolutionAndFramesAreInputErrors) {
  const scenes::Scene s = test::cornell_box();
  RenderOptions o;
  o.width = o.height = 8;
  auto run = [&] { render_sequence(*ctx, *compiler, s, o, [](RenderedFrame&) {}); };
  o.view = "nope";
  EXPECT_THROW(run(), InputError);
  o.view = "0";
  o.width = 0;
  EXPECT_THROW(run(), InputError);
  o.width = 8;
  o.frames = 0;
  EXPECT_THROW(run(), InputError);
}

TEST_F(RendererTest, PtAccumulatesAcrossFramesDeterministically) {
  // Two runs with the same seed give identical images; frame k holds k+1 samples' mean.
  const scenes::Scene s = test::cornell_box();
  RenderOptions o;
  o.technique = "pt";
  o.width = o.height = 8;
  o.frames = 3;
  std::vector<image::Image> a, b;
  render_sequence(*ctx, *compiler, s, o, [&](RenderedFrame& f) { a.push_back(std::move(f.image)); });
  render_sequence(*ctx, *compiler, s, o, [&](RenderedFrame& f) { b.push_back(std::move(f.image)); });
  ASSERT_EQ(a.size(), 3u);
  for (size_t k = 0; k < 3; ++k)
    for (size_t i = 0; i < a[k].pixel_count(); ++i) ASSERT_EQ(a[k].channel("R")[i], b[k].channel("R")[i]);
  EXPECT_EQ(a[2].metadata.at("giq.technique_frame"), "3");
}

}  // namespace
}  // namespace giq::realtime
