// End to end: `giq reference` on a small glTF file. The written EXR has every layer with
// beauty = direct + indirect, its files are byte-identical across thread counts and after a
// SIGKILL followed by --resume, and bad input exits with code 2.

#include <gtest/gtest.h>

#include <limits>
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/subprocess.h"
#include "giq/image/io.h"

namespace fs = std::filesystem;

namespace {

// A scratch folder for this process, removed when the tests end.
struct WorkDir {
  fs::path path;
  WorkDir() : path(fs::temp_directory_path() / ("giq_ref_cli_" + std::to_string(::getpid()))) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~WorkDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

fs::path work_dir() {
  static const WorkDir d;
  return d.path;
}

// A floor, a back wall and a double-sided area light, with a camera, as glTF 2.0 with an
// external buffer.
fs::path write_scene() {
  const fs::path dir = work_dir();
  const float pos[] = {-2, 0, 2, 2, 0, 2, 2, 0, -2, -2, 0, -2,      // floor, facing +y
                       -2, 0, -2, 2, 0, -2, 2, 3, -2, -2, 3, -2,    // back wall, facing +z
                       -0.5f, 2, -0.5f, 0.5f, 2, -0.5f, 0.5f, 2, 0.5f, -0.5f, 2, 0.5f};  // light
  const uint16_t idx[] = {0, 1, 2, 0, 2, 3};
  std::ofstream bin(dir / "scene.bin", std::ios::binary);
  bin.write(reinterpret_cast<const char*>(pos), sizeof pos);
  bin.write(reinterpret_cast<const char*>(idx), sizeof idx);
  bin.close();
  std::ostringstream j;
  j << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,1,2,3]}],
  "nodes":[{"mesh":0,"name":"floor"},{"mesh":1,"name":"wall"},{"mesh":2,"name":"light"},
           {"camera":0,"name":"cam","translation":[0.3,1.2,3.5]}],
  "cameras":[{"type":"perspective","perspective":{"yfov":0.9,"znear":0.01}}],
  "materials":[{"pbrMetallicRoughness":{"baseColorFactor":[0.7,0.6,0.5,1],"metallicFactor":0,"roughnessFactor":0.4}},
               {"pbrMetallicRoughness":{"baseColorFactor":[0.3,0.5,0.7,1],"metallicFactor":0}},
               {"emissiveFactor":[1,0.9,0.8],"doubleSided":true,"pbrMetallicRoughness":{"baseColorFactor":[0,0,0,1],"metallicFactor":0}}],
  "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":3,"material":0}]},
            {"primitives":[{"attributes":{"POSITION":1},"indices":3,"material":1}]},
            {"primitives":[{"attributes":{"POSITION":2},"indices":3,"material":2}]}],
  "buffers":[{"byteLength":)" << sizeof pos + sizeof idx << R"(,"uri":"scene.bin"}],
  "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":144},{"buffer":0,"byteOffset":144,"byteLength":12}],
  "accessors":[
    {"bufferView":0,"byteOffset":0,"componentType":5126,"count":4,"type":"VEC3","min":[-2,0,-2],"max":[2,0,2]},
    {"bufferView":0,"byteOffset":48,"componentType":5126,"count":4,"type":"VEC3","min":[-2,0,-2],"max":[2,3,-2]},
    {"bufferView":0,"byteOffset":96,"componentType":5126,"count":4,"type":"VEC3","min":[-0.5,2,-0.5],"max":[0.5,2,0.5]},
    {"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}]})";
  std::ofstream(dir / "scene.gltf") << j.str();
  return dir / "scene.gltf";
}

// Runs giq with the arguments; returns its pid (wait for it with finish()).
pid_t start(const std::vector<std::string>& args) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::vector<char*> argv;
    std::string bin = GIQ_BINARY;
    argv.push_back(bin.data());
    std::vector<std::string> copy = args;
    for (std::string& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(null, 2);
    ::execv(bin.c_str(), argv.data());
    ::_exit(127);
  }
  return pid;
}
int finish(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}
int giq(const std::vector<std::string>& args) { return finish(start(args)); }

