// `giq gate` and `giq golden update` end to end, with fake_giq standing in for the renderers
// and the scorer (--giq): bad configs exit 2 with one line, goldens are rendered once per
// scene/view/frames and recorded, a stale or missing golden is never used, a value over its
// bound fails with the right case and metric, crashes and missing frames fail their case only,
// identical reruns are reused, and the JUnit report parses.

#include <expat.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include "support/subprocess.h"
#include <sstream>

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using giq::test::slurp;

struct Result {
  int code = -1;
  std::string out, err;
};

class GateCli : public testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() / ("giq_gate_cli_" + std::to_string(::getpid()) + "_" +
                                     testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    ::setenv("FAKE_GIQ_LOG", (dir_ / "calls.log").c_str(), 1);
    ::setenv("FAKE_GIQ_BEHAVIOUR", (dir_ / "behaviour.json").c_str(), 1);
    ::unsetenv("FAKE_GIQ_DEVICE");
    behave(json::object());
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }

  void behave(const json& b) { std::ofstream(dir_ / "behaviour.json") << b.dump(); }

  void config(const json& cases) {
    json c = {{"version", 1},
              {"defaults",
               {{"scene", std::string(GIQ_SCENES_DIR) + "/cornell.gltf"},
                {"resolution", {16, 8}},
                {"golden", {{"spp", 32}, {"seed", 2}}}}},
              {"cases", cases}};
    std::ofstream(dir_ / "gate.json") << c.dump(2);
  }

  Result giq(const std::string& args) {
    const std::string cmd = std::string("cd ") + dir_.string() + " && " + GIQ_BINARY + " " + args +
                            " >out.txt 2>err.txt";
    Result r;
    r.code = giq::test::exit_code(std::system(cmd.c_str()));
    r.out = slurp(dir_ / "out.txt");
    r.err = slurp(dir_ / "err.txt");
    return r;
  }
  Result gate(const std::string& extra = "") {
    return giq(std::string("gate --config gate.json --out out --giq ") + FAKE_GIQ + " " + extra);
  }
  Result update(const std::string& extra = "") {
    return giq(std::string("golden update --config gate.json --giq ") + FAKE_GIQ + " " + extra);
  }

  // status of (case, metric) in gate.json
  std::string status(const std::string& c, const std::string& m) {
    const json g = json::parse(slurp(dir_ / "out" / "gate.json"));
    for (const auto& o : g["outcomes"])
      if (o["case"] == c && o["metric"] == m)
        return o["status"].get<std::string>() + " " + o["message"].get<std::string>();
    return "absent";
  }

  int calls(const std::string& needle) {
    std::ifstream in(dir_ / "calls.log");
    int n = 0;
    for (std::string line; std::getline(in, line);) n += line.find(needle) != std::string::npos;
    return n;
  }

  fs::path dir_;
};

TEST_F(GateCli, BadConfigExitsTwoWithOneLine) {
  std::ofstream(dir_ / "gate.json")
      << R"({"version": 1, "cases": [{"name": "a", "scene": "s", "technique": "t",
      "bounds": {"flip_mean": {"fail": 0.1, "warn": 0.3}}}]})";
  for (const Result& r : {gate(), update()}) {
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("cases[0].bounds.flip_mean.warn"), std::string::npos) << r.err;
  }
  EXPECT_EQ(giq("gate --config absent.json").code, 2);
  config(json::array({{{"name", "a"}, {"technique", "t"}, {"bounds", {{"relmse", 1}}}}}));
  const Result r = gate("--only 'zzz*'");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("matches no case"), std::string::npos) << r.err;
  // --out under a regular file, or the folder holding the config: refused before any case runs
  // (the first was an internal error).
  std::ofstream(dir_ / "a_file") << "x";
  for (const std::string& out : {std::string("a_file/out"), std::string(".")}) {
    const Result o = giq(std::string("gate --config gate.json --out ") + out + " --giq " + FAKE_GIQ);
    EXPECT_EQ(o.code, 2) << out << ": " << o.err;
    EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
  }
  EXPECT_EQ(calls("realtime"), 0);
}

