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
#include <string>

namespace {

namespace fs = std::filesystem;

struct Outcome {
  int exit_code = -1;
  std::string out, err;
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

Outcome giq(const std::string& args) {
  static int n = 0;
  const fs::path dir = fs::temp_directory_path() / ("giq_cli_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path out = dir / ("out" + std::to_string(n)), err = dir / ("err" + std::to_string(n));
  ++n;
  const std::string cmd = quote(GIQ_BINARY) + " " + args + " >" + quote(out.string()) + " 2>" + quote(err.string());
  const int status = std::system(cmd.c_str());
  Outcome r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  fs::remove(out);
  fs::remove(err);
  return r;
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
  EXPECT_EQ(j["views"].size(), 4u);
  EXPECT_EQ(j["counts"]["punctual_lights"], 3);
  EXPECT_EQ(j["leak_regions"], nlohmann::json::array({"floor"}));
  // Positions are reported in world coordinates (origin + local).
  EXPECT_DOUBLE_EQ(j["views"][2]["position"][0].get<double>(), 104.0);
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
