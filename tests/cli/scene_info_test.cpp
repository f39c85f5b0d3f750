// `giq scene info` end to end: every hostile scene exits 2 with exactly one line on stderr
// naming the file and the glTF path; a valid scene prints JSON and exits 0.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include "support/subprocess.h"
#include <string>

namespace {

namespace fs = std::filesystem;

using giq::test::Outcome;
using giq::test::slurp;
const auto& quote = giq::test::shell_quote;

Outcome giq(const std::string& args) {
  return giq::test::run_captured(quote(GIQ_BINARY) + " " + args,
                                 fs::temp_directory_path() / ("giq_cli_test_" + std::to_string(::getpid())));
}

const fs::path kScenes = fs::path(GIQ_TEST_DATA) / "scenes";

TEST(CliSceneInfo, HostileScenesExitTwoWithOneLine) {
  std::ifstream list(kScenes / "hostile" / "expected.tsv");
  std::string line;
  int checked = 0;
  while (std::getline(list, line)) {
    if (line.empty() || line[0] == '#') continue;
    const std::string name = line.substr(0, line.find('\t')), field = line.substr(line.find('\t') + 1);
    const std::string path = (kScenes / "hostile" / name).string();
    SCOPED_TRACE(name);
    const Outcome r = giq("scene info " + quote(path));
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(r.out.empty()) << r.out;
    ASSERT_FALSE(r.err.empty());
    EXPECT_EQ(r.err.back(), '\n');
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "more than one line: " << r.err;
    EXPECT_NE(r.err.find(path + ": " + field + ": "), std::string::npos) << r.err;
    ++checked;
  }
  EXPECT_GE(checked, 30);
}

TEST(CliSceneInfo, ValidSceneAsJson) {
  const Outcome r = giq("scene info " + quote((kScenes / "lights_cameras.gltf").string()) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["views"].size(), 6u);
  EXPECT_EQ(j["counts"]["punctual_lights"], 3);
  EXPECT_EQ(j["leak_regions"], nlohmann::json::array({"floor"}));
  // Positions are reported in world coordinates (origin + local).
  EXPECT_DOUBLE_EQ(j["views"][3]["position"][0].get<double>(), 104.0);
  EXPECT_EQ(j["views"][2]["projection"], "orthographic");
  EXPECT_DOUBLE_EQ(j["views"][2]["ymag"].get<double>(), 3.0);
  EXPECT_FALSE(j["views"][2].contains("yfov_deg"));
  EXPECT_EQ(j["views"][3]["projection"], "perspective");
  ASSERT_EQ(j["warnings"].size(), 1u);  // the negative ymag
  EXPECT_NE(j["warnings"][0].get<std::string>().find("ymag is negative"), std::string::npos);
}

TEST(CliSceneInfo, ValidSceneAsTable) {
  const Outcome r = giq("scene info " + quote((kScenes / "textured.gltf").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("emissive_meshes"), std::string::npos) << r.out;
}

TEST(CliSceneInfo, MissingFileIsAnInputError) {
  const Outcome r = giq("scene info " + quote((kScenes / "no_such_scene.gltf").string()));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
}

}  // namespace
