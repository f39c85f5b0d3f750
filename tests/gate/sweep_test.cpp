// giq sweep: the technique listing reader and the settings plan, then sweeps end to end with
// fake_giq, whose costs and errors follow known curves, so the Pareto front and the
// convergence slopes are known exactly.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "support/subprocess.h"
#include "giq/base/error.h"
#include "sweep_plan.h"

namespace {

namespace fs = std::filesystem;
using giq::cli::Setting;
using nlohmann::json;

const char* kListing = R"({"version": 1, "techniques": [
  {"name": "direct", "description": "Shadow maps and one lighting pass", "parameters": [
    {"name": "shadow_map_size", "default": 2048, "min": 256, "max": 4096, "integer": true, "description": "texels"},
    {"name": "normal_offset", "default": 1.5, "min": 0, "max": 8, "integer": false, "description": "texels"}],
   "quality": {"parameter": "shadow_map_size", "values": [256, 1024]}},
  {"name": "pt", "description": "Progressive path tracer", "parameters": [
    {"name": "samples_per_frame", "default": 1, "min": 1, "max": 64, "integer": true, "description": "samples"}],
   "quality": {"parameter": "samples_per_frame", "values": [1, 2, 4]}}]})";

TEST(SweepPlan, ReadsTheJsonListing) {
  const auto t = giq::cli::parse_technique_list(kListing);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[0].name, "direct");
  ASSERT_EQ(t[0].parameters.size(), 2u);
  EXPECT_EQ(t[0].parameters[0].name, "shadow_map_size");
  EXPECT_DOUBLE_EQ(t[0].parameters[0].default_value, 2048);
  EXPECT_DOUBLE_EQ(t[0].parameters[0].min_value, 256);
  EXPECT_TRUE(t[0].parameters[0].integer);
  EXPECT_FALSE(t[0].parameters[1].integer);
  EXPECT_DOUBLE_EQ(t[0].parameters[1].default_value, 1.5);
  EXPECT_EQ(t[1].parameters[0].name, "samples_per_frame");
  EXPECT_EQ(giq::cli::quality_axis(t[1]), "pt.samples_per_frame=1,2,4");
  EXPECT_THROW(giq::cli::parse_technique_list("direct\n    --param x=1   [0, 2]\n"), giq::InputError);
  EXPECT_THROW(giq::cli::parse_technique_list(R"({"techniques": [{"name": "x"}]})"), giq::InputError);
}

TEST(SweepPlan, GridAutoAndDefaults) {
  const auto t = giq::cli::parse_technique_list(kListing);
  // Two axes: 2 x 3 settings plus the defaults (shadow_map_size 2048, normal_offset 1.5).
  auto s = giq::cli::plan_settings(
      t[0], {"shadow_map_size=512,1024", "direct.normal_offset=0,1,2", "samples_per_frame=4"}, 0,
      64);
  ASSERT_EQ(s.size(), 7u);
  EXPECT_EQ(s[0], (Setting{{"normal_offset", 0}, {"shadow_map_size", 512}}));
  EXPECT_EQ(s.back(), (Setting{{"normal_offset", 1.5}, {"shadow_map_size", 2048}}));
  EXPECT_TRUE(giq::cli::is_default(t[0], s.back()));
  EXPECT_FALSE(giq::cli::is_default(t[0], s[0]));
  // --auto 3: shadow_map_size spans a factor 16 -> geometric 256, 1024, 4096; normal_offset
  // linear 0, 4, 8; the defaults are not on the grid, so 9 + 1.
  s = giq::cli::plan_settings(t[0], {}, 3, 64);
  ASSERT_EQ(s.size(), 10u);
  EXPECT_EQ(s[1], (Setting{{"normal_offset", 0}, {"shadow_map_size", 1024}}));
  EXPECT_EQ(s[5], (Setting{{"normal_offset", 4}, {"shadow_map_size", 4096}}));
  // The default already on the grid is not added twice.
  EXPECT_EQ(giq::cli::plan_settings(t[1], {"samples_per_frame=1,8"}, 0, 64).size(), 2u);
  EXPECT_THROW(giq::cli::plan_settings(t[1], {"pt.samples_per_frame=0"}, 0, 64), giq::InputError);
  EXPECT_THROW(giq::cli::plan_settings(t[1], {"pt.nope=1"}, 0, 64), giq::InputError);
  EXPECT_THROW(giq::cli::plan_settings(t[1], {"samples_per_frame"}, 0, 64), giq::InputError);
  EXPECT_THROW(giq::cli::plan_settings(t[0], {}, 9, 20), giq::InputError);
}

