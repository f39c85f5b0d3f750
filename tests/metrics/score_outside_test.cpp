// `giq score` with images from outside giq, end to end: an engine's tone-mapped screenshot
// under the same display transform, exposure and unit mismatches, black and noisy references,
// --fail/--warn bounds, separate layers, crops and alpha, docs/own-engine.md's worked example,
// and the per-pixel z-test.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "giq/image/io.h"
#include "giq/image/srgb.h"
#include "score_cli.h"
#include "support/subprocess.h"
#include "synthetic.h"

using namespace giq;
using namespace giq::test::score_cli;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

// The tone curves written out here from their sources, independently of metrics/display.cpp.
double curve(const std::string& name, double x) {
  if (name == "clamp") return std::min(x, 1.0);
  if (name == "reinhard") return x / (1.0 + x);
  if (name == "aces") return std::clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
  auto h = [](double v) {
    const double A = 0.15, B = 0.50, C = 0.10, D = 0.20, E = 0.02, F = 0.30;
    return ((v * (A * v + C * B) + D * E) / (v * (A * v + B) + D * F)) - E / F;
  };
  return h(x) / h(11.2);  // hable
}

}  // namespace

// An engine's screenshot: the reference's radiance (0 to 8, HDR), exposed by -1 stop, through
// the engine's tone curve, sRGB-encoded to 8 bits. Scored with the same --tonemap and
// --exposure, only the 8-bit rounding is left: at most half a code step in linear light per
// channel (the largest step, between codes 254 and 255, bounds it), no warning, and a
// brightness ratio of 1 within that rounding. Without the tone curve the same PNG is an
// LDR image against HDR radiance, which is said, and the error is far larger.
TEST(ScoreCli, ToneMappedScreenshotIsScoredUnderTheSameCurve) {
  const fs::path d = fresh_dir("tonemap");
  image::Image ref = test::rgb_image(W, H, [](int x, int y, int k) { return 8.0f * test::hash01(x, y, k); });
  // A golden's noise small enough to resolve 8-bit rounding.
  test::add_layer(ref, "variance", [](int, int, int) { return 1e-10f; });
  image::write_exr(ref, d / "ref.exr");
  const double half_step = 0.5 * (1.0 - image::srgb_decode(254.0f / 255.0f));
  for (const std::string name : {"clamp", "reinhard", "aces", "hable"}) {
    std::vector<unsigned char> px(size_t(W) * H * 3);
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x)
        for (int k = 0; k < 3; ++k) {
          const double v = curve(name, 0.5 * ref.at(k == 0 ? "R" : k == 1 ? "G" : "B", x, y));
          px[(size_t(y) * W + size_t(x)) * 3 + size_t(k)] = (unsigned char)std::lround(255.0 * image::srgb_encode(float(v)));
        }
    image::write_png_rgb8(d / (name + ".png"), W, H, 3, px.data());
    const CliRun r = giq_run("score --ref " + (d / "ref.exr").string() + " --test " + (d / (name + ".png")).string() +
                                 " --tonemap " + name + " --exposure -1 --out " + (d / name).string() + " --json",
                             d);
    ASSERT_EQ(r.code, 0) << r.err;
    const json j = json::parse(r.out);
    EXPECT_LE(j["metrics"]["mae"]["value"].get<double>(), half_step) << name;
    EXPECT_LE(j["metrics"]["mse"]["value"].get<double>(), half_step * half_step) << name;
    EXPECT_NEAR(j["metrics"]["mean_luminance_ratio"].get<double>(), 1.0, 0.02) << name;
    EXPECT_EQ(j["warnings"], json::array()) << name;
    EXPECT_TRUE(r.err.empty()) << r.err;
    EXPECT_EQ(j["inputs"]["display"]["tone_curve"], name);
    EXPECT_EQ(j["inputs"]["dynamic_range"], "ldr");
    if (name != "aces") continue;
    const CliRun raw = giq_run("score --ref " + (d / "ref.exr").string() + " --test " + (d / "aces.png").string() +
                                   " --out " + (d / "raw").string() + " --json",
                               d);
    ASSERT_EQ(raw.code, 0) << raw.err;
    const json jr = json::parse(raw.out);
    ASSERT_EQ(jr["warnings"].size(), 2u) << jr["warnings"];  // LDR against HDR, and the brightness
    EXPECT_NE(jr["warnings"][0].get<std::string>().find("low-dynamic-range"), std::string::npos);
    EXPECT_NE(raw.err.find("warning: the test is a low-dynamic-range image"), std::string::npos) << raw.err;
    EXPECT_GT(jr["metrics"]["mse"]["value"].get<double>(), 100.0 * j["metrics"]["mse"]["value"].get<double>());
  }
}