using giq::test::slurp;

std::vector<std::string> render_args(const fs::path& scene, const fs::path& out, int spp, int threads) {
  return {"reference", "--scene", scene.string(), "--spp", std::to_string(spp), "--width", "32", "--height", "24",
          "--threads", std::to_string(threads), "--out", out.string()};
}

TEST(ReferenceCli, WritesEveryLayerWithBeautyEqualToDirectPlusIndirect) {
  const fs::path scene = write_scene(), out = work_dir() / "layers.exr";
  ASSERT_EQ(giq(render_args(scene, out, 16, 2)), 0);
  const giq::image::Image img = giq::image::read_image(out);
  for (const char* c : {"R", "G", "B", "direct.R", "direct.G", "direct.B", "indirect.R", "indirect.G", "indirect.B", "albedo.R",
                        "albedo.G", "albedo.B", "N.X", "N.Y", "N.Z", "Z", "objectId", "variance.R", "variance.G", "variance.B", "spp"})
    EXPECT_TRUE(img.has_channel(c)) << c;
  double indirect = 0.0;
  for (const char* l : {"R", "G", "B"}) {
    const float* b = img.channel(l);
    const float* d = img.channel(std::string("direct.") + l);
    const float* i = img.channel(std::string("indirect.") + l);
    for (size_t k = 0; k < img.pixel_count(); ++k) {
      ASSERT_TRUE(std::isfinite(b[k]));
      // Exactly, in float arithmetic.
      ASSERT_EQ(d[k] + i[k], b[k]) << l << " pixel " << k;
      ASSERT_GE(i[k], 0.0f);
      indirect += i[k];
    }
  }
  EXPECT_GT(indirect, 0.0);  // the wall lights the floor: there is indirect light
  for (size_t k = 0; k < img.pixel_count(); ++k) EXPECT_EQ(img.channel("spp")[k], 16.0f);
  for (const char* key : {"giq.version", "giq.scene_hash", "giq.view", "giq.frame", "giq.spp", "giq.seed", "giq.settings",
                          "giq.nonfinite_samples", "giq.camera"})
    EXPECT_TRUE(img.metadata.count(key)) << key;
  EXPECT_EQ(img.metadata.at("giq.spp"), "16");
  EXPECT_EQ(img.metadata.at("giq.nonfinite_samples"), "0");
  EXPECT_EQ(img.metadata.at("giq.view"), "cam");
}

// --half: the colour layers are the float32 render rounded to float16 (within half an ulp:
// 2^(e - 11) for a value in [2^e, 2^(e+1))), every other channel is bit-identical, and the file
// is smaller.
TEST(ReferenceCli, HalfStoresColourLayersAsFloat16AndTheRestExactly) {
  const fs::path scene = write_scene(), f32 = work_dir() / "f32.exr", f16 = work_dir() / "f16.exr";
  ASSERT_EQ(giq(render_args(scene, f32, 16, 2)), 0);
  std::vector<std::string> args = render_args(scene, f16, 16, 2);
  args.insert(args.end() - 2, "--half");
  ASSERT_EQ(giq(args), 0);
  const giq::image::Image a = giq::image::read_image(f32), b = giq::image::read_image(f16);
  ASSERT_EQ(a.channel_names().size(), b.channel_names().size());
  size_t rounded = 0;
  for (const std::string& c : a.channel_names()) {
    const bool colour = c.size() == 1 ? (c == "R" || c == "G" || c == "B")
                                      : c.rfind("direct.", 0) == 0 || c.rfind("indirect.", 0) == 0 ||
                                            c.rfind("albedo.", 0) == 0;
    for (size_t k = 0; k < a.pixel_count(); ++k) {
      const float x = a.channel(c)[k], y = b.channel(c)[k];
      if (!colour) {
        ASSERT_EQ(x, y) << c << " pixel " << k;
        continue;
      }
      const float ulp = x == 0.0f ? 0.0f : std::ldexp(1.0f, std::ilogb(std::max(std::fabs(x), 6.103515625e-05f)) - 10);
      ASSERT_LE(std::fabs(x - y), 0.5f * ulp) << c << " pixel " << k;
      rounded += x != y;
    }
  }
  EXPECT_GT(rounded, 0u);  // float16 is really used
  EXPECT_LT(fs::file_size(f16), fs::file_size(f32));
}

