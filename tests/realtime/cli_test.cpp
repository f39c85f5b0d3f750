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

// An asset as real ones come: four 2048^2 8-bit textures (DamagedHelmet's set), no light and
// no camera. As float RGBA its texels took 256 MiB, twice lavapipe's largest storage buffer;
// at 8 bits they take 64 MiB. --sun and --camera auto light and frame it.
TEST(RealtimeCli, RendersAssetTexturesAtTheirRealSize) {
  const fs::path dir = scratch() / "asset";
  fs::create_directories(dir);
  const int n = 2048;
  std::vector<unsigned char> rgba(size_t(n) * n * 4);
  for (int k = 0; k < 4; ++k) {
    for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = (i % 4 == 3) ? 255 : (unsigned char)(40 * (k + 1) + (i / 4) % 7);
    giq::image::write_png_rgb8(dir / ("t" + std::to_string(k) + ".png"), n, n, 4, rgba.data());
  }
  // A unit quad in the xy plane facing +z, with UVs: positions, normals, uvs, indices.
  const float data[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 1, 1, 1, 1, 0, 0, 0};
  const uint16_t idx[] = {0, 1, 2, 0, 2, 3};
  {
    std::ofstream bin(dir / "quad.bin", std::ios::binary);
    bin.write(reinterpret_cast<const char*>(data), sizeof data);
    bin.write(reinterpret_cast<const char*>(idx), sizeof idx);
  }
  std::ofstream(dir / "asset.gltf") << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2},"indices":3,"material":0}]}],
    "materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0},"metallicRoughnessTexture":{"index":1}},
                  "normalTexture":{"index":2},"emissiveTexture":{"index":3},"emissiveFactor":[0.1,0.1,0.1]}],
    "textures":[{"source":0},{"source":1},{"source":2},{"source":3}],
    "images":[{"uri":"t0.png"},{"uri":"t1.png"},{"uri":"t2.png"},{"uri":"t3.png"}],
    "buffers":[{"uri":"quad.bin","byteLength":140}],
    "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":48},
                   {"buffer":0,"byteOffset":96,"byteLength":32},{"buffer":0,"byteOffset":128,"byteLength":12}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
                 {"bufferView":1,"componentType":5126,"count":4,"type":"VEC3"},
                 {"bufferView":2,"componentType":5126,"count":4,"type":"VEC2"},
                 {"bufferView":3,"componentType":5123,"count":6,"type":"SCALAR"}]})";
  const fs::path out = dir / "run";
  const Outcome r = giq("--scene '" + (dir / "asset.gltf").string() + "' --technique direct --param shadow_map_size=64 --sun dir=0,0,-1 "
                        "illuminance=2 --camera auto --width 16 --height 16 --out '" + out.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(out / "timings.json"));
  // Four textures of 2048^2 words, each with its mip chain down to 1 x 1 (a sum of
  // 2048^2 / 4^l over 12 levels: (4^12 - 1) / 3 words), plus the 512-word decode table.
  const double chain = (std::pow(4.0, 12) - 1.0) / 3.0;
  ASSERT_EQ(n, 2048);
  EXPECT_NEAR(j["gpu_memory_mb"]["textures"].get<double>(), (4.0 * chain + 512.0) * 4.0 / (1 << 20), 1e-9);
  const giq::image::Image img = giq::image::read_image(out / "frame_0000.exr");
  double sum = 0.0;
  for (size_t i = 0; i < img.pixel_count(); ++i) sum += img.channel("G")[i];
  EXPECT_TRUE(std::isfinite(sum) && sum > 0.0);
  // Lit by an environment instead: `direct` shows it only as background, and says so.
  const Outcome env = giq("--scene '" + (dir / "asset.gltf").string() + "' --technique direct --param shadow_map_size=64 --env 0.2 "
                          "--camera auto --width 8 --height 8 --out '" + (dir / "env").string() + "'");
  ASSERT_EQ(env.exit_code, 0) << env.err;
  EXPECT_NE(env.err.find("technique direct does not light surfaces with the environment"), std::string::npos) << env.err;
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