// Exposure alone keeps the comparison HDR and scales the reference's radiance by 2^ev and its
// variance (the noise floor) by 4^ev; a test twice as bright as the reference then matches
// with --exposure 1, and without it the brightness ratio is reported.
TEST(ScoreCli, ExposureScalesRadianceAndNoiseAndTheRatioIsReported) {
  const fs::path d = fresh_dir("exposure");
  const image::Image ref = reference();
  image::write_exr(ref, d / "ref.exr");
  image::Image twice = test::rgb_image(W, H, [&](int x, int y, int k) { return 2.0f * ref.at(k == 0 ? "R" : k == 1 ? "G" : "B", x, y); });
  image::write_exr(twice, d / "twice.exr");
  const std::string base = "score --ref " + (d / "ref.exr").string() + " --test " + (d / "twice.exr").string() + " --json --out ";
  const CliRun plain = giq_run(base + (d / "plain").string(), d);
  ASSERT_EQ(plain.code, 0) << plain.err;
  const json jp = json::parse(plain.out);
  EXPECT_NEAR(jp["metrics"]["mean_luminance_ratio"].get<double>(), 2.0, 1e-6);
  ASSERT_EQ(jp["warnings"].size(), 1u);
  EXPECT_NE(jp["warnings"][0].get<std::string>().find("2.000000 times"), std::string::npos) << jp["warnings"][0];
  const CliRun exposed = giq_run(base + (d / "exposed").string() + " --exposure 1", d);
  ASSERT_EQ(exposed.code, 0) << exposed.err;
  const json je = json::parse(exposed.out);
  EXPECT_EQ(je["metrics"]["mse"]["value"].get<double>(), 0.0);  // x 2 is exact in float
  EXPECT_EQ(je["metrics"]["mean_luminance_ratio"].get<double>(), 1.0);
  // An error of 0 lies below the golden's noise floor (1e-6 x 4): only that is said.
  ASSERT_EQ(je["warnings"].size(), 1u) << je["warnings"];
  EXPECT_NE(je["warnings"][0].get<std::string>().find("too noisy"), std::string::npos);
  EXPECT_EQ(je["inputs"]["dynamic_range"], "hdr");
  EXPECT_NEAR(je["metrics"]["noise_floor"]["value"].get<double>(), 4.0 * jp["metrics"]["noise_floor"]["value"].get<double>(), 1e-12);
  // 683 lm/W between photometric and radiometric units is named.
  image::write_exr(test::rgb_image(W, H, [&](int x, int y, int k) { return 683.0f * ref.at(k == 0 ? "R" : k == 1 ? "G" : "B", x, y); }),
                   d / "lumens.exr");
  const CliRun units = giq_run("score --ref " + (d / "ref.exr").string() + " --test " + (d / "lumens.exr").string() +
                                   " --json --out " + (d / "units").string(), d);
  ASSERT_EQ(units.code, 0) << units.err;
  EXPECT_NE(json::parse(units.out)["warnings"][0].get<std::string>().find("683"), std::string::npos);
}

// A black reference and one too noisy to resolve the error are each said once; an identical
// pair says nothing.
TEST(ScoreCli, BlackOrNoisyReferencesAreSaid) {
  const fs::path d = fresh_dir("doubtful");
  image::write_exr(test::rgb_image(W, H, [](int, int, int) { return 0.0f; }), d / "black.exr");
  image::write_exr(test::rgb_image(W, H, [](int x, int y, int k) { return 0.5f + 0.01f * test::hash01(x, y, k); }), d / "test.exr");
  image::Image noisy = test::rgb_image(W, H, [](int, int, int) { return 0.5f; });
  test::add_layer(noisy, "variance", [](int, int, int) { return 1.0f; });
  image::write_exr(noisy, d / "noisy.exr");
  auto warnings = [&](const std::string& ref, const std::string& test_file, const std::string& out) {
    const CliRun r = giq_run("score --ref " + (d / ref).string() + " --test " + (d / test_file).string() + " --json --out " +
                                 (d / out).string(), d);
    EXPECT_EQ(r.code, 0) << r.err;
    return json::parse(r.out)["warnings"];
  };
  const json black = warnings("black.exr", "test.exr", "b");
  ASSERT_EQ(black.size(), 1u) << black;
  EXPECT_NE(black[0].get<std::string>().find("black"), std::string::npos);
  const json noisy_w = warnings("noisy.exr", "test.exr", "n");
  ASSERT_EQ(noisy_w.size(), 1u) << noisy_w;
  EXPECT_NE(noisy_w[0].get<std::string>().find("too noisy"), std::string::npos);
  EXPECT_EQ(warnings("test.exr", "test.exr", "same"), json::array());
}

