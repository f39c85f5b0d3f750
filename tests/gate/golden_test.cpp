// The golden manifest: round trip, and every way a golden goes stale or missing.

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

#include "giq/base/error.h"
#include "giq/base/frames.h"
#include "giq/gate/config.h"
#include "giq/gate/escape.h"
#include "giq/gate/golden_manifest.h"

namespace {

namespace fs = std::filesystem;
using giq::gate::Freshness;

class GoldenManifest : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("giq_golden_test_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    config_ = giq::gate::parse_config(
        R"({"version": 1, "cases": [{"name": "c", "scene": "scenes/box.gltf", "view": "front", "technique": "t",
           "frames": "0:1", "resolution": [32, 16], "golden": {"spp": 64, "seed": 5}, "bounds": {"relmse": 1}}]})",
        dir_ / "gate.json");
    const auto& c = config_.cases[0];
    key_ = giq::gate::golden_key(c);
    fs::create_directories(config_.golden_dir / key_);
    giq::gate::GoldenEntry e;
    e.scene = "scenes/box.gltf";
    e.scene_hash = "00112233aabbccdd";
    e.settings = giq::gate::golden_settings(c);
    e.spp = 64;
    e.render_seconds = 1.5;
    e.giq_version = "0.1.0";
    for (int f = 0; f <= 1; ++f) {
      const fs::path p = config_.golden_dir / key_ / giq::frame_file(f);
      std::ofstream(p) << "frame " << f;
      e.files[p.filename().string()] = giq::gate::file_hash(p);
    }
    manifest_.entries[key_] = e;
    giq::gate::write_manifest(config_.golden_dir / "manifest.json", manifest_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  Freshness check(const giq::gate::Case& c, const std::string& hash = "00112233aabbccdd") {
    return giq::gate::check_golden(giq::gate::read_manifest(config_.golden_dir / "manifest.json"),
                                   config_.golden_dir, c, hash);
  }

  fs::path dir_;
  giq::gate::Config config_;
  giq::gate::Manifest manifest_;
  std::string key_;
};

TEST_F(GoldenManifest, RoundTripAndFresh) {
  EXPECT_EQ(key_, "box_front_f0-1");
  const auto m = giq::gate::read_manifest(config_.golden_dir / "manifest.json");
  const auto& e = m.entries.at(key_);
  EXPECT_EQ(e.scene_hash, "00112233aabbccdd");
  EXPECT_EQ(*e.spp, 64u);
  EXPECT_EQ(e.settings["resolution"], nlohmann::json::array({32, 16}));
  EXPECT_EQ(e.files.size(), 2u);
  EXPECT_EQ(check(config_.cases[0]).state, Freshness::State::Fresh);
}

TEST_F(GoldenManifest, StaleWhenSceneSettingsOrFilesChange) {
  auto f = check(config_.cases[0], "ffffffffffffffff");
  EXPECT_EQ(f.state, Freshness::State::Stale);
  EXPECT_NE(f.reason.find("scene changed"), std::string::npos);

  auto c = config_.cases[0];
  c.golden.spp = 128;
  f = check(c);
  EXPECT_EQ(f.state, Freshness::State::Stale);
  EXPECT_NE(f.reason.find("\"spp\":64"), std::string::npos);

  c = config_.cases[0];
  c.width = 64;
  EXPECT_EQ(check(c).state, Freshness::State::Stale);

  std::ofstream(config_.golden_dir / key_ / "frame_0001.exr") << "edited";
  f = check(config_.cases[0]);
  EXPECT_EQ(f.state, Freshness::State::Stale);
  EXPECT_NE(f.reason.find("modified"), std::string::npos);

  fs::remove(config_.golden_dir / key_ / "frame_0001.exr");
  EXPECT_EQ(check(config_.cases[0]).state, Freshness::State::Missing);

  c = config_.cases[0];
  c.view = "top";
  f = check(c);
  EXPECT_EQ(f.state, Freshness::State::Missing);
  EXPECT_NE(f.reason.find("giq golden update"), std::string::npos);
}

