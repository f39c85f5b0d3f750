// `giq score` end to end on small synthetic EXRs written here: metrics, maps and strip, bad
// input, sequences, leak regions, PNG pairs, replacing a score, paths relative to metrics.json.
// Images from outside giq (display transforms, warnings, bounds, layers, the z-test) are in
// score_outside_test.cpp.

#include <gtest/gtest.h>
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>

#include "giq/image/io.h"
#include "giq/image/srgb.h"
#include "giq/metrics/catalogue.h"
#include "giq/scenes/scene.h"
#include "score_cli.h"
#include "support/subprocess.h"
#include "synthetic.h"

using namespace giq;
using namespace giq::test::score_cli;
using nlohmann::json;
namespace fs = std::filesystem;

TEST(MetricCatalogue, NamesAreUniqueAndEachIsDefinedInTheDocs) {
  std::ifstream in(std::string(GIQ_SOURCE_DIR) + "/docs/metrics.md");
  ASSERT_TRUE(in);
  std::set<std::string> anchors;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("#", 0) != 0) continue;
    // GitHub's anchor of a heading: lower case, letters, digits, spaces as '-', '-' and '_'.
    std::string a;
    for (char ch : line.substr(line.find_first_not_of('#')))
      if (std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_') a += char(std::tolower(ch));
      else if (ch == ' ') a += '-';
    anchors.insert(a.substr(a.find_first_not_of('-')));
  }
  std::set<std::string_view> names;
  for (const metrics::MetricInfo& m : metrics::kMetricCatalogue) {
    EXPECT_TRUE(names.insert(m.name).second) << m.name;
    EXPECT_TRUE(anchors.count(std::string(m.anchor))) << m.name << ": no section #" << m.anchor << " in docs/metrics.md";
    EXPECT_EQ(metrics::find_metric_info(m.name), &m);
  }
  EXPECT_EQ(metrics::better_direction("psnr"), metrics::Better::Higher);
  EXPECT_EQ(metrics::better_direction("last_frame.metrics.ssim"), metrics::Better::Higher);
  EXPECT_EQ(metrics::better_direction("leak.declared.leak"), metrics::Better::Lower);
}