TEST_F(GateCli, ProvesTheGateCanFail) {
  config(json::array({
      {{"name", "good"},
       {"technique", "direct"},
       {"parameters", {{"pcf_radius", 2}}},
       {"bounds",
        {{"relmse", {{"fail", 0.05}, {"warn", 0.02}}},
         {"gpu_ms", {{"fail", 1}, {"device", "H100"}}}}}},
      {{"name", "bright"},
       {"technique", "direct"},
       {"bounds", {{"flip_mean", 0.1}, {"relmse", 0.05}}}},
      {{"name", "noframes"}, {"technique", "pt"}, {"bounds", {{"relmse", 0.05}}}},
      {{"name", "crash"}, {"technique", "pt"}, {"bounds", {{"relmse", 0.05}}}},
      {{"name", "noisy"}, {"technique", "pt"}, {"bounds", {{"relmse", 0.005}}}},
  }));
  behave({{"bright",
           {{"metrics", {{"flip", {{"mean", {{"value", 0.3}}}}}, {"relmse", {{"value", 0.01}}}}}}},
          {"noframes", {{"realtime", "no-frames"}}},
          {"crash", {{"score", "crash"}}},
          {"noisy", {{"metrics", {{"relmse", {{"value", 0.01}, {"unresolved", true}}}}}}}});

  // No golden yet: every case fails and says what to run; nothing is scored.
  Result r = gate();
  EXPECT_EQ(r.code, 1) << r.out << r.err;
  EXPECT_NE(status("good", "relmse").find("giq golden update"), std::string::npos)
      << status("good", "relmse");
  EXPECT_EQ(calls("score"), 0);

  r = update("--jobs 2");
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_EQ(calls("reference"), 1);  // one golden serves every case of the same scene, view, frames
  const json manifest = json::parse(slurp(dir_ / "refs" / "manifest.json"));
  const json& e = manifest["goldens"]["cornell_0_f0-0"];
  EXPECT_EQ(e["spp"], 32);
  EXPECT_EQ(e["giq_version"], "fake-reference");
  EXPECT_EQ(e["settings"]["resolution"], json::array({16, 8}));
  EXPECT_EQ(e["files"].size(), 1u);
  EXPECT_EQ(e["scene_hash"].get<std::string>().size(), 16u);
  EXPECT_EQ(fs::path(e["scene"].get<std::string>()).filename(),
            "cornell.gltf");  // relative to the config
  EXPECT_EQ(update().code, 0);
  EXPECT_EQ(calls("reference"), 1);  // fresh: not rendered again

  r = gate("--jobs 3");
  EXPECT_EQ(r.code, 1) << r.out << r.err;
  EXPECT_EQ(status("good", "relmse").rfind("PASS", 0), 0u);
  EXPECT_EQ(status("good", "gpu_ms").rfind("SKIP", 0), 0u)
      << status("good", "gpu_ms");  // llvmpipe, not H100
  EXPECT_EQ(status("bright", "flip_mean").rfind("FAIL flip_mean = 0.3", 0), 0u)
      << status("bright", "flip_mean");
  EXPECT_EQ(status("bright", "relmse").rfind("PASS", 0), 0u);
  EXPECT_NE(status("noframes", "relmse").find("did not write"), std::string::npos)
      << status("noframes", "relmse");
  EXPECT_NE(status("crash", "relmse").find("giq score failed (exit 134"), std::string::npos)
      << status("crash", "relmse");
  EXPECT_EQ(status("noisy", "relmse").rfind("UNRESOLVED", 0), 0u);
  EXPECT_NE(r.out.find("FAILED"), std::string::npos);

  // The orchestration's arguments: parameters, frames after warm-up, the timing run.
  EXPECT_EQ(calls("realtime --scene"), 5 + 1);
  EXPECT_EQ(calls("--param pcf_radius=2"), 2);
  EXPECT_EQ(calls("--no-images --warmup 10 --frames 20"), 1);
  EXPECT_EQ(calls("--warmup 0 --frames 1 --out"), 5);
  EXPECT_EQ(calls("--layer beauty --scene"), 4);  // every case whose frames exist is scored

  // JUnit: well-formed, one testcase per case and metric, failures where the table says.
  const std::string xml = slurp(dir_ / "out" / "gate-report.xml");
  XML_Parser p = XML_ParserCreate("UTF-8");
  EXPECT_EQ(XML_Parse(p, xml.data(), int(xml.size()), 1), XML_STATUS_OK) << xml;
  XML_ParserFree(p);
  EXPECT_NE(
      xml.find(
          "<testsuites name=\"giq gate\" tests=\"7\" failures=\"2\" errors=\"2\" skipped=\"1\""),
      std::string::npos)
      << xml;
  EXPECT_NE(xml.find("<testcase classname=\"giq.gate.bright\" name=\"flip_mean\""),
            std::string::npos);
  // A crash and missing frames are errors (no verdict on the technique), not failures; every
  // testcase carries its share of its case's time.
  EXPECT_NE(xml.find("<error message=\"ERROR: the case could not be rendered or scored, so relmse (bound &lt;= 0.05) "
                     "has no value: score: giq score failed (exit 134"),
            std::string::npos)
      << xml;
  EXPECT_EQ(xml.find("time=\"0\""), std::string::npos) << xml;
  EXPECT_NE(slurp(dir_ / "out" / "gate-summary.md").find("| bright | flip_mean | 0.3 |"),
            std::string::npos);
  EXPECT_TRUE(fs::exists(dir_ / "out" / "cases" / "bright" / "score" /
                         "metrics.json"));  // kept beside the report

  // Only the passing case: exit 0, and its identical outputs are reused, not rendered again.
  const int before = calls("realtime --scene");
  r = gate("--only good");
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_EQ(calls("realtime --scene"), before);
  r = gate("--only good --rerender");
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(calls("realtime --scene"), before + 2);

  // A golden edited after the update is stale and never used.
  std::ofstream(dir_ / "refs" / "cornell_0_f0-0" / "frame_0000.exr", std::ios::app) << "x";
  r = gate("--only good");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(status("good", "relmse").find("modified"), std::string::npos)
      << status("good", "relmse");
}