// --fail and --warn bound any catalogue metric: exit 0 when every fail level holds (warn
// levels only mark), 1 when one does not, and the table marks which.
TEST(ScoreCli, BoundsSetTheExitCode) {
  const fs::path d = fresh_dir("bounds");
  const image::Image ref = reference();
  image::write_exr(ref, d / "ref.exr");
  image::write_exr(test::rgb_image(W, H, [&](int x, int y, int k) { return ref.at(k == 0 ? "R" : k == 1 ? "G" : "B", x, y) + 0.1f; }),
                   d / "tech.exr");
  const std::string base = "score --ref " + (d / "ref.exr").string() + " --test " + (d / "tech.exr").string() + " --out ";
  // mse is 0.01 (T - R = 0.1 everywhere).
  const CliRun pass = giq_run(base + (d / "p").string() + " --fail 'mse<=0.02' --fail 'ssim>=0.1'", d);
  EXPECT_EQ(pass.code, 0) << pass.out << pass.err;
  EXPECT_NE(pass.out.find("PASS"), std::string::npos);
  const CliRun warn = giq_run(base + (d / "w").string() + " --fail 'mse<=0.02' --warn 'mse<=0.005'", d);
  EXPECT_EQ(warn.code, 0) << warn.out;
  EXPECT_NE(warn.out.find("WARN"), std::string::npos);
  const CliRun fail = giq_run(base + (d / "f").string() + " --fail 'mse<=0.005' --fail 'psnr>=10'", d);
  EXPECT_EQ(fail.code, 1) << fail.out;
  EXPECT_NE(fail.out.find("mse <= 0.005"), std::string::npos) << fail.out;
  EXPECT_NE(fail.out.find("FAIL"), std::string::npos);
  const CliRun json_fail = giq_run(base + (d / "j").string() + " --fail 'mse<=0.005' --json", d);
  EXPECT_EQ(json_fail.code, 1);
  EXPECT_EQ(json::parse(json_fail.out)["bounds"][0]["status"], "FAIL");
}

// An engine's indirect-only buffer, saved as its image's beauty, against the reference's
// indirect layer; a region of both; an alpha channel, which is ignored.
TEST(ScoreCli, SeparateLayersCropAndAlpha) {
  const fs::path d = fresh_dir("layers");
  const image::Image ref = reference();
  image::write_exr(ref, d / "ref.exr");
  image::Image engine = test::rgb_image(W, H, [&](int x, int y, int k) {
    const float v = ref.at(k == 0 ? "indirect.R" : k == 1 ? "indirect.G" : "indirect.B", x, y);
    return x < 4 ? v + 1.0f : v;  // wrong in the first four columns only
  });
  engine.add_channel("A", 0.25f);
  image::write_exr(engine, d / "engine.exr");
  const std::string base = "score --ref " + (d / "ref.exr").string() + " --test " + (d / "engine.exr").string() +
                           " --ref-layer indirect --json --out ";
  const CliRun whole = giq_run(base + (d / "whole").string(), d);
  ASSERT_EQ(whole.code, 0) << whole.err;
  const json jw = json::parse(whole.out);
  EXPECT_NEAR(jw["metrics"]["mae"]["value"].get<double>(), 4.0 / W, 1e-6);  // 1 in 4 of W columns
  EXPECT_EQ(jw["inputs"]["layer"], "indirect");
  EXPECT_EQ(jw["inputs"]["test_layer"], "beauty");
  const CliRun cropped = giq_run(base + (d / "crop").string() + " --crop 4,2,12,10", d);
  ASSERT_EQ(cropped.code, 0) << cropped.err;
  const json jc = json::parse(cropped.out);
  EXPECT_EQ(jc["metrics"]["mse"]["value"].get<double>(), 0.0);
  EXPECT_EQ(jc["inputs"]["width"], 12);
  EXPECT_EQ(jc["inputs"]["height"], 10);
  EXPECT_EQ(jc["inputs"]["crop"], json({4, 2, 12, 10}));
}

