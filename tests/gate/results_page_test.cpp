// `giq results --page-only`: the page generated from a results.json written here, so its
// numbers and sentences are known exactly. `giq results --update` (with the fake giq of the
// gate tests doing the rendering): the page's other rows are kept, in order, and a page made
// with other settings is refused.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "support/subprocess.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// The indirect layer's numbers are the beauty's, but for its flicker when one is given.
json row(const std::string& scene, const std::string& technique, double flip, double relmse, json flicker,
         json indirect_flicker = nullptr) {
  const json layer = {{"flip_mean", flip}, {"relmse", relmse}, {"leak", nullptr}, {"leak_absolute", nullptr},
                      {"flicker", flicker}, {"lag90_frames", nullptr}};
  json indirect = layer;
  if (!indirect_flicker.is_null()) indirect["flicker"] = indirect_flicker;
  return {{"scene", scene},   {"technique", technique},
          {"device", "dev"},  {"gpu_ms", 1234.5},
          {"beauty", layer},  {"indirect", indirect},
          {"gpu_memory_mb", {{"scene", 1.0}, {"technique", 96.125}}}};
}

TEST(ResultsPage, NumbersAndComparisonsFromResultsJson) {
  const fs::path dir = fs::temp_directory_path() / ("giq_results_page_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  json results = {
      {"settings", {{"size", 64}, {"reference_spp", 16}, {"sequence_reference_spp", 4}, {"static_frames", 2}}},
      {"rows",
       {row("box", "direct", 0.5, 0.08, 7e-10), row("box", "better", 0.25, 0.02, 2e-9),
        row("box", "worse", 0.75, 0.1, 0.3, 0.6)}}};
  // The GPU machine's timings of one row: the column names its device and resolution, and
  // its memory replaces the local one.
  results["rows"][1]["gpu"] = {{"device", "GPU X"},
                               {"resolution", {1920, 1080}},
                               {"gpu_ms", 0.5},
                               {"gpu_memory_mb", {{"scene", 2.0}, {"technique", 12.5}}}};
  std::ofstream(dir / "results.json") << results.dump(1);
  const auto r = giq::test::run_captured(
      giq::test::shell_quote(GIQ_BINARY) + " results --page-only --doc " + (dir / "results.md").string(), dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string page = giq::test::slurp(dir / "results.md");
  // Three significant digits, large values without decimals, memory from the row.
  EXPECT_NE(page.find("| `direct` | 0.500 | 0.0800 | 0.500 | 0.0800 | – | – | 7.00e-10 | 7.00e-10 | – | 1234 | – | 96.1 |"),
            std::string::npos)
      << page;
  EXPECT_NE(page.find("| GPU ms (local) | GPU ms (GPU X, 1920×1080) | memory MB |"), std::string::npos) << page;
  EXPECT_NE(page.find("| `better` | 0.250 | 0.0200 | 0.250 | 0.0200 | – | – | 2.00e-09 | 2.00e-09 | – | 1234 | 0.500 | 12.5 |"),
            std::string::npos)
      << page;
  EXPECT_NE(page.find("- FLIP of the beauty: `better` is better than `direct` (0.250 vs 0.500, 2.00× better); "
                      "`worse` is worse than `direct` (0.750 vs 0.500, 1.50× worse)."),
            std::string::npos)
      << page;
  // Every technique but `direct` against the best of them.
  EXPECT_NE(page.find("- FLIP of the beauty, against the best other technique: `better` is the best (0.250); "
                      "`worse` 3.00× worse (0.750)."),
            std::string::npos)
      << page;
  // Flicker below 1e-4 is float rounding: equal to direct's, which is below it too.
  EXPECT_NE(page.find("- flicker of the beauty: `better` equals `direct` (0.00); `worse` is worse than `direct` (0.300 vs "
                      "0.00)."),
            std::string::npos)
      << page;
  EXPECT_NE(page.find("- flicker of the beauty, against the best other technique: `better` is the best (0.00); `worse` "
                      "worse (0.300)."),
            std::string::npos)
      << page;
  // The indirect light's flicker has a column and sentences of its own.
  EXPECT_NE(page.find("| `worse` | 0.750 | 0.100 | 0.750 | 0.100 | – | – | 0.300 | 0.600 | – |"), std::string::npos)
      << page;
  EXPECT_NE(page.find("- flicker of the indirect light: `better` equals `direct` (0.00); `worse` is worse than `direct` "
                      "(0.600 vs 0.00)."),
            std::string::npos)
      << page;
  EXPECT_NE(page.find("Local device: dev"), std::string::npos);
  fs::remove_all(dir);
}

TEST(ResultsPage, PageOnlyWithGpuReadsTheGpuMachinesFiguresAgain) {
  // A row the GPU machine measured again (its timings.json as bench/realtime/device-run
  // writes it) takes the new figures; a row it did not measure keeps its own; the data beside
  // the page records them.
  const fs::path dir = fs::temp_directory_path() / ("giq_results_gpu_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "h200" / "results" / "box" / "better");
  json results = {{"settings", {{"size", 64}, {"reference_spp", 16}, {"sequence_reference_spp", 4}, {"static_frames", 2}}},
                  {"rows", {row("box", "direct", 0.5, 0.08, 0.0), row("box", "better", 0.25, 0.02, 0.0)}}};
  results["rows"][0]["gpu"] = {{"device", "GPU X"}, {"resolution", {1920, 1080}}, {"gpu_ms", 3.0}};
  results["rows"][1]["gpu"] = {{"device", "GPU X"}, {"resolution", {1920, 1080}}, {"gpu_ms", 2.0}};
  std::ofstream(dir / "results.json") << results.dump(1);
  const json timings = {{"device", {{"name", "GPU X"}}},
                        {"resolution", {1920, 1080}},
                        {"frame_gpu_ms", {{"median", 0.75}}},
                        {"passes", {{{"name", "grid"}, {"gpu_ms", {{"median", 0.25}}}}}},
                        {"gpu_memory_mb", {{"scene", 2.0}, {"technique", 12.5}}}};
  std::ofstream(dir / "h200" / "results" / "box" / "better" / "timings.json") << timings.dump();
  const auto r = giq::test::run_captured(giq::test::shell_quote(GIQ_BINARY) + " results --page-only --gpu " + (dir / "h200").string() +
                                             " --doc " + (dir / "results.md").string(),
                                         dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string page = giq::test::slurp(dir / "results.md");
  EXPECT_NE(page.find("| `direct` | 0.500 | 0.0800 | 0.500 | 0.0800 | – | – | 0.00 | 0.00 | – | 1234 | 3.00 | 96.1 |"), std::string::npos)
      << page;
  EXPECT_NE(page.find("| `better` | 0.250 | 0.0200 | 0.250 | 0.0200 | – | – | 0.00 | 0.00 | – | 1234 | 0.750 | 12.5 |"), std::string::npos)
      << page;
  std::ifstream in(dir / "results.json");
  const json data = json::parse(in);
  EXPECT_EQ(data["rows"][1]["gpu"]["passes"]["grid"], 0.25);
  EXPECT_EQ(data["rows"][0]["gpu"]["gpu_ms"], 3.0);
  EXPECT_EQ(data["settings"]["gpu_dir"], (dir / "h200").string());
  fs::remove_all(dir);
}

// `giq results ARGS` run from `dir` (as from a repository root) with the fake giq doing the
// rendering; `env` goes before the command ("NAME=value " or "").
giq::test::Outcome run_results(const fs::path& dir, const std::string& args, const std::string& env = "") {
  return giq::test::run_captured("cd " + giq::test::shell_quote(dir.string()) + " && " + env +
                                     giq::test::shell_quote(GIQ_BINARY) + " results --giq " +
                                     giq::test::shell_quote(FAKE_GIQ) + " " + args,
                                 dir);
}

// The page of an earlier run: `direct` and `pt` on the scene `box`, `direct` on `zzz`.
json earlier_page() {
  return {{"settings", {{"size", 8}, {"reference_spp", 1}, {"sequence_reference_spp", 1}, {"static_frames", 1}}},
          {"rows", {row("box", "direct", 0.5, 0.08, 0.0), row("box", "pt", 0.25, 0.02, 0.0), row("zzz", "direct", 0.125, 0.01, 0.0)}},
          {"sweeps", json::array({{{"scene", "box"}, {"technique", "pt"}, {"parameters", {{"samples_per_frame", 1}}},
                                   {"default", true}, {"gpu_ms", 1.5}, {"flip_mean", 0.5}, {"relmse", 0.1},
                                   {"pareto_front", true}, {"resolution", {8, 8}}, {"timing_resolution", {8, 8}},
                                   {"error", ""}}})}};
}

TEST(ResultsPage, UpdateRendersOnlyTheGivenTechniqueAndKeepsTheOtherRows) {
  const fs::path dir = fs::temp_directory_path() / ("giq_results_update_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "scenes");
  fs::create_directories(dir / "docs");
  fs::copy_file(fs::path(GIQ_SCENES_DIR) / "cornell.gltf", dir / "scenes" / "box.gltf");
  std::ofstream(dir / "docs" / "results.json") << earlier_page().dump(1);
  const auto r = run_results(dir, "--technique direct --scene box --update --size 8 --spp 1 --sequence-spp 1 --frames 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(dir / "docs" / "results.json");
  const json page = json::parse(in);
  ASSERT_EQ(page["rows"].size(), 3u) << page.dump(1);
  // box/direct rendered again (by the fake: its device and 2.5 ms), box/pt and zzz/direct kept
  // as they were, in the page's order; the earlier sweeps kept too.
  EXPECT_EQ(page["rows"][0]["scene"], "box");
  EXPECT_EQ(page["rows"][0]["technique"], "direct");
  EXPECT_EQ(page["rows"][0]["device"], "llvmpipe (LLVM 15.0.6, 256 bits)");
  EXPECT_EQ(page["rows"][0]["gpu_ms"], 2.5);
  EXPECT_EQ(page["rows"][1], earlier_page()["rows"][1]);
  EXPECT_EQ(page["rows"][2], earlier_page()["rows"][2]);
  EXPECT_EQ(page["sweeps"], earlier_page()["sweeps"]);

  // Another size: the rows would not be comparable.
  const auto bad =
      run_results(dir, "--technique direct --scene box --update --size 16 --spp 1 --sequence-spp 1 --frames 1");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("settings.size"), std::string::npos) << bad.err;
  fs::remove_all(dir);
}

// giq results in `dir` on one built-in scene, `scene_file` copied as scenes/<name>.gltf, with
// `direct` only, the fake giq behaving as `behaviour` in results' folders (which are not gate
// cases: behaviour key ""): the page's JSON (null when results failed).
json one_scene_page(const fs::path& dir, const std::string& scene_file, const std::string& name, const json& behaviour) {
  fs::remove_all(dir);
  fs::create_directories(dir / "scenes");
  fs::create_directories(dir / "docs");
  fs::copy_file(fs::path(GIQ_SCENES_DIR) / scene_file, dir / "scenes" / (name + ".gltf"));
  std::ofstream(dir / "behaviour.json") << json({{"", behaviour}}).dump();
  const auto r = run_results(dir, "--technique direct --scene " + name + " --size 8 --spp 1 --sequence-spp 1 --frames 1",
                             "FAKE_GIQ_BEHAVIOUR=" + giq::test::shell_quote((dir / "behaviour.json").string()) + " ");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  if (r.exit_code != 0) return json();
  std::ifstream in(dir / "docs" / "results.json");
  return json::parse(in);
}

// The leak columns of a scene with declared leak regions: a view that shows some of a region
// measures its leak (0 is a measurement), a view that shows none of it measures nothing ("–").
TEST(ResultsPage, LeakIsUndefinedWhereTheViewShowsNoneOfTheRegion) {
  const fs::path dir = fs::temp_directory_path() / ("giq_results_leak_" + std::to_string(::getpid()));
  for (const int pixels : {0, 12}) {
    // Every score the fake giq writes.
    const json declared = {{"leak", {{"value", 0.0}}}, {"leak_absolute", {{"value", 0.0}}}, {"pixels", pixels}};
    const json raw = {{"last_frame", {{"metrics", {{"leak", {{"declared", declared}}}}}}},
                      {"sequence", {{"flicker", {{"value", 0.0}}}}}};
    const json page = one_scene_page(dir, "cornell.gltf", "box", {{"raw", raw}});
    ASSERT_EQ(page["rows"].size(), 1u) << page.dump(1);
    const json& beauty = page["rows"][0]["beauty"];
    if (pixels == 0) {
      EXPECT_TRUE(beauty["leak"].is_null()) << beauty.dump();
      EXPECT_TRUE(beauty["leak_absolute"].is_null()) << beauty.dump();
    } else {
      EXPECT_EQ(beauty["leak"], 0.0) << beauty.dump();
      EXPECT_EQ(beauty["leak_absolute"], 0.0) << beauty.dump();
    }
  }
  fs::remove_all(dir);
}

// An animated scene that declares where flicker and lag are measured (extras.giq.sequence):
// its rows take flicker from a score over the flicker window and lag from one over the lag
// window, the rest from every frame, and the page says which frames.
TEST(ResultsPage, FlickerAndLagOverTheFramesTheSceneDeclares) {
  const fs::path dir = fs::temp_directory_path() / ("giq_results_windows_" + std::to_string(::getpid()));
  const json page = one_scene_page(dir, "movinglight.gltf", "moving", {{"echo_frames", true}});
  ASSERT_EQ(page["rows"].size(), 1u) << page.dump(1);
  const json& row = page["rows"][0];
  // movinglight declares flicker over frames 12-27 and lag over 28-59 (of 0-59).
  EXPECT_EQ(row["beauty"]["flicker"], 12) << row.dump();
  EXPECT_EQ(row["indirect"]["flicker"], 12) << row.dump();
  EXPECT_EQ(row["beauty"]["lag90_frames"], 59) << row.dump();
  EXPECT_EQ(row["flicker_frames"], "12:27");
  EXPECT_EQ(row["lag_frames"], "28:59");
  const std::string text = giq::test::slurp(dir / "docs" / "results.md");
  EXPECT_NE(text.find("flicker over frames 12–27, lag over frames 28–59, as the scene declares"), std::string::npos) << text;
  fs::remove_all(dir);
}

}  // namespace