TEST(ReferenceCli, FilesAreByteIdenticalAcrossThreadsAndAfterKillAndResume) {
  const fs::path scene = write_scene();
  const fs::path a = work_dir() / "a.exr", b = work_dir() / "b.exr", c = work_dir() / "c.exr";
  const int spp = 1500;
  ASSERT_EQ(giq(render_args(scene, a, spp, 1)), 0);
  ASSERT_EQ(giq(render_args(scene, b, spp, 2)), 0);
  EXPECT_EQ(slurp(a), slurp(b));

  // SIGKILL partway, then resume: the result must be the uninterrupted file.
  std::vector<std::string> args = render_args(scene, c, spp, 2);
  args.insert(args.end(), {"--checkpoint-interval", "0.05"});
  const pid_t pid = start(args);
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  ::kill(pid, SIGKILL);
  const int killed = finish(pid);
  args.push_back("--resume");
  ASSERT_EQ(giq(args), 0);
  EXPECT_EQ(slurp(a), slurp(c)) << (killed == 0 ? "(the render finished before the kill)" : "");
  EXPECT_FALSE(fs::exists(c.string() + ".checkpoint"));

  // SIGINT: the command saves a checkpoint and exits with 130; --resume completes it.
  fs::remove(c);
  args.pop_back();
  const pid_t pid2 = start(args);
  // Interrupt once the render has saved progress (the first checkpoint, 0.05 s into the
  // render), however long start-up takes on a loaded machine.
  for (int i = 0; i < 6000 && !fs::exists(c.string() + ".checkpoint") && !fs::exists(c); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ::kill(pid2, SIGINT);
  const int interrupted = finish(pid2);
  if (interrupted == 130) {
    EXPECT_TRUE(fs::exists(c.string() + ".checkpoint"));
    EXPECT_FALSE(fs::exists(c));
  } else {
    EXPECT_EQ(interrupted, 0) << "neither interrupted nor finished";
  }
  args.push_back("--resume");
  ASSERT_EQ(giq(args), 0);
  EXPECT_EQ(slurp(a), slurp(c));
}

TEST(ReferenceCli, BadInputExitsWithTwo) {
  const fs::path scene = write_scene(), out = work_dir() / "bad.exr";
  std::vector<std::string> args = render_args(scene, out, 4, 1);
  args.insert(args.end(), {"--view", "nosuchview"});
  EXPECT_EQ(giq(args), 2);
  EXPECT_EQ(giq({"reference", "--scene", scene.string(), "--out", out.string()}), 2);  // no stopping criterion
  EXPECT_EQ(giq({"reference", "--scene", scene.string(), "--spp", "4", "--camera", "eye=1,2", "target=0,0,0", "--out",
                 out.string()}),
            2);
  // An orthographic half height must be positive, and excludes a field of view.
  for (const std::vector<std::string>& camera : std::vector<std::vector<std::string>>{{"ymag=0"}, {"ymag=-1"}, {"ymag=nan"}, {"fov=30", "ymag=1"}}) {
    std::vector<std::string> a = {"reference", "--scene", scene.string(), "--spp", "4", "--camera", "eye=1,2,3", "target=0,0,0"};
    a.insert(a.end(), camera.begin(), camera.end());
    a.insert(a.end(), {"--out", out.string()});
    EXPECT_EQ(giq(a), 2) << camera.back();
  }
  EXPECT_EQ(giq({"reference", "--scene", scene.string(), "--spp", "4", "--width", "0", "--out", out.string()}), 2);
  EXPECT_EQ(giq({"reference", "--scene", (work_dir() / "missing.gltf").string(), "--spp", "4", "--out", out.string()}), 2);
  // Seeds outside uint64 were once wrapped (-1) or clamped (2^64) to 2^64 - 1 without a word.
  for (const char* seed : {"-1", "18446744073709551616", "1e23", "7x"})
    EXPECT_EQ(giq({"reference", "--scene", scene.string(), "--spp", "4", "--seed", seed, "--out", out.string()}), 2)
        << seed;
  EXPECT_FALSE(fs::exists(out));
}

TEST(ReferenceCli, ASceneWithoutLightIsRefusedUntilTheCommandLineGivesOne) {
  // transforms.gltf has geometry and no light, no camera: every image of it would be black.
  const fs::path scene = fs::path(GIQ_TEST_DATA) / "scenes" / "transforms.gltf", out = work_dir() / "unlit.exr";
  std::vector<std::string> args = {"reference", "--scene", scene.string(), "--spp", "8", "--width", "16", "--height", "16",
                                   "--camera", "auto", "--out", out.string()};
  EXPECT_EQ(giq(args), 2);
  EXPECT_FALSE(fs::exists(out));
  // A sun straight down: the floor quad (facing +y) is lit. The scene hash names the sun, so
  // this image cannot pass for a render of the file alone.
  args.insert(args.end(), {"--sun", "dir=0,-1,0", "illuminance=2"});
  ASSERT_EQ(giq(args), 0);
  const giq::image::Image lit = giq::image::read_image(out);
  EXPECT_EQ(lit.metadata.at("giq.view"), "camera");
  double sum = 0.0;
  for (size_t k = 0; k < lit.pixel_count(); ++k) sum += lit.channel("G")[k];
  EXPECT_GT(sum, 0.0);
  const std::string sun_hash = lit.metadata.at("giq.scene_hash");
  // The same sun spelt differently (an unnormalised direction, 2.0 for 2) is the same scene.
  fs::remove(out);
  std::vector<std::string> respelt(args.begin(), args.end() - 3);
  respelt.insert(respelt.end(), {"--sun", "dir=0,-2,0", "illuminance=2.0"});
  ASSERT_EQ(giq(respelt), 0);
  EXPECT_EQ(giq::image::read_image(out).metadata.at("giq.scene_hash"), sun_hash);
  // The same with a constant environment instead: lit again, under another scene hash.
  fs::remove(out);
  args.resize(args.size() - 3);
  args.insert(args.end(), {"--env", "0.5"});
  ASSERT_EQ(giq(args), 0);
  const std::string env_hash = giq::image::read_image(out).metadata.at("giq.scene_hash");
  EXPECT_NE(sun_hash, env_hash);
  // An equirectangular map (a 8 x 4 OpenEXR): lit, under a hash of its own.
  const fs::path map = work_dir() / "sky.exr", bad_map = work_dir() / "nan_sky.exr";
  giq::image::Image sky(8, 4);
  for (const char* c : {"R", "G", "B"}) {
    float* p = sky.add_channel(c);
    for (size_t k = 0; k < sky.pixel_count(); ++k) p[k] = k < 16 ? 2.0f : 0.1f;
  }
  giq::image::write_exr(sky, map);
  fs::remove(out);
  args.resize(args.size() - 2);
  args.insert(args.end(), {"--env", map.string()});
  ASSERT_EQ(giq(args), 0);
  const giq::image::Image under_map = giq::image::read_image(out);
  EXPECT_NE(under_map.metadata.at("giq.scene_hash"), env_hash);
  sum = 0.0;
  for (size_t k = 0; k < under_map.pixel_count(); ++k) sum += under_map.channel("G")[k];
  EXPECT_GT(sum, 0.0);
  // A map with a NaN, and a missing map: input errors, nothing written.
  sky.channel("G")[5] = std::numeric_limits<float>::quiet_NaN();
  giq::image::write_exr(sky, bad_map);
  for (const fs::path& m : {bad_map, work_dir() / "no_such_sky.exr"}) {
    fs::remove(out);
    args.back() = m.string();
    EXPECT_EQ(giq(args), 2) << m;
    EXPECT_FALSE(fs::exists(out));
  }
  // Malformed light options are input errors.
  for (const std::vector<std::string>& bad : {std::vector<std::string>{"--sun", "dir=0,0,0", "illuminance=1"},
                                              {"--sun", "dir=0,-1,0", "illuminance=-1"},
                                              {"--sun", "illuminance=1", "color=1,1,1"},
                                              {"--env", "1,2"},
                                              {"--env", "-1"}}) {
    std::vector<std::string> a = {"reference", "--scene", scene.string(), "--spp", "4", "--camera", "auto", "--out",
                                  (work_dir() / "bad_light.exr").string()};
    a.insert(a.end(), bad.begin(), bad.end());
    EXPECT_EQ(giq(a), 2) << bad[1];
  }
}

TEST(ReferenceCli, OutputsAreCheckedBeforeAnyWork) {
  const fs::path scene = write_scene(), dir = work_dir();
  const std::string before = slurp(scene);
  // The scene as the output: refused, the scene untouched.
  EXPECT_EQ(giq(render_args(scene, scene, 4, 1)), 2);
  EXPECT_EQ(slurp(scene), before);
  // A folder as the output, or an output under a regular file: refused before rendering; 10^6
  // samples per pixel would take minutes, so a quick exit shows that nothing was rendered.
  fs::create_directories(dir / "a_folder.exr");
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(giq(render_args(scene, dir / "a_folder.exr", 1000000, 1)), 2);
  EXPECT_EQ(giq(render_args(scene, scene / "under_a_file.exr", 1000000, 1)), 2);
  // Where the checkpoint would go, a folder: once an internal error (exit 3).
  fs::create_directories(dir / "cp_folder.exr.checkpoint" / "x");
  EXPECT_EQ(giq(render_args(scene, dir / "cp_folder.exr", 1000000, 1)), 2);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 30.0);
}

