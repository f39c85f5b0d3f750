// Gate config parsing: defaults, path resolution, bound forms, and bad input naming the field.

#include "giq/gate/config.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "giq/base/error.h"

namespace {

using giq::gate::Better;
using giq::gate::parse_config;

const char* kGood = R"({
  "version": 1,
  "golden_dir": "refs",
  "defaults": {"resolution": [64, 32], "golden": {"spp": 512, "seed": 3},
               "bounds": {"flip_mean": {"fail": 0.1, "warn": 0.05}}},
  "cases": [
    {"name": "cornell-direct", "scene": "../scenes/cornell.gltf", "view": "front", "technique": "direct",
     "parameters": {"pcf_radius": 2, "normal_offset": 1.5},
     "bounds": {"relmse": 0.2, "ssim": {"fail": 0.9, "warn": 0.95},
                "gpu_ms": {"fail": 4, "device": "H100"}}},
    {"name": "moving-pt", "scene": "/abs/movinglight.gltf", "technique": "pt", "frames": "2:9", "layer": "indirect",
     "golden": {"rel_error": 0.02}, "bounds": {"flip_mean": 0.2, "flicker": {"warn": 0.01}}}
  ]})";

TEST(GateConfig, ParsesCasesWithDefaults) {
  const auto c = parse_config(kGood, "/repo/golden/gate.json");
  EXPECT_EQ(c.golden_dir, "/repo/golden/refs");
  ASSERT_EQ(c.cases.size(), 2u);
  const auto& a = c.cases[0];
  EXPECT_EQ(a.scene, "/repo/scenes/cornell.gltf");
  EXPECT_EQ(a.view, "front");
  EXPECT_EQ(a.width, 64);
  EXPECT_EQ(a.height, 32);
  ASSERT_EQ(a.parameters.size(), 2u);
  EXPECT_EQ(a.parameters[0].first, "normal_offset");  // sorted by name
  EXPECT_EQ(giq::gate::parameter_arguments(a)[1], "pcf_radius=2");
  EXPECT_EQ(*a.golden.spp, 512u);
  EXPECT_EQ(a.golden.seed, 3u);
  ASSERT_EQ(a.bounds.size(), 4u);  // flip_mean from the defaults, then the case's own
  EXPECT_EQ(a.bounds[0].metric, "flip_mean");
  EXPECT_DOUBLE_EQ(*a.bounds[0].warn, 0.05);
  EXPECT_DOUBLE_EQ(*a.bounds[1].fail, 0.2);
  EXPECT_FALSE(a.bounds[1].warn);
  EXPECT_EQ(a.bounds[2].better, Better::Higher);  // ssim grows with quality
  EXPECT_EQ(a.bounds[3].device, "H100");
  EXPECT_TRUE(a.needs_timing());
  EXPECT_FALSE(a.sequence());

  const auto& b = c.cases[1];
  EXPECT_EQ(b.scene, "/abs/movinglight.gltf");
  EXPECT_EQ(b.view, "0");
  EXPECT_EQ(b.first_frame, 2);
  EXPECT_EQ(b.last_frame, 9);
  EXPECT_TRUE(b.sequence());
  EXPECT_EQ(b.layer, "indirect");
  EXPECT_FALSE(b.golden.spp);  // rel_error replaces the default spp
  EXPECT_DOUBLE_EQ(*b.golden.rel_error, 0.02);
  ASSERT_EQ(b.bounds.size(), 2u);
  EXPECT_DOUBLE_EQ(*b.bounds[0].fail, 0.2);  // the case's flip_mean replaces the default's
  EXPECT_FALSE(b.bounds[0].warn);
  EXPECT_FALSE(b.needs_timing());
}

struct Bad {
  std::string json;
  std::string field;
  std::string words;
};

class GateConfigBad : public testing::TestWithParam<Bad> {};