// The real giq score on fake images: identical images give errors that the reference's
// variance cannot resolve (UNRESOLVED, within bound), a brightened quarter fails flip_mean and
// relmse with the right case and metric.
TEST_F(GateCli, RealScoreOfABrightenedRegionFails) {
  ::setenv("FAKE_GIQ_REAL", GIQ_BINARY, 1);
  config(json::array({{{"name", "same"},
                       {"technique", "direct"},
                       {"bounds", {{"flip_mean", 0.05}, {"relmse", 0.01}}}},
                      {{"name", "bright"},
                       {"technique", "direct"},
                       {"bounds", {{"flip_mean", 0.05}, {"relmse", 0.01}}}}}));
  behave({{"bright", {{"realtime", "brighten"}}}});
  ASSERT_EQ(update().code, 0);
  const Result r = gate();
  ::unsetenv("FAKE_GIQ_REAL");
  EXPECT_EQ(r.code, 1) << r.out << r.err;
  EXPECT_EQ(status("same", "flip_mean").rfind("PASS", 0), 0u) << status("same", "flip_mean");
  EXPECT_EQ(status("same", "relmse").rfind("UNRESOLVED", 0), 0u) << status("same", "relmse");
  EXPECT_EQ(status("bright", "flip_mean").rfind("FAIL", 0), 0u) << status("bright", "flip_mean");
  EXPECT_EQ(status("bright", "relmse").rfind("FAIL", 0), 0u) << status("bright", "relmse");
  const json g = json::parse(slurp(dir_ / "out" / "gate.json"));
  EXPECT_FALSE(g["passed"].get<bool>());
  EXPECT_TRUE(fs::exists(dir_ / "out" / "cases" / "bright" / "score" / "metrics.json"));
}

TEST_F(GateCli, SequenceCaseScoresEveryFrame) {
  config(json::array({{{"name", "seq"},
                       {"technique", "pt"},
                       {"frames", "2:4"},
                       {"view", "0"},
                       {"bounds", {{"flicker", 0.01}}}}}));
  behave({{"seq", {{"raw", {{"sequence", {{"flicker", {{"value", 0.02}}}}}}}}}});
  ASSERT_EQ(update().code, 0);
  for (int f = 2; f <= 4; ++f) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.exr", f);
    EXPECT_TRUE(fs::exists(dir_ / "refs" / "cornell_0_f2-4" / name)) << name;
  }
  const Result r = gate();
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(calls("--warmup 2 --frames 3"), 1);
  EXPECT_EQ(calls("--frames 2:4 --layer beauty"), 1);
  EXPECT_EQ(status("seq", "flicker").rfind("FAIL flicker = 0.02", 0), 0u)
      << status("seq", "flicker");
}