TEST(ScoreCli, SingleImageWritesMetricsMapsAndStrip) {
  const fs::path d = fresh_dir("single");
  image::Image ref = reference();
  image::Image tech = test::rgb_image(W, H, [&](int x, int y, int k) { return ref.at(k == 0 ? "R" : k == 1 ? "G" : "B", x, y) + 0.1f; });
  test::add_layer(tech, "indirect", [&](int x, int y, int k) {
    return ref.at(k == 0 ? "indirect.R" : k == 1 ? "indirect.G" : "indirect.B", x, y);
  });
  tech.channel("G")[5] = std::nanf("");
  image::write_exr(ref, d / "ref.exr");
  image::write_exr(tech, d / "tech.exr");

  const CliRun r = giq_run("score --ref " + (d / "ref.exr").string() + " --test " + (d / "tech.exr").string() +
                            " --out " + (d / "out").string() + " --json",
                        d);
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  const json& m = j["metrics"];
  EXPECT_EQ(m["nonfinite_pixels"], 1);
  EXPECT_EQ(m["valid_pixels"], W * H - 1);
  // T - R = 0.1 in float: (0.1 +- 3e-8)^2.
  EXPECT_NEAR(m["mse"]["value"].get<double>(), 0.01, 1e-8);
  EXPECT_EQ(m["mse"]["definition"], "mse");
  EXPECT_EQ(m["mse"]["inputs"][0], "reference:beauty");
  EXPECT_FALSE(m["mse"]["unresolved"].get<bool>());  // 0.01 >> 3e-6
  EXPECT_NEAR(m["noise_floor"]["value"].get<double>(), 1e-6, 1e-12);
  const double flip = m["flip"]["mean"]["value"].get<double>();
  EXPECT_GT(flip, 0.0);
  EXPECT_LT(flip, 1.0);
  EXPECT_EQ(j["inputs"]["dynamic_range"], "hdr");
  // Every per-image metric of the catalogue is where the catalogue says, in its unit.
  for (const metrics::MetricInfo& info : metrics::kMetricCatalogue) {
    if (info.scope != metrics::Scope::Image) continue;
    bool found = false;
    for (std::string_view path : info.paths) {
      if (path.empty()) continue;
      const json::json_pointer pointer("/" + std::regex_replace(std::string(path), std::regex("\\."), "/"));
      if (!m.contains(pointer)) continue;
      found = true;
      const json& v = m[pointer];
      if (v.is_object()) EXPECT_EQ(v["unit"], std::string(info.unit)) << info.name;
    }
    EXPECT_TRUE(found) << info.name << " is not in metrics.json";
  }
  const fs::path out = d / "out";
  for (const char* f : {"metrics.json", "abs_error.exr", "abs_error.png", "relative_error.exr", "relative_error.png",
                        "signed_luminance_error.exr", "signed_luminance_error.png", "leak.exr", "leak.png",
                        "flip.exr", "flip.png", "strip.png"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  EXPECT_EQ(json::parse(std::ifstream(out / "metrics.json")), j);
  // The signed map's scale is in its PNG and in metrics.json.
  const auto png = image::read_image(out / "signed_luminance_error.png");
  EXPECT_EQ(png.metadata.at("giq:colormap"), "blue-white-red");
  EXPECT_NEAR(std::stod(png.metadata.at("giq:range_max")), j["maps"]["signed_luminance_error"]["range"][1].get<double>(),
              1e-6);
  const auto strip = image::read_image(out / "strip.png");
  EXPECT_EQ(strip.width(), 3 * W);
  EXPECT_EQ(strip.height(), H);

  // The indirect layer is identical: zero error, psnr reported as "inf", SSIM 1.
  const CliRun ind = giq_run("score --ref " + (d / "ref.exr").string() + " --test " + (d / "tech.exr").string() +
                              " --layer indirect --out " + (d / "out_ind").string() + " --json",
                          d);
  ASSERT_EQ(ind.code, 0) << ind.err;
  const json ji = json::parse(ind.out);
  EXPECT_EQ(ji["metrics"]["mse"]["value"], 0.0);
  EXPECT_EQ(ji["metrics"]["psnr"]["value"], "inf");
  EXPECT_NEAR(ji["metrics"]["ssim"]["value"].get<double>(), 1.0, 1e-12);
  EXPECT_EQ(ji["metrics"]["flip"]["mean"]["value"], 0.0);
  EXPECT_EQ(ji["inputs"]["variance_layer"], "variance");

  // Human table on stdout without --json.
  const CliRun table = giq_run("score --ref " + (d / "ref.exr").string() + " --test " + (d / "tech.exr").string() +
                                " --out " + (d / "out_t").string(),
                            d);
  ASSERT_EQ(table.code, 0) << table.err;
  EXPECT_NE(table.out.find("mse"), std::string::npos);
  EXPECT_NE(table.out.find("flip mean"), std::string::npos);
}

TEST(ScoreCli, BadInputExitsTwoWithOneLine) {
  const fs::path d = fresh_dir("bad");
  image::Image ref = reference();
  image::write_exr(ref, d / "ref.exr");
  image::write_exr(test::rgb_image(W + 1, H, [](int, int, int) { return 0.5f; }), d / "wide.exr");
  image::write_exr(test::rgb_image(W, H, [](int, int, int) { return 0.5f; }), d / "beauty_only.exr");
  fs::create_directories(d / "o");
  image::write_exr(test::rgb_image(W, H, [](int, int, int) { return 0.25f; }), d / "o" / "abs_error.exr");
  const std::string clobber_before = test::slurp(d / "o" / "abs_error.exr");
  struct Case {
    std::string args, must_name;
  };
  const std::string base = "score --ref " + (d / "ref.exr").string() + " --out " + (d / "o").string() + " --test ";
  const Case cases[] = {
      {base + (d / "wide.exr").string(), "wide.exr"},                                // size mismatch
      {base + (d / "beauty_only.exr").string() + " --layer indirect", "indirect"},   // missing layer
      {base + (d / "missing.exr").string(), "missing.exr"},                          // no such file
      {base + (d / "ref.exr").string() + " --frames 3", "--frames"},                  // bad frames
      {base + (d / "ref.exr").string() + " --step-frame -7", "--step-frame"},         // was ignored
      {base + (d / "ref.exr").string() + " --crop 20,0,10,4", "--crop"},              // beyond the image
      {base + (d / "ref.exr").string() + " --crop 1,2,3", "--crop"},                  // not x,y,w,h
      {base + (d / "ref.exr").string() + " --tonemap filmic", "--tonemap"},           // no such curve
      {base + (d / "ref.exr").string() + " --test-encoding linear", "--test-encoding"},  // an EXR is linear
      {base + (d / "ref.exr").string() + " --fail relmse", "--fail"},                 // no level
      {base + (d / "ref.exr").string() + " --fail 'mse<=0.1' --warn 'mse<=0.2'", "--warn"},  // warn beyond fail
      {base + (d / "ref.exr").string() + " --fail 'relmsee<=0.1'", "relmsee"},          // no such metric
      {base + (d / "ref.exr").string() + " --test-layer direct", "direct"},           // the test has no such layer
      {base + (d / "ref.exr").string() + " --tonemp aces", "did you mean '--tonemap'"},  // a typo in an option
      {base + (d / "ref.exr").string() + " --fail 'flip_maen<=1'", "did you mean 'flip_mean'"},  // in a metric
      // An input inside the output folder, where the maps would replace it.
      {"score --ref " + (d / "ref.exr").string() + " --test " + (d / "o" / "abs_error.exr").string() + " --out " +
           (d / "o").string(),
       "abs_error.exr"},
  };
  for (const auto& c : cases) {
    const CliRun r = giq_run(c.args, d);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.must_name), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  EXPECT_EQ(test::slurp(d / "o" / "abs_error.exr"), clobber_before);
}

// A light switches on at frame t0 over the left half (Y 0.1 -> 1.0); the technique follows
// with its error halving every frame: r_t = 0.9 * 2^-(t-t0). ref_%04d.exr and tech_%04d.exr,
// frames 0 to frames - 1, in `d`.
void write_step_sequence(const fs::path& d, int frames, int t0) {
  char name[64];
  for (int t = 0; t < frames; ++t) {
    auto lit = [&](int x) { return x < W / 2 && t >= t0; };
    auto ref = test::rgb_image(W, H, [&](int x, int, int) { return lit(x) ? 1.0f : 0.1f; });
    test::add_layer(ref, "variance", [](int, int, int) { return 1e-8f; });
    const float lagging = t >= t0 ? 1.0f - 0.9f * std::ldexp(1.0f, -(t - t0)) : 0.1f;
    auto tech = test::rgb_image(W, H, [&](int x, int, int) { return x < W / 2 ? lagging : 0.1f; });
    std::snprintf(name, sizeof name, "ref_%04d.exr", t);
    image::write_exr(ref, d / name);
    std::snprintf(name, sizeof name, "tech_%04d.exr", t);
    image::write_exr(tech, d / name);
  }
}

TEST(ScoreCli, SequenceBiasFlickerAndLag) {
  const fs::path d = fresh_dir("sequence");
  const int frames = 12, t0 = 3;
  write_step_sequence(d, frames, t0);
  char name[64];
  std::ofstream(d / "timings.json") << R"({"frame_ms": {"median": 10.0, "mean": 11.0}})";
  const CliRun r = giq_run("score --ref '" + (d / "ref_%04d.exr").string() + "' --test '" +
                            (d / "tech_%04d.exr").string() + "' --frames 0:11 --timings " +
                            (d / "timings.json").string() + " --out " + (d / "out").string() + " --json",
                        d);
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  const json& q = j["sequence"];
  EXPECT_EQ(q["frames"], frames);
  EXPECT_EQ(q["lag"]["step_frame"], t0);
  EXPECT_EQ(q["lag"]["region_pixels"], W / 2 * H);
  // r_inf = 0.9 (2^-6 + 2^-7 + 2^-8) / 3 = 0.0082; threshold 0.0974; 0.9 * 2^-4 = 0.056 is the
  // first below it: 4 frames, 40 ms.
  EXPECT_NEAR(q["lag"]["r_inf"].get<double>(), 0.9 * (0.015625 + 0.0078125 + 0.00390625) / 3.0, 1e-6);
  EXPECT_EQ(q["lag90_frames"]["value"], 4);
  EXPECT_NEAR(q["lag90_ms"]["value"].get<double>(), 40.0, 1e-9);
  // Decomposition: mse_seq = bias2 + variance over the left half's errors.
  EXPECT_NEAR(q["mse_seq"]["value"].get<double>(),
              q["bias2"]["value"].get<double>() + q["variance"]["value"].get<double>(), 1e-12);
  EXPECT_GT(q["flicker"]["value"].get<double>(), 0.0);
  EXPECT_TRUE(fs::exists(d / "out" / "temporal_stddev.png"));
  EXPECT_TRUE(fs::exists(d / "out" / "flip.exr"));  // the last frame's full score
  EXPECT_EQ(j["per_frame"].size(), size_t(frames));

  // One reference for a static scene: the technique that flickers by +-0.05 around the truth.
  auto still = test::rgb_image(W, H, [](int, int, int) { return 0.5f; });
  image::write_exr(still, d / "still.exr");
  for (int t = 0; t < 4; ++t) {
    std::snprintf(name, sizeof name, "flick_%02d.exr", t);
    image::write_exr(test::rgb_image(W, H, [&](int, int, int) { return t % 2 ? 0.45f : 0.55f; }), d / name);
  }
  const CliRun s = giq_run("score --ref " + (d / "still.exr").string() + " --test '" + (d / "flick_%02d.exr").string() +
                            "' --frames 0:3 --out " + (d / "out_still").string() + " --json",
                        d);
  ASSERT_EQ(s.code, 0) << s.err;
  const json js = json::parse(s.out);
  // e = +-0.05: bias 0, variance 0.0025, flicker = 0.05 / 0.5.
  EXPECT_NEAR(js["sequence"]["bias2"]["value"].get<double>(), 0.0, 1e-12);
  EXPECT_NEAR(js["sequence"]["variance"]["value"].get<double>(), 0.0025, 1e-8);
  EXPECT_NEAR(js["sequence"]["flicker"]["value"].get<double>(), 0.1, 1e-6);
  EXPECT_GT(js["sequence"]["temporal_flip"]["value"].get<double>(), 0.0);
  EXPECT_TRUE(js["sequence"]["lag"]["value_frames"].is_null());
}

// A step frame the scene declares (extras.giq.sequence.step_frame) is lag's t0 where the scored
// frames hold it, though the reference changes most at another frame; a given --step-frame
// comes first, and frames without the declared step detect theirs.
TEST(ScoreCli, LagTakesTheStepTheSceneDeclares) {
  const fs::path d = fresh_dir("declared_step");
  write_step_sequence(d, 12, 3);
  json scene = json::parse(test::slurp(fs::path(GIQ_SCENES_DIR) / "movinglight.gltf"));
  scene["extras"]["giq"]["sequence"]["step_frame"] = 2;
  scene["extras"]["giq"]["sequence"]["lag_frames"] = "1:11";
  scene["extras"]["giq"]["sequence"]["flicker_frames"] = "0:1";
  std::ofstream(d / "scene.gltf") << scene.dump();
  auto lag = [&](const std::string& extra, const std::string& out) {
    const CliRun r = giq_run("score --ref '" + (d / "ref_%04d.exr").string() + "' --test '" + (d / "tech_%04d.exr").string() +
                                 "' --scene " + (d / "scene.gltf").string() + " " + extra + " --out " + (d / out).string() +
                                 " --json",
                             d);
    EXPECT_EQ(r.code, 0) << r.err;
    return r.code == 0 ? json::parse(r.out)["sequence"]["lag"] : json();
  };
  const json declared = lag("--frames 0:11", "declared");
  EXPECT_EQ(declared["step_frame"], 2);
  EXPECT_NE(declared["step_frame_source"].get<std::string>().find("declared by the scene"), std::string::npos);
  const json given = lag("--frames 0:11 --step-frame 3", "given");
  EXPECT_EQ(given["step_frame"], 3);
  EXPECT_EQ(given["step_frame_source"], "given");
  const json detected = lag("--frames 2:11", "detected");  // a step at frame 2 has no frame before it here
  EXPECT_EQ(detected["step_frame_source"].get<std::string>().rfind("detected", 0), 0u);
}

TEST(ScoreCli, DeclaredLeakRegionsFromTheScene) {
  // The built-in leak scene declares room B's surfaces as leak regions; their object ids are
  // what the reference's objectId channel holds there.
  const scenes::Scene scene = scenes::load(fs::path(GIQ_SCENES_DIR) / "leak.gltf");
  ASSERT_FALSE(scene.leak_object_ids.empty());
  const float leak_id = float(scene.leak_object_ids.front());
  const fs::path d = fresh_dir("declared");
  // Left half: a leak-region surface, dark in the truth (0.001); right half: lit room (1.0),
  // object id 1000 (no such object). The technique adds 0.05 on the leak surface.
  auto ref = test::rgb_image(W, H, [](int x, int, int) { return x < W / 2 ? 0.001f : 1.0f; });
  float* id = ref.add_channel("objectId");
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) id[ref.index(x, y)] = x < W / 2 ? leak_id : 1000.0f;
  auto tech = test::rgb_image(W, H, [](int x, int, int) { return x < W / 2 ? 0.051f : 1.0f; });
  image::write_exr(ref, d / "ref.exr");
  image::write_exr(tech, d / "tech.exr");
  const CliRun r = giq_run("score --ref " + (d / "ref.exr").string() + " --test " + (d / "tech.exr").string() +
                               " --scene " + (fs::path(GIQ_SCENES_DIR) / "leak.gltf").string() + " --out " +
                               (d / "out").string() + " --json",
                           d);
  ASSERT_EQ(r.code, 0) << r.err;
  const json leak = json::parse(r.out)["metrics"]["leak"];
  const double n = W / 2 * H, sum_y = n * double(0.001f) + n * 1.0;
  // excess = 0.051 - 0.001 = 0.05 per region pixel (float luminance maths: 1e-6 relative).
  EXPECT_EQ(leak["declared"]["pixels"], int(n));
  EXPECT_NEAR(leak["declared"]["leak"]["value"].get<double>(), n * 0.05 / sum_y, 1e-6);
  EXPECT_EQ(leak["declared"]["leak_pixels"]["value"], 1.0);
  // The dark half is also the automatic region (0.001 <= 0.05 x 0.5005).
  EXPECT_NEAR(leak["automatic"]["leak"]["value"].get<double>(), n * 0.05 / sum_y, 1e-6);

  // Declared regions need the reference's objectId channel.
  ref.remove_channel("objectId");
  image::write_exr(ref, d / "ref_noid.exr");
  const CliRun bad = giq_run("score --ref " + (d / "ref_noid.exr").string() + " --test " +
                                 (d / "tech.exr").string() + " --scene " +
                                 (fs::path(GIQ_SCENES_DIR) / "leak.gltf").string() + " --out " + (d / "o2").string(),
                             d);
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("objectId"), std::string::npos) << bad.err;
}