TEST_F(GoldenManifest, ConflictingCasesAndMalformedFiles) {
  auto config = giq::gate::parse_config(
      R"({"version": 1, "cases": [
          {"name": "a", "scene": "box.gltf", "technique": "t", "bounds": {"relmse": 1}},
          {"name": "b", "scene": "box.gltf", "technique": "u", "golden": {"spp": 8}, "bounds": {"relmse": 1}}]})",
      dir_ / "gate.json");
  EXPECT_THROW(giq::gate::check_golden_conflicts(config), giq::InputError);
  config.cases[1].golden.spp = config.cases[0].golden.spp;
  EXPECT_NO_THROW(giq::gate::check_golden_conflicts(config));

  std::ofstream(dir_ / "bad.json") << "{\"version\": 1}";
  EXPECT_THROW(giq::gate::read_manifest(dir_ / "bad.json"), giq::InputError);
  EXPECT_TRUE(giq::gate::read_manifest(dir_ / "absent.json").entries.empty());
}

// A still golden is one image of the first frame: a flicker case over frames 0:7 shares the
// golden of the single-frame case of frame 0 and needs only frame_0000.exr; float16 storage is
// part of the settings, so switching it makes the golden stale.
TEST(GoldenKey, StillAndHalfGoldens) {
  const auto config = giq::gate::parse_config(
      R"({"version": 1, "defaults": {"golden": {"spp": 64, "half": true}}, "cases": [
          {"name": "one", "scene": "box.gltf", "technique": "t", "bounds": {"relmse": 1}},
          {"name": "seq", "scene": "box.gltf", "technique": "t", "frames": "0:7", "golden": {"still": true},
           "bounds": {"flicker": 1}},
          {"name": "anim", "scene": "box.gltf", "technique": "t", "frames": "0:7", "bounds": {"flicker": 1}}]})",
      "gate.json");
  const auto& c = config.cases;
  EXPECT_TRUE(c[1].golden.still && c[1].golden.half && c[1].golden.spp == 64u);
  EXPECT_EQ(c[1].golden_last_frame(), 0);
  EXPECT_EQ(c[2].golden_last_frame(), 7);
  EXPECT_EQ(giq::gate::golden_key(c[0]), "box_0_f0-0");
  EXPECT_EQ(giq::gate::golden_key(c[1]), "box_0_f0-0");
  EXPECT_EQ(giq::gate::golden_key(c[2]), "box_0_f0-7");
  EXPECT_EQ(giq::gate::golden_settings(c[1]), giq::gate::golden_settings(c[0]));
  EXPECT_EQ(giq::gate::golden_settings(c[1])["half"], true);
  EXPECT_NO_THROW(giq::gate::check_golden_conflicts(config));
  giq::gate::Case f32 = c[0];
  f32.golden.half = false;
  EXPECT_FALSE(giq::gate::golden_settings(f32).contains("half"));
  // Goldens use the independent sampler unless the config asks otherwise; only the other
  // choice enters the settings, so manifests written before the option stay fresh.
  EXPECT_EQ(c[0].golden.sampler, "independent");
  EXPECT_FALSE(giq::gate::golden_settings(c[0]).contains("sampler"));
  giq::gate::Case sobol = c[0];
  sobol.golden.sampler = "sobol";
  EXPECT_EQ(giq::gate::golden_settings(sobol)["sampler"], "sobol");
}

TEST(GateEscape, HtmlAndBase64) {
  EXPECT_EQ(giq::gate::html_escape("<script>alert('x&y')</script>\""),
            "&lt;script&gt;alert(&#39;x&amp;y&#39;)&lt;/script&gt;&quot;");
  EXPECT_EQ(giq::gate::xml_escape(std::string("a\x02z")), "a\xEF\xBF\xBDz");
  // RFC 4648 section 10 test vectors.
  EXPECT_EQ(giq::gate::base64(""), "");
  EXPECT_EQ(giq::gate::base64("f"), "Zg==");
  EXPECT_EQ(giq::gate::base64("fo"), "Zm8=");
  EXPECT_EQ(giq::gate::base64("foo"), "Zm9v");
  EXPECT_EQ(giq::gate::base64("foobar"), "Zm9vYmFy");
}

}  // namespace