TEST(ReferenceCli, AnExistingCheckpointIsNeverDiscardedSilently) {
  const fs::path scene = write_scene(), out = work_dir() / "cp.exr", checkpoint = work_dir() / "cp.exr.checkpoint";
  std::ofstream(checkpoint) << "hours of samples";
  // Without --resume or --overwrite: exit 2, the checkpoint kept, nothing written.
  EXPECT_EQ(giq(render_args(scene, out, 4, 1)), 2);
  EXPECT_EQ(slurp(checkpoint), "hours of samples");
  EXPECT_FALSE(fs::exists(out));
  std::vector<std::string> both = render_args(scene, out, 4, 1);
  both.insert(both.end(), {"--resume", "--overwrite"});
  EXPECT_EQ(giq(both), 2);
  // --overwrite starts again and leaves the image, no checkpoint.
  std::vector<std::string> overwrite = render_args(scene, out, 4, 1);
  overwrite.push_back("--overwrite");
  EXPECT_EQ(giq(overwrite), 0);
  EXPECT_TRUE(fs::exists(out));
  EXPECT_FALSE(fs::exists(checkpoint));
}

}  // namespace

namespace {

giq::test::Outcome giq_captured(const std::string& args) {
  return giq::test::run_captured(giq::test::shell_quote(GIQ_BINARY) + " " + args, work_dir() / "captured");
}

}  // namespace