// A still golden: one image of the first frame, shared with the single-frame case, scored
// against every frame of the sequence; asked of an animated scene it is refused.
TEST_F(GateCli, StillGoldenServesEveryFrameOfAStaticScene) {
  config(json::array({{{"name", "one"}, {"technique", "pt"}, {"bounds", {{"relmse", 0.1}}}},
                      {{"name", "seq"},
                       {"technique", "pt"},
                       {"frames", "0:3"},
                       {"golden", {{"still", true}}},
                       {"bounds", {{"flicker", 0.03}}}}}));
  behave({{"seq", {{"raw", {{"sequence", {{"flicker", {{"value", 0.02}}}}}}}}}});
  ASSERT_EQ(update().code, 0);
  EXPECT_EQ(calls("reference"), 1);  // the two cases share one golden
  EXPECT_TRUE(fs::exists(dir_ / "refs" / "cornell_0_f0-0" / "frame_0000.exr"));
  EXPECT_FALSE(fs::exists(dir_ / "refs" / "cornell_0_f0-0" / "frame_0001.exr"));
  const Result r = gate();
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_EQ(calls("--warmup 0 --frames 4"), 1);
  EXPECT_EQ(calls("cornell_0_f0-0/frame_0000.exr --test"), 2);  // one image for the sequence too
  EXPECT_EQ(status("seq", "flicker").rfind("PASS", 0), 0u) << status("seq", "flicker");

  config(json::array({{{"name", "anim"},
                       {"scene", std::string(GIQ_SCENES_DIR) + "/movinglight.gltf"},
                       {"technique", "pt"},
                       {"frames", "28:31"},
                       {"golden", {{"still", true}}},
                       {"bounds", {{"flicker", 0.03}}}}}));
  const Result u = update();
  EXPECT_EQ(u.code, 1);
  EXPECT_NE(u.out.find("static scenes only"), std::string::npos) << u.out;
}

}  // namespace

// A case with image files from outside giq instead of a technique: scored against its golden
// with no render; a missing file is an error of that case. Typos in a technique's name, its
// parameters or the view stop the gate before any work (exit 2, one line).
TEST_F(GateCli, ImageFilesFromOutsideAreGatedAndConfigTyposStopIt) {
  config(json::array({
      {{"name", "engine"}, {"test", "shots/engine.exr"}, {"bounds", {{"relmse", 0.05}}}},
      {{"name", "missing"}, {"test", "shots/absent.exr"}, {"bounds", {{"relmse", 0.05}}}},
  }));
  ASSERT_EQ(update().code, 0);
  fs::create_directories(dir_ / "shots");
  fs::copy_file(dir_ / "refs" / "cornell_0_f0-0" / "frame_0000.exr", dir_ / "shots" / "engine.exr");
  const Result r = gate();
  EXPECT_EQ(r.code, 1) << r.out << r.err;
  EXPECT_EQ(status("engine", "relmse").rfind("PASS", 0), 0u) << status("engine", "relmse");
  EXPECT_NE(status("missing", "relmse").find("absent.exr"), std::string::npos) << status("missing", "relmse");
  EXPECT_EQ(calls("realtime --scene"), 0);
  EXPECT_EQ(calls("shots/engine.exr"), 1);
  const std::string xml = slurp(dir_ / "out" / "gate-report.xml");
  EXPECT_NE(xml.find("tests=\"2\" failures=\"0\" errors=\"1\""), std::string::npos) << xml;

  for (const json& typo : {json{{"name", "a"}, {"technique", "dirct"}, {"bounds", {{"relmse", 1}}}},
                           json{{"name", "a"}, {"technique", "direct"}, {"parameters", {{"pcf_radius", 9}}}, {"bounds", {{"relmse", 1}}}},
                           json{{"name", "a"}, {"technique", "direct"}, {"parameters", {{"pcf_raduis", 1}}}, {"bounds", {{"relmse", 1}}}},
                           json{{"name", "a"}, {"technique", "direct"}, {"view", "back"}, {"bounds", {{"relmse", 1}}}}}) {
    config(json::array({typo}));
    const Result t = gate();
    EXPECT_EQ(t.code, 2) << typo << t.err;
    EXPECT_EQ(std::count(t.err.begin(), t.err.end(), '\n'), 1) << t.err;
    EXPECT_NE(t.err.find("cases.a."), std::string::npos) << t.err;
    if (typo["technique"] == "dirct") EXPECT_NE(t.err.find("did you mean 'direct'"), std::string::npos) << t.err;
  }
  EXPECT_EQ(calls("realtime --scene"), 0);
}

