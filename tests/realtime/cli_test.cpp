// `giq realtime` end to end: frames and timings.json are written, the validation layer stays
// silent, and bad input exits 2 with one line naming the field.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "support/subprocess.h"
#include "giq/image/io.h"

namespace {

namespace fs = std::filesystem;

using giq::test::Outcome;
using giq::test::slurp;

fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / ("giq_realtime_cli_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

Outcome giq(const std::string& args) {
  return giq::test::run_captured(std::string("GIQ_SHADER_CACHE=") + GIQ_TEST_SHADER_CACHE + " '" + GIQ_BINARY +
                                     "' realtime " + args,
                                 scratch());
}

const std::string kCornell = std::string(GIQ_SCENES_DIR) + "/cornell.gltf";

TEST(RealtimeCli, WritesFramesAndTimings) {
  const fs::path out = scratch() / "run";
  fs::remove_all(out);
  const Outcome r = giq("--scene '" + kCornell + "' --technique direct --param shadow_map_size=128 --frames 2 --warmup 1 "
                        "--width 24 --height 16 --validation --out '" + out.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;  // no validation message, no warning
  // Frames 1 and 2 are measured (frame 0 is the warm-up).
  EXPECT_FALSE(fs::exists(out / "frame_0000.exr"));
  const giq::image::Image img = giq::image::read_image(out / "frame_0002.exr");
  EXPECT_EQ(img.width(), 24);
  EXPECT_EQ(img.height(), 16);
  for (const char* c : {"R", "G", "B", "direct.R", "indirect.B"}) EXPECT_TRUE(img.has_channel(c)) << c;
  EXPECT_EQ(img.metadata.at("giq.technique"), "direct");
  const auto j = nlohmann::json::parse(slurp(out / "timings.json"));
  EXPECT_EQ(j["frames"]["measured"], 2);
  EXPECT_EQ(j["frames"]["warmup"], 1);
  EXPECT_EQ(j["resolution"], nlohmann::json::array({24, 16}));
  EXPECT_FALSE(j["device"]["name"].get<std::string>().empty());
  EXPECT_EQ(j["passes"].size(), 3u);
}

TEST(RealtimeCli, RendersTexturedNormalMappedAlphaMaskedScenes) {
  const std::string scene = std::string(GIQ_TEST_DATA) + "/scenes/textured_room.gltf";
  for (const char* technique : {"direct", "pt"}) {
    const fs::path out = scratch() / (std::string("textured_") + technique);
    fs::remove_all(out);
    const Outcome r = giq("--scene '" + scene + "' --technique " + technique +
                          " --param " + (technique == std::string("direct") ? "shadow_map_size=128" : "samples_per_frame=2") +
                          " --frames 1 --width 16 --height 16 --validation --out '" + out.string() + "'");
    ASSERT_EQ(r.exit_code, 0) << technique << "\n" << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;
    const giq::image::Image img = giq::image::read_image(out / "frame_0000.exr");
    double sum = 0.0;
    for (size_t i = 0; i < img.pixel_count(); ++i) sum += img.channel("G")[i];
    EXPECT_TRUE(std::isfinite(sum) && sum > 0.0) << technique;
  }
}

TEST(RealtimeCli, ListsTechniquesWithTheirParameters) {
  const Outcome r = giq("--list");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("pt"), std::string::npos);
  EXPECT_NE(r.out.find("--param shadow_map_size=2048"), std::string::npos) << r.out;
}

TEST(RealtimeCli, BadInputExitsTwoWithOneLine) {
  const fs::path out = scratch() / "bad";
  for (const std::string& args :
       {"--scene '" + kCornell + "' --technique nope --out '" + out.string() + "'",
        "--scene '" + kCornell + "' --technique pt --param bounces=3 --out '" + out.string() + "'",
        "--scene '" + kCornell + "' --view nowhere --out '" + out.string() + "'",
        "--scene '" + kCornell + "' --device no-such-device --out '" + out.string() + "'",
        "--scene /no/such/scene.gltf --out '" + out.string() + "'"}) {
    const Outcome r = giq(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

}  // namespace