TEST(SweepPlan, EveryGridAxisMustReachASweptTechnique) {
  const auto t = giq::cli::parse_technique_list(kListing);
  const std::vector<const giq::cli::TechniqueParameters*> direct = {&t[0]}, both = {&t[0], &t[1]};
  // Bare axes reach the techniques that declare them; qualified ones their technique.
  EXPECT_NO_THROW(giq::cli::check_grid(both, {"shadow_map_size=512", "samples_per_frame=4", "pt.samples_per_frame=2"}));
  auto field_and_words = [&](const std::vector<const giq::cli::TechniqueParameters*>& swept, const std::string& axis,
                             const std::string& words) {
    try {
      giq::cli::check_grid(swept, {axis});
      ADD_FAILURE() << "accepted " << axis;
    } catch (const giq::InputError& e) {
      EXPECT_EQ(e.field(), "--grid");
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  field_and_words(direct, "bogus=1,2", "declares the parameter 'bogus'");
  field_and_words(direct, "samples_per_frame=4", "declares the parameter 'samples_per_frame'");
  field_and_words(direct, "pt.samples_per_frame=4", "technique pt, which is not swept");
  field_and_words(both, "direct.samples_per_frame=4", "declares the parameter 'samples_per_frame'");
}

class SweepCli : public testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() / ("giq_sweep_cli_" + std::to_string(::getpid()) + "_" +
                                     testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    ::unsetenv("FAKE_GIQ_BEHAVIOUR");
    ::unsetenv("FAKE_GIQ_GPU_MS");
    ::setenv("FAKE_GIQ_LOG", (dir_ / "calls.log").c_str(), 1);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  int giq(const std::string& args) {
    const std::string cmd =
        "cd " + dir_.string() + " && " + GIQ_BINARY + " sweep --giq " + FAKE_GIQ + " --scene " +
        GIQ_SCENES_DIR + "/cornell.gltf --width 8 --height 8 --out out " + args + " >log.txt 2>&1";
    return giq::test::exit_code(std::system(cmd.c_str()));
  }
  json read(const std::string& name) {
    std::ifstream in(dir_ / "out" / name);
    return json::parse(in);
  }
  fs::path dir_;
};

TEST_F(SweepCli, ParetoFrontAcrossTechniques) {
  ASSERT_EQ(giq("--technique direct --technique pt --grid pcf_radius=0,2,4 --grid "
                "pt.samples_per_frame=1,4,16 "
                "--warmup 1 --frames 3 --ref-spp 8 --jobs 2"),
            0)
      << std::ifstream(dir_ / "log.txt").rdbuf();
  // fake_giq: direct costs 1 + v ms, pt 2 (1 + v); flip_mean = 1 / (1 + v) for both.
  const json s = read("sweep.json");
  ASSERT_EQ(s["rows"].size(),
            7u);  // direct: 3 + its default (1); pt: 3, its default (1) among them
  std::map<std::string, bool> front;
  for (const json& r : s["rows"]) {
    const double v = r["parameters"].begin().value().get<double>();
    const bool pt = r["technique"] == "pt";
    EXPECT_NEAR(r["gpu_ms"].get<double>(), (pt ? 2 : 1) * (1 + v), 1e-9);
    EXPECT_NEAR(r["metrics"]["flip_mean"].get<double>(), 1 / (1 + v), 1e-9);
    front[r["technique"].get<std::string>() + std::to_string(int(v))] = r["pareto_front"];
    EXPECT_EQ(r["default"].get<bool>(), v == 1.0);
  }
  // Every direct setting is on the front (cost and error trade monotonically). pt at 1 and 4
  // costs twice the direct setting of the same error: dominated; pt at 16 is the most
  // accurate of all.
  EXPECT_TRUE(front["direct0"] && front["direct1"] && front["direct2"] && front["direct4"]);
  EXPECT_FALSE(front["pt1"]);
  EXPECT_FALSE(front["pt4"]);
  EXPECT_TRUE(front["pt16"]);
  std::ifstream csv(dir_ / "out" / "sweep.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("technique,parameters,default,gpu_ms,flip_mean", 0), 0u);
  std::stringstream svg;
  svg << std::ifstream(dir_ / "out" / "sweep.svg").rdbuf();
  EXPECT_NE(svg.str().find("class=\"front\""), std::string::npos);
  EXPECT_NE(svg.str().find("class=\"default\""), std::string::npos);
}

// GPU time at the resolution that matters (1080p on the GPU of interest) while the error is
// scored at the reference's: a second run per setting, without images, at the timing size.
TEST_F(SweepCli, TimesAtAnotherResolution) {
  ASSERT_EQ(giq("--technique direct --grid pcf_radius=0,2 --warmup 1 --frames 3 --ref-spp 8 "
                "--timing-width 24 --timing-height 16"),
            0)
      << std::ifstream(dir_ / "log.txt").rdbuf();
  const json s = read("sweep.json");
  EXPECT_EQ(s["run"]["timing_resolution"], json::array({24, 16}));
  EXPECT_EQ(s["run"]["resolution"], json::array({8, 8}));
  std::ifstream calls(dir_ / "calls.log");
  int scored = 0, timed = 0;
  for (std::string line; std::getline(calls, line);) {
    if (line.find("realtime") == std::string::npos || line.find("--list") != std::string::npos) continue;
    if (line.find("--no-images") != std::string::npos) {
      ++timed;
      EXPECT_NE(line.find("--width 24 --height 16"), std::string::npos) << line;
    } else {
      ++scored;
      EXPECT_NE(line.find("--width 8 --height 8"), std::string::npos) << line;
    }
  }
  EXPECT_EQ(scored, 3);  // 0, 2 and the default 1
  EXPECT_EQ(timed, 3);
  EXPECT_EQ(giq("--technique direct --timing-width 24"), 2);  // a width needs a height
}

TEST_F(SweepCli, ReferenceConvergenceSlope) {
  ASSERT_EQ(giq("--convergence --spp 1,4,16,64 --ref-spp 4096"), 0)
      << std::ifstream(dir_ / "log.txt").rdbuf();
  // fake rmse = 0.5 spp^-1/2 and 0.01 s per spp: both slopes are -1/2 up to rounding of the
  // printed values (%.10g-level), far below 1e-6.
  const json c = read("convergence.json");
  EXPECT_NEAR(c["fit_spp"]["slope"].get<double>(), -0.5, 1e-6);
  EXPECT_NEAR(c["fit_seconds"]["slope"].get<double>(), -0.5, 1e-6);
  EXPECT_NEAR(c["fit_spp"]["intercept_log10"].get<double>(), std::log10(0.5), 1e-6);
  EXPECT_EQ(c["rows"].size(), 4u);
  EXPECT_EQ(c["sampler"], "sobol");
  EXPECT_TRUE(fs::exists(dir_ / "out" / "convergence_spp.svg"));
  EXPECT_TRUE(fs::exists(dir_ / "out" / "convergence_seconds.svg"));
  EXPECT_NE(giq("--convergence --spp 4"), 0);
}

}  // namespace