TEST(ScoreCli, PngPairIsScoredAsLdr) {
  const fs::path d = fresh_dir("ldr");
  // 8-bit codes 188 and 128 (linear 0.5029 and 0.2159 after decoding) everywhere.
  image::write_png(test::rgb_image(W, H, [](int, int, int) { return 0.5f; }), d / "ref.png");
  image::write_png(test::rgb_image(W, H, [](int, int, int) { return 0.2159f; }), d / "tech.png");
  const CliRun r = giq_run("score --ref " + (d / "ref.png").string() + " --test " + (d / "tech.png").string() +
                               " --out " + (d / "out").string() + " --json",
                           d);
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["inputs"]["dynamic_range"], "ldr");
  const double diff = image::srgb_decode(188.0f / 255.0f) - image::srgb_decode(128.0f / 255.0f);
  EXPECT_NEAR(j["metrics"]["mse"]["value"].get<double>(), diff * diff, 1e-6);
  EXPECT_EQ(j["strip"]["exposure"], 0.0);
  EXPECT_GT(j["metrics"]["flip"]["mean"]["value"].get<double>(), 0.0);
}

TEST(ScoreCli, AScoreReplacesThePreviousOneAsAWholeAndAConcurrentOneIsRefused) {
  const fs::path d = fresh_dir("replace");
  image::write_exr(test::rgb_image(W, H, [](int, int, int) { return 0.5f; }), d / "still.exr");
  for (int t = 0; t < 3; ++t)
    image::write_exr(test::rgb_image(W, H, [&](int, int, int) { return t % 2 ? 0.45f : 0.55f; }),
                     d / ("flick_0" + std::to_string(t) + ".exr"));
  const fs::path out = d / "out";
  const std::string ref = " --ref " + (d / "still.exr").string() + " --out " + out.string();
  const CliRun seq = giq_run("score" + ref + " --test '" + (d / "flick_%02d.exr").string() + "' --frames 0:2", d);
  ASSERT_EQ(seq.code, 0) << seq.err;
  ASSERT_TRUE(fs::exists(out / "temporal_stddev.exr"));
  std::ofstream(out / "notes.txt") << "the user's";

  // A single-image score over it: the sequence's own map goes, the user's file stays, and the
  // folder holds exactly what the new metrics.json names.
  const CliRun single = giq_run("score" + ref + " --test " + (d / "flick_01.exr").string(), d);
  ASSERT_EQ(single.code, 0) << single.err;
  const json j = json::parse(test::slurp(out / "metrics.json"));
  EXPECT_FALSE(j.contains("sequence"));
  std::set<std::string> named{"metrics.json", "notes.txt", j["strip"]["png"].get<std::string>()};
  for (const auto& [name, m] : j["maps"].items()) named.insert({m["exr"].get<std::string>(), m["png"].get<std::string>()});
  std::set<std::string> present;
  for (const auto& e : fs::directory_iterator(out)) present.insert(e.path().filename().string());
  EXPECT_EQ(present, named);

  // While another writer holds the folder, a score is refused and changes nothing.
  const std::string before = test::slurp(out / "metrics.json");
  const int fd = ::open(out.c_str(), O_RDONLY | O_DIRECTORY);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX), 0);
  const CliRun refused = giq_run("score" + ref + " --test " + (d / "flick_00.exr").string(), d);
  ::close(fd);
  EXPECT_EQ(refused.code, 2);
  EXPECT_NE(refused.err.find("another giq process is writing to this folder"), std::string::npos) << refused.err;
  EXPECT_EQ(std::count(refused.err.begin(), refused.err.end(), '\n'), 1) << refused.err;
  EXPECT_EQ(test::slurp(out / "metrics.json"), before);
}

