// Every file under tests/data/scenes/hostile is rejected with an InputError naming the file
// and the glTF path listed for it in expected.tsv; none is left unlisted.

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <set>

#include "giq/base/error.h"
#include "giq/scenes/scene.h"
#include "support/scratch.h"
#include "test_paths.h"

namespace giq::scenes {
namespace {

std::map<std::string, std::string> expected_fields() {
  std::map<std::string, std::string> out;
  std::ifstream in(test::data("hostile/expected.tsv"));
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto tab = line.find('\t');
    if (tab != std::string::npos) out[line.substr(0, tab)] = line.substr(tab + 1);
  }
  return out;
}

TEST(Hostile, EveryFileIsListed) {
  const auto expected = expected_fields();
  EXPECT_GE(expected.size(), 30u);
  std::set<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(test::data("hostile"))) {
    const std::string ext = e.path().extension().string();
    if (ext == ".gltf" || ext == ".glb") files.insert(e.path().filename().string());
  }
  for (const auto& f : files) EXPECT_TRUE(expected.count(f)) << f << " has no line in expected.tsv";
  for (const auto& [f, field] : expected) EXPECT_TRUE(files.count(f)) << f << " is listed but missing";
}

TEST(Hostile, EachFileGivesItsError) {
  for (const auto& [name, field] : expected_fields()) {
    const std::filesystem::path path = test::data("hostile/" + name);
    SCOPED_TRACE(name);
    try {
      load(path);
      ADD_FAILURE() << "loaded without error";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), path.string());
      EXPECT_EQ(e.field(), field) << e.what();
      const std::string what = e.what();
      EXPECT_EQ(what.find('\n'), std::string::npos);
      EXPECT_EQ(what.rfind(path.string() + ": " + field + ": ", 0), 0u) << what;
    }
  }
}

// What arrives in place of a model is named in the error, not left to the JSON or image
// decoder's words.
TEST(Hostile, StandInsSayWhatTheyAre) {
  const std::map<std::string, std::string> says = {
      {"empty.glb", "the file is empty"},
      {"lfs_pointer.glb", "Git LFS pointer"},
      {"lfs_buffer.gltf", "Git LFS pointer"},
      {"lfs_texture.gltf", "Git LFS pointer"},
      {"html_page.gltf", "an HTML or XML page"},
      {"zip_named_glb.glb", "begins with \"PK\\x03\\x04\""},
  };
  for (const auto& [name, phrase] : says) {
    SCOPED_TRACE(name);
    try {
      load(test::data("hostile/" + name));
      ADD_FAILURE() << "loaded without error";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(phrase), std::string::npos) << e.what();
    }
  }
}

// glTF's JSON form under a .glb name, with or without a byte-order mark, is still read.
TEST(Hostile, JsonNamedGlbLoads) {
  const giq::test::ScratchDir dir("hostile_json_glb");
  const std::string json = giq::test::slurp(test::data("transforms.gltf"));
  for (const std::string& prefix : {std::string(), std::string("\xEF\xBB\xBF\n ")}) {
    const std::filesystem::path path = dir.path / "transforms.glb";
    std::ofstream(path, std::ios::binary) << prefix << json;
    EXPECT_EQ(load(path).meshes.size(), load(test::data("transforms.gltf")).meshes.size());
  }
}

TEST(Hostile, MissingFileIsAnInputError) {
  EXPECT_THROW(load(test::data("hostile/does_not_exist.gltf")), InputError);
  EXPECT_THROW(load(test::data("hostile")), InputError);  // a directory
}

}  // namespace
}  // namespace giq::scenes