TEST_P(GateConfigBad, NamesTheField) {
  const Bad& b = GetParam();
  try {
    parse_config(b.json, "g.json");
    FAIL() << "accepted " << b.json;
  } catch (const giq::InputError& e) {
    EXPECT_EQ(e.file(), "g.json");
    EXPECT_EQ(e.field(), b.field) << e.what();
    EXPECT_NE(std::string(e.what()).find(b.words), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line: " << e.what();
  }
}

#define CASE_PREFIX \
  R"({"version": 1, "cases": [{"name": "a", "scene": "s.gltf", "technique": "t", )"

INSTANTIATE_TEST_SUITE_P(
    Inputs, GateConfigBad,
    testing::Values(
        Bad{"{", "JSON", "not valid JSON"},
        // The last of two equal keys would win silently: 10 instead of 0.01.
        Bad{CASE_PREFIX R"("bounds": {"relmse": 0.01, "relmse": 10}}]})", "cases[].bounds.relmse",
            "appears twice"},
        Bad{R"({"version": 2, "cases": []})", "version", "expected 1"},
        Bad{R"({"version": 1})", "cases", "missing or empty"},
        Bad{R"({"version": 1, "cases": [], "extra": 1})", "extra", "unknown key"},
        Bad{CASE_PREFIX R"("bounds": {"flip_mean": {"fail": 0.1, "warn": 0.2}}}]})",
            "cases[0].bounds.flip_mean.warn", "stricter"},
        Bad{CASE_PREFIX R"("bounds": {"ssim": {"fail": 0.9, "warn": 0.8}}}]})",
            "cases[0].bounds.ssim.warn", "stricter"},
        Bad{CASE_PREFIX R"("bounds": {"gpu_ms": 3}}]})", "cases[0].bounds.gpu_ms.device", "device"},
        Bad{CASE_PREFIX R"("bounds": {"relmse": "small"}}]})", "cases[0].bounds.relmse",
            "not an object"},
        Bad{CASE_PREFIX R"("bounds": {"relmse": {}}}]})", "cases[0].bounds.relmse", "fail level"},
        Bad{CASE_PREFIX R"("bounds": {"relmse": {"fail": 1, "better": "up"}}}]})",
            "cases[0].bounds.relmse.better", "\"lower\" or \"higher\""},
        Bad{CASE_PREFIX R"("bounds": {}}]})", "cases[0].bounds", "at least one metric"},
        Bad{CASE_PREFIX R"("frames": "5:2", "bounds": {"relmse": 1}}]})", "cases[0].frames",
            "A <= B"},
        Bad{CASE_PREFIX R"("resolution": [0, 4], "bounds": {"relmse": 1}}]})",
            "cases[0].resolution[0]", "integer in [1, 16384]"},
        Bad{CASE_PREFIX R"("golden": {"spp": 4, "rel_error": 0.1}, "bounds": {"relmse": 1}}]})",
            "cases[0].golden", "not both"},
        Bad{CASE_PREFIX R"("golden": {"rel_error": 2}, "bounds": {"relmse": 1}}]})",
            "cases[0].golden.rel_error", "fraction"},
        Bad{CASE_PREFIX R"("golden": {"still": 1}, "bounds": {"relmse": 1}}]})",
            "cases[0].golden.still", "true or false"},
        Bad{CASE_PREFIX R"("golden": {"half": "yes"}, "bounds": {"relmse": 1}}]})",
            "cases[0].golden.half", "true or false"},
        Bad{CASE_PREFIX R"("golden": {"sampler": "halton"}, "bounds": {"relmse": 1}}]})",
            "cases[0].golden.sampler", "\"independent\" or \"sobol\""},
        Bad{CASE_PREFIX R"("colour": 1, "bounds": {"relmse": 1}}]})", "cases[0].colour",
            "unknown key"},
        Bad{CASE_PREFIX R"("bounds": {"relmse": 1}}, {"name": "a", "scene": "s", "technique": "t",
                        "bounds": {"relmse": 1}}]})",
            "cases[1].name", "unique"},
        Bad{R"({"version": 1, "cases": [{"name": "a/b", "scene": "s", "technique": "t", "bounds": {"relmse": 1}}]})",
            "cases[0].name", "folders"},
        // Once an internal error: a folder name longer than the file system allows.
        Bad{R"({"version": 1, "cases": [{"name": ")" + std::string(300, 'a') +
                R"(", "scene": "s", "technique": "t", "bounds": {"relmse": 1}}]})",
            "cases[0].name", "expected at most 128"},
        // Once an internal error: nlohmann's number overflow.
        Bad{CASE_PREFIX R"("bounds": {"relmse": 1e999}}]})", "JSON", "number overflow"},
        Bad{R"({"version": 1, "cases": [{"name": "a", "technique": "t", "bounds": {"relmse": 1}}]})",
            "cases[0].scene", "missing"},
        // A typo in a metric's name, once a FAIL of every run ("metrics.json has no metric").
        Bad{CASE_PREFIX R"("bounds": {"flip_maen": 0.1}}]})", "cases[0].bounds.flip_maen", "not a metric"},
        // Test images from outside giq instead of a technique: one or the other, no parameters,
        // no frame time, a pattern exactly when there is a frame range.
        Bad{CASE_PREFIX R"("test": "shot.png", "bounds": {"relmse": 1}}]})", "cases[0].test", "not both"},
        Bad{R"({"version": 1, "cases": [{"name": "a", "scene": "s", "bounds": {"relmse": 1}}]})", "cases[0].technique",
            "or test"},
        Bad{R"({"version": 1, "cases": [{"name": "a", "scene": "s", "test": "x.png", "parameters": {"k": 1},
            "bounds": {"relmse": 1}}]})", "cases[0].parameters", "need a technique"},
        Bad{R"({"version": 1, "cases": [{"name": "a", "scene": "s", "test": "x.png",
            "bounds": {"gpu_ms": {"fail": 1, "device": "H200"}}}]})", "cases[0].bounds.gpu_ms", "needs a technique"},
        Bad{R"({"version": 1, "cases": [{"name": "a", "scene": "s", "test": "x.png", "frames": "0:3",
            "bounds": {"relmse": 1}}]})", "cases[0].test", "frame pattern"},
        Bad{R"({"version": 1, "cases": [{"name": "a", "scene": "s", "test": "x_%04d.png",
            "bounds": {"relmse": 1}}]})", "cases[0].test", "frame range"}));