// A camera given in an engine's frame and units (docs/own-engine.md, "Cameras") renders the
// same image as the same camera given in glTF's: Unreal's (x, y, z) centimetres is glTF's
// (y, z, -x) / 100, Unity's (x, y, z) is (x, y, -z). A horizontal field of view at the image's
// aspect is the vertical 2 atan(tan(h/2) / aspect). Each mistake gets its own message.
TEST(ReferenceCli, CamerasInAnEnginesFrameAndEachMistakeSaid) {
  const std::string scene = giq::test::shell_quote((fs::path(GIQ_SCENES_DIR) / "cornell.gltf").string());
  const std::string common = "reference --scene " + scene + " --spp 8 --seed 3 --width 24 --height 16 ";
  auto render = [&](const std::string& camera, const std::string& name) {
    const fs::path out = work_dir() / (name + ".exr");
    const auto r = giq_captured(common + "--camera " + camera + " --out " + giq::test::shell_quote(out.string()));
    EXPECT_EQ(r.exit_code, 0) << camera << "\n" << r.err;
    return giq::image::read_image(out);
  };
  // Cornell's front camera, 39.3 degrees vertical (24 x 16 pixels: aspect 1.5).
  const double vfov = 2.0 * std::atan(12.5 / 35.0) * 180.0 / M_PI;
  const double hfov = 2.0 * std::atan(std::tan(0.5 * vfov * M_PI / 180.0) * 1.5) * 180.0 / M_PI;
  char fov[64], hfov_arg[64];
  std::snprintf(fov, sizeof fov, "fov=%.9g", vfov);
  std::snprintf(hfov_arg, sizeof hfov_arg, "hfov=%.9g", hfov);
  const auto gltf = render(std::string("eye=0.278,0.273,-0.8 target=0.278,0.273,0 ") + fov, "gltf");
  const auto unreal = render(std::string("eye=80,27.8,27.3 target=0,27.8,27.3 frame=unreal ") + fov, "unreal");
  const auto unity = render(std::string("eye=0.278,0.273,0.8 target=0.278,0.273,0 handedness=left ") + hfov_arg, "unity");
  const auto mm = render(std::string("eye=278,273,-800 target=278,273,0 units=mm ") + fov, "mm");
  // The header keeps the camera as given, beside the camera the renderer used.
  EXPECT_EQ(unreal.metadata.at("giq.camera_given"), std::string("eye=80,27.8,27.3 target=0,27.8,27.3 frame=unreal ") + fov);
  EXPECT_EQ(unreal.metadata.at("giq.camera"), gltf.metadata.at("giq.camera"));
  for (const auto* other : {&unreal, &unity, &mm}) {
    // The same rays to float precision: the same paths, up to a last-bit difference in a
    // direction that may move a rare path; means differ by far less than their noise.
    double diff = 0.0, sum = 0.0;
    for (const char* c : {"R", "G", "B"})
      for (size_t i = 0; i < gltf.pixel_count(); ++i)
        diff += std::abs(double(gltf.channel(c)[i]) - other->channel(c)[i]), sum += gltf.channel(c)[i];
    EXPECT_LT(diff, 1e-3 * sum);
  }
  // A camera looking away from the box: black, said so, and no "rel.err 0%".
  const auto away = giq_captured(common + "--camera eye=0.278,0.273,-0.8 target=0.278,0.273,-2 --out " +
                                 giq::test::shell_quote((work_dir() / "away.exr").string()));
  EXPECT_EQ(away.exit_code, 0) << away.err;
  EXPECT_NE(away.err.find("black in every pixel"), std::string::npos) << away.err;
  EXPECT_NE(away.out.find("rel.err n/a"), std::string::npos) << away.out;
  EXPECT_EQ(gltf.pixel_count(), 24u * 16u);
  std::vector<std::string> messages;
  for (const char* mistake : {"fov=0", "fov=39deg", "hfov=50 fov=30", "target=0.278,0.273,-0.8", "frame=blender",
                              "units=km", "handedness=up", "fov=30 ymag=1", "focal=35"}) {
    const auto r = giq_captured(common + "--camera eye=0.278,0.273,-0.8 target=0.278,0.273,0 " + mistake + " --out " +
                                giq::test::shell_quote((work_dir() / "bad.exr").string()));
    EXPECT_EQ(r.exit_code, 2) << mistake;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(std::find(messages.begin(), messages.end(), r.err), messages.end()) << "the same message twice: " << r.err;
    messages.push_back(r.err);
  }
}