// docs/own-engine.md's worked example, step by step with a cheaper reference (64 paths per
// pixel instead of 1024): the engine's tone-mapped PNG scores without a warning under its
// display transform and at less than half the FLIP it gets without one (which warns that an
// LDR image meets an HDR reference), and the engine's linear EXR needs no transform.
TEST(ScoreCli, TheOwnEngineExampleScoresAsItsPageSays) {
  const fs::path d = fresh_dir("own_engine");
  const fs::path ex = fs::path(GIQ_SOURCE_DIR) / "docs" / "examples" / "own-engine";
  const CliRun ref = giq_run("reference --scene " + (fs::path(GIQ_SOURCE_DIR) / "scenes" / "cornell.gltf").string() +
                                 " --camera eye=0.278,0.273,0.8 target=0.278,0.273,-0.28 fov=39.31 frame=unity"
                                 " --width 320 --height 240 --spp 64 --out " + (d / "ref.exr").string(),
                             d);
  ASSERT_EQ(ref.code, 0) << ref.err;
  auto score = [&](const std::string& test, const std::string& options, const std::string& out) {
    const CliRun r = giq_run("score --ref " + (d / "ref.exr").string() + " --test " + (ex / test).string() + " " +
                                 options + " --out " + (d / out).string() + " --json",
                             d);
    EXPECT_EQ(r.code, 0) << r.err;
    return json::parse(r.out);
  };
  const json shown = score("screenshot-aces.png", "--tonemap aces --exposure 1 --test-encoding srgb", "aces");
  EXPECT_EQ(shown["warnings"], json::array()) << shown["warnings"];
  const double ratio = shown["metrics"]["mean_luminance_ratio"].get<double>();
  EXPECT_TRUE(ratio >= 0.8 && ratio <= 1.25) << ratio;
  const json raw = score("screenshot-aces.png", "", "raw");
  ASSERT_FALSE(raw["warnings"].empty());
  EXPECT_NE(raw["warnings"][0].get<std::string>().find("low-dynamic-range"), std::string::npos);
  EXPECT_LT(shown["metrics"]["flip"]["mean"]["value"].get<double>(),
            0.5 * raw["metrics"]["flip"]["mean"]["value"].get<double>());
  const json linear = score("lighting-linear.exr", "", "linear");
  EXPECT_EQ(linear["warnings"], json::array()) << linear["warnings"];
  EXPECT_EQ(linear["inputs"]["dynamic_range"], "hdr");
  fs::remove_all(d);
}

// The per-pixel z-test: a test image that is the reference plus noise of exactly the
// reference's standard deviation (standard normal deviates from Box-Muller on a fixed hash)
// passes at the 1 % level after the Šidák correction; the same image with one value moved by
// 8 sigma fails it. The reported p is the one computed here from the largest |z|.
TEST(ScoreCli, PerPixelZTestWithSidakCorrection) {
  const fs::path d = fresh_dir("ztest");
  const image::Image ref = reference();  // variance 1e-6 in every channel
  image::write_exr(ref, d / "ref.exr");
  const double sigma = 1e-3;
  auto normal = [](int x, int y, int k) {
    const double u1 = std::max(1e-12, double(test::hash01(x, y, k, 7))), u2 = test::hash01(x, y, k, 8);
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * 3.14159265358979323846 * u2);
  };
  const char* rgb[3] = {"R", "G", "B"};
  image::Image noisy = test::rgb_image(W, H, [&](int x, int y, int k) { return float(ref.at(rgb[k], x, y) + sigma * normal(x, y, k)); });
  image::write_exr(noisy, d / "noisy.exr");
  double max_z = 0.0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      for (int k = 0; k < 3; ++k)
        max_z = std::max(max_z, std::abs(double(noisy.at(rgb[k], x, y)) - double(ref.at(rgb[k], x, y))) /
                                    std::sqrt(double(ref.at(std::string("variance.") + rgb[k], x, y))));
  const double n = 3.0 * W * H, p = 1.0 - std::pow(1.0 - std::erfc(max_z / std::sqrt(2.0)), n);
  ASSERT_GT(p, 0.01) << "the fixed noise sample is itself an outlier; pick other hash seeds";
  const CliRun pass = giq_run("score --ref " + (d / "ref.exr").string() + " --test " + (d / "noisy.exr").string() +
                                  " --fail 'ztest_p>=0.01' --json --out " + (d / "pass").string(), d);
  EXPECT_EQ(pass.code, 0) << pass.err;
  const json jp = json::parse(pass.out)["metrics"]["ztest"];
  EXPECT_EQ(jp["tested"].get<double>(), n);
  // float images: z carries a relative rounding of ~1e-7 / 1e-3 per value.
  EXPECT_NEAR(jp["max_abs_z"].get<double>(), max_z, 1e-3);
  EXPECT_NEAR(jp["p_sidak"]["value"].get<double>(), p, 1e-3);

  image::Image biased = noisy;
  biased.channel("G")[biased.index(3, 4)] = float(ref.at("G", 3, 4) + 8.0 * sigma);
  image::write_exr(biased, d / "biased.exr");
  const CliRun fail = giq_run("score --ref " + (d / "ref.exr").string() + " --test " + (d / "biased.exr").string() +
                                  " --fail 'ztest_p>=0.01' --json --out " + (d / "fail").string(), d);
  EXPECT_EQ(fail.code, 1) << fail.err;
  EXPECT_LT(json::parse(fail.out)["metrics"]["ztest"]["p_sidak"]["value"].get<double>(), 1e-9);
}