TEST(GateConfig, DeeplyNestedInputIsAnErrorNotACrash) {
  // 100 000 nested arrays where the cases go: once a crash (the stack of a recursive walk).
  const std::string text = R"({"version": 1, "cases": )" + std::string(100000, '[') + std::string(100000, ']') + "}";
  try {
    parse_config(text, "g.json");
    FAIL() << "accepted";
  } catch (const giq::InputError& e) {
    EXPECT_EQ(e.field(), "JSON");
    EXPECT_NE(std::string(e.what()).find("nest deeper than 256 levels at cases[]"), std::string::npos) << e.what();
  }
}

TEST(GateConfig, Glob) {
  using giq::gate::glob_match;
  EXPECT_TRUE(glob_match("cornell-*", "cornell-direct"));
  EXPECT_TRUE(glob_match("*pt*", "moving-pt-seq"));
  EXPECT_TRUE(glob_match("a?c", "abc"));
  EXPECT_FALSE(glob_match("a?c", "abbc"));
  EXPECT_FALSE(glob_match("cornell-*", "leak-direct"));
  EXPECT_TRUE(glob_match("*", ""));
  const auto c = parse_config(kGood, "/g/gate.json");
  EXPECT_EQ(giq::gate::select_cases(c, "moving-*").size(), 1u);
  EXPECT_EQ(giq::gate::select_cases(c, "").size(), 2u);
  EXPECT_TRUE(giq::gate::select_cases(c, "nothing").empty());
}

}  // namespace

namespace {

// The documented example (docs/gate.md) stays valid.
TEST(GateConfig, DocumentedExampleParses) {
  const auto c = giq::gate::read_config(std::string(GIQ_TEST_DATA) + "/gate/example.json");
  ASSERT_EQ(c.cases.size(), 2u);
  EXPECT_TRUE(std::filesystem::exists(c.cases[0].scene)) << c.cases[0].scene;
  EXPECT_TRUE(std::filesystem::exists(c.cases[1].scene)) << c.cases[1].scene;
  EXPECT_EQ(c.cases[1].last_frame, 29);
  EXPECT_EQ(c.cases[0].bounds.size(), 4u);
}

}  // namespace