// Cases with a camera in world coordinates instead of a view (an engine's camera, converted
// by frame=): the golden and the render get the same --camera, each camera its own golden,
// and a camera giq would refuse, or a view beside a camera, stops the gate before any work.
TEST_F(GateCli, CamerasInWorldCoordinates) {
  const std::string unity = "eye=0.278,0.273,0.8 target=0.278,0.273,-0.28 fov=39.31 frame=unity";
  const std::string gltf = "eye=0.278,0.273,-0.8 target=0.278,0.273,0.28 fov=39.31";
  config(json::array({{{"name", "unity"}, {"technique", "pt"}, {"camera", unity}, {"bounds", {{"relmse", 0.1}}}},
                      {{"name", "gltf"}, {"technique", "pt"}, {"camera", gltf}, {"bounds", {{"relmse", 0.1}}}}}));
  ASSERT_EQ(update().code, 0);
  EXPECT_EQ(calls("reference"), 2);  // two cameras, two goldens
  EXPECT_EQ(calls("--camera " + unity), 1);
  int goldens = 0;
  for (const auto& e : fs::directory_iterator(dir_ / "refs"))
    goldens += e.path().filename().string().rfind("cornell_camera-", 0) == 0;
  EXPECT_EQ(goldens, 2);
  const Result r = gate();
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_EQ(calls("realtime --scene " + std::string(GIQ_SCENES_DIR) + "/cornell.gltf --camera " + gltf), 1);

  config(json::array({{{"name", "bad"}, {"technique", "pt"}, {"camera", "eye=1,1,1 target=1,1,1"},
                       {"bounds", {{"relmse", 0.1}}}}}));
  Result bad = gate();
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("cases.bad.camera"), std::string::npos) << bad.err;
  config(json::array({{{"name", "both"}, {"technique", "pt"}, {"view", "0"}, {"camera", gltf},
                       {"bounds", {{"relmse", 0.1}}}}}));
  bad = gate();
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("a view or a camera, not both"), std::string::npos) << bad.err;
}

// A tone-mapped screenshot in a gate case: the case's "display" reaches giq score as its
// options, and a tone curve or encoding giq score would not know stops the gate at load.
TEST_F(GateCli, ScreenshotsAreScoredUnderTheCasesDisplayTransform) {
  config(json::array({{{"name", "shot"},
                       {"test", "shots/engine.exr"},
                       {"display", {{"tonemap", "aces"}, {"exposure", 1}, {"test_encoding", "srgb"}}},
                       {"bounds", {{"relmse", 0.05}}}}}));
  ASSERT_EQ(update().code, 0);
  fs::create_directories(dir_ / "shots");
  fs::copy_file(dir_ / "refs" / "cornell_0_f0-0" / "frame_0000.exr", dir_ / "shots" / "engine.exr");
  const Result r = gate();
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_EQ(calls("--tonemap aces --exposure 1 --test-encoding srgb"), 1);
  for (const json& display : {json{{"tonemap", "filmic"}}, json{{"test_encoding", "gamma"}}, json{{"gamma", 2.2}}}) {
    config(json::array({{{"name", "shot"}, {"test", "shots/engine.exr"}, {"display", display},
                         {"bounds", {{"relmse", 0.05}}}}}));
    const Result bad = gate();
    EXPECT_EQ(bad.code, 2) << display;
    EXPECT_NE(bad.err.find("display"), std::string::npos) << bad.err;
  }
}