// metrics.json names its inputs relative to its own folder (schema version 2), so the folder
// of scores and inputs can be moved as a whole and reported from any working directory.
TEST(ScoreCli, InputPathsAreRelativeToMetricsJsonAndTheReportWorksFromAnywhere) {
  const fs::path d = fresh_dir("relative");
  const image::Image ref = reference();
  fs::create_directories(d / "work" / "engine");
  image::write_exr(ref, d / "work" / "ref.exr");
  image::write_exr(test::rgb_image(W, H, [&](int x, int y, int k) { return ref.at(k == 0 ? "R" : k == 1 ? "G" : "B", x, y) * 0.9f; }),
                   d / "work" / "engine" / "shot.exr");
  auto in_dir = [&](const fs::path& cwd, const std::string& args) {
    const std::string cmd = "cd " + test::shell_quote(cwd.string()) + " && " + test::shell_quote(GIQ_BINARY) + " " + args +
                            " >" + test::shell_quote((d / "out.txt").string()) + " 2>&1";
    return test::exit_code(std::system(cmd.c_str()));
  };
  ASSERT_EQ(in_dir(d / "work", "score --ref ref.exr --test engine/shot.exr --out scores/shot"), 0) << test::slurp(d / "out.txt");
  const json j = json::parse(test::slurp(d / "work" / "scores" / "shot" / "metrics.json"));
  EXPECT_EQ(j["schema_version"], 2);
  EXPECT_EQ(j["inputs"]["reference"], "../../ref.exr");
  EXPECT_EQ(j["inputs"]["test"], "../../engine/shot.exr");
  // The table still names them as typed.
  EXPECT_NE(test::slurp(d / "out.txt").find("engine/shot.exr  vs  ref.exr"), std::string::npos) << test::slurp(d / "out.txt");
  fs::rename(d / "work", d / "moved");
  ASSERT_EQ(in_dir("/", "report " + test::shell_quote((d / "moved" / "scores").string())), 0) << test::slurp(d / "out.txt");
  const std::string html = test::slurp(d / "moved" / "scores" / "report.html");
  size_t pngs = 0;
  for (size_t p = 0; (p = html.find("src=\"data:image/png;base64,", p)) != std::string::npos; ++p) ++pngs;
  EXPECT_GE(pngs, 3u);  // the reference, the test and at least one error map
}
