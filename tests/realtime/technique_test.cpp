#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <string>

#include "giq/base/error.h"
#include "giq/realtime/pass_builder.h"
#include "giq/realtime/renderer.h"
#include "giq/realtime/technique.h"
#include "test_scenes.h"

namespace giq::realtime {
namespace {

TEST(Techniques, EveryRegisteredTechniqueDeclaresValidParametersAndAQualityKnob) {
  std::set<std::string> names;
  for (const auto& t : techniques()) {
    EXPECT_TRUE(names.insert(t.name).second) << "registered twice: " << t.name;
    EXPECT_FALSE(t.description.empty()) << t.name;
    std::set<std::string> parameters;
    for (const auto& p : t.parameters) {
      EXPECT_TRUE(parameters.insert(p.name).second) << t.name << " declares " << p.name << " twice";
      EXPECT_LE(p.min_value, p.default_value) << t.name << "." << p.name;
      EXPECT_LE(p.default_value, p.max_value) << t.name << "." << p.name;
      EXPECT_FALSE(p.description.empty()) << t.name << "." << p.name;
    }
    // The quality knob is a declared parameter, swept from cheapest to best within its range:
    // strictly monotonic, increasing or (a temporal upscale factor) decreasing.
    const auto knob = std::find_if(t.parameters.begin(), t.parameters.end(),
                                   [&](const Parameter& p) { return p.name == t.quality.parameter; });
    ASSERT_NE(knob, t.parameters.end()) << t.name << "'s quality knob '" << t.quality.parameter << "'";
    ASSERT_GE(t.quality.values.size(), 2u) << t.name;
    const double direction = t.quality.values[1] > t.quality.values[0] ? 1.0 : -1.0;
    for (size_t i = 0; i < t.quality.values.size(); ++i) {
      EXPECT_GE(t.quality.values[i], knob->min_value) << t.name;
      EXPECT_LE(t.quality.values[i], knob->max_value) << t.name;
      if (i > 0) EXPECT_GT(direction * (t.quality.values[i] - t.quality.values[i - 1]), 0.0) << t.name;
    }
    EXPECT_EQ(&find_technique(t.name), &t);
  }
  EXPECT_THROW(find_technique("rtx"), InputError);
}

TEST(Techniques, TheJsonListingIsTheRegistry) {
  const nlohmann::json j = techniques_json();
  ASSERT_EQ(j["techniques"].size(), techniques().size());
  for (size_t i = 0; i < techniques().size(); ++i) {
    const TechniqueInfo& t = techniques()[i];
    const nlohmann::json& e = j["techniques"][i];
    EXPECT_EQ(e["name"], t.name);
    ASSERT_EQ(e["parameters"].size(), t.parameters.size());
    for (size_t k = 0; k < t.parameters.size(); ++k) {
      EXPECT_EQ(e["parameters"][k]["name"], t.parameters[k].name);
      EXPECT_EQ(e["parameters"][k]["default"].get<double>(), t.parameters[k].default_value);
      EXPECT_EQ(e["parameters"][k]["min"].get<double>(), t.parameters[k].min_value);
      EXPECT_EQ(e["parameters"][k]["max"].get<double>(), t.parameters[k].max_value);
      EXPECT_EQ(e["parameters"][k]["integer"].get<bool>(), t.parameters[k].integer);
    }
    EXPECT_EQ(e["quality"]["parameter"], t.quality.parameter);
    EXPECT_EQ(e["quality"]["values"].get<std::vector<double>>(), t.quality.values);
  }
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
  // A repeated parameter is refused, not resolved by keeping the last value.
  try {
    ParameterValues(declared, {"size=16", "alpha=0.25", "size=32"});
    FAIL() << "accepted a repeated parameter";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "--param size");
    EXPECT_NE(std::string(e.what()).find("more than once"), std::string::npos) << e.what();
  }
}

class RendererTest : public test::VulkanTest {};

// timings.json names the builder each two-way pass used: what was asked, or the device's choice.
TEST_F(RendererTest, TimingsSayWhichBuilderRan) {
  const scenes::Scene s = test::cornell_box();
  RenderOptions o;
  o.technique = "rsm";
  o.width = o.height = 16;
  for (const auto& [asked, expected] : std::vector<std::pair<std::vector<std::string>, nlohmann::json>>{
           {{}, {{"gbuffer_ray_traced", "raster"}, {"rsm_ray_traced", "raster"}, {"shadow_maps_ray_traced", "raster"}}},
           {{"gbuffer_ray_traced=1", "rsm_ray_traced=1", "shadow_maps_ray_traced=1"},
            {{"gbuffer_ray_traced", "rays"}, {"rsm_ray_traced", "rays"}, {"shadow_maps_ray_traced", "rays"}}},
           {{"rsm_ray_traced=1"}, {{"gbuffer_ray_traced", "raster"}, {"rsm_ray_traced", "rays"}, {"shadow_maps_ray_traced", "raster"}}}}) {
    o.parameters = asked;
    o.parameters.insert(o.parameters.end(), {"shadow_map_size=64", "rsm_cube_size=16", "samples=4"});
    const auto j = render_sequence(*ctx, *compiler, s, o, [](RenderedFrame&) {});
    EXPECT_EQ(j["builders"], expected) << j["builders"].dump();
  }
  o.technique = "pt";
  o.parameters = {};
  EXPECT_EQ(render_sequence(*ctx, *compiler, s, o, [](RenderedFrame&) {})["builders"], nlohmann::json::object());
  EXPECT_THROW(pass_builder_parameter("shadow_ray_traced", "shadow maps'"), std::logic_error);
}

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
  // lavapipe is a CPU device: the device's choice (-1, the default) is the rasteriser.
  EXPECT_EQ(j["builders"], nlohmann::json({{"gbuffer_ray_traced", "raster"}, {"shadow_maps_ray_traced", "raster"}}));
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

// `frames` of technique t at 16 x 16 with cheap settings: the quality knob's cheapest value,
// small shadow and reflective shadow maps.
RenderOptions cheap(const TechniqueInfo& t, int frames) {
  RenderOptions o;
  o.technique = t.name;
  o.width = o.height = 16;
  o.frames = frames;
  o.parameters = {t.quality.parameter + "=" + nlohmann::json(t.quality.values.front()).dump()};
  for (const auto& p : t.parameters)
    if (p.name != t.quality.parameter && (p.name == "shadow_map_size" || p.name == "rsm_size" || p.name == "rsm_cube_size"))
      o.parameters.push_back(p.name + "=64");
  return o;
}

TEST_F(RendererTest, EveryRegisteredTechniqueRendersFiniteLayersAndTimesItsPasses) {
  // Whatever a technique is, the renderer gets beauty, direct and indirect from it, finite,
  // with beauty = direct + indirect where it composites, and timings for what it recorded.
  const scenes::Scene s = test::cornell_box();
  for (const auto& t : techniques()) {
    SCOPED_TRACE(t.name);
    RenderOptions o = cheap(t, 2);
    image::Image last;
    const auto j = render_sequence(*ctx, *compiler, s, o, [&](RenderedFrame& f) { last = std::move(f.image); });
    for (const char* c : {"R", "G", "B", "direct.R", "direct.G", "direct.B", "indirect.R", "indirect.G", "indirect.B"}) {
      ASSERT_TRUE(last.has_channel(c)) << c;
      for (size_t i = 0; i < last.pixel_count(); ++i) ASSERT_TRUE(std::isfinite(last.channel(c)[i])) << c << " " << i;
    }
    double beauty = 0.0;
    for (size_t i = 0; i < last.pixel_count(); ++i) beauty += last.channel("G")[i];
    EXPECT_GT(beauty, 0.0) << "a lit Cornell box renders black";
    ASSERT_FALSE(j["passes"].empty());
    for (const auto& p : j["passes"]) EXPECT_FALSE(p["name"].get<std::string>().empty());
  }
}

TEST_F(RendererTest, EveryRegisteredTechniqueRendersParticlesFinitely) {
  // The generated fountain (tests/data/scenes/generate.py) through frames 0..5, from no
  // particle to a few dozen: the stages' meshes fill, the lights grow from nothing, the
  // geometry changes size every frame; every technique's layers stay finite and the particles
  // light something.
  const scenes::Scene s = scenes::load(std::filesystem::path(GIQ_TEST_DATA) / "scenes" / "fountain.gltf");
  for (const auto& t : techniques()) {
    SCOPED_TRACE(t.name);
    RenderOptions o = cheap(t, 6);
    image::Image last;
    render_sequence(*ctx, *compiler, s, o, [&](RenderedFrame& f) { last = std::move(f.image); });
    double beauty = 0.0;
    for (const char* c : {"R", "G", "B", "direct.R", "direct.G", "direct.B", "indirect.R", "indirect.G", "indirect.B"})
      for (size_t i = 0; i < last.pixel_count(); ++i) {
        ASSERT_TRUE(std::isfinite(last.channel(c)[i])) << c << " " << i;
        if (c[0] == 'R') beauty += last.channel(c)[i];
      }
    EXPECT_GT(beauty, 0.0) << "glowing particles render black";
  }
}

}  // namespace
}  // namespace giq::realtime
