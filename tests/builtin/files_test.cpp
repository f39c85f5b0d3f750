// The committed built-in scenes are exactly what giq-scenegen writes, and they are valid,
// self-contained glTF 2.0: checked here against the specification without the scene loader.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <glm/gtc/quaternion.hpp>
#include <set>
#include <string>

#include "gltf_file.h"

namespace fs = std::filesystem;
using giq::test::GltfFile;
using nlohmann::json;

namespace {

const std::vector<std::string> kScenes = {"cornell", "leak", "sunroom", "movinglight", "atrium", "dynamic"};
// Scenes with curved surfaces, smooth-shaded: vertex normals of the surface, not of the face.
const std::set<std::string> kSmooth = {"atrium"};

fs::path scene_path(const std::string& name) {
  return fs::path(GIQ_SCENES_DIR) / (name + ".gltf");
}

// Float data are written from doubles rounded once to float: a unit normal is off by at most a
// few float ulps (2^-24 relative each), far inside this bound.
constexpr double kUnitTolerance = 1e-6;

void collect_extensions(const json& j, std::set<std::string>& out) {
  if (j.is_object()) {
    for (const auto& [key, value] : j.items()) {
      if (key == "extensions" && value.is_object())
        for (const auto& [name, ignored] : value.items()) out.insert(name);
      collect_extensions(value, out);
    }
  } else if (j.is_array()) {
    for (const auto& v : j) collect_extensions(v, out);
  }
}

}  // namespace

TEST(BuiltinScenes, RegeneratingGivesTheCommittedBytes) {
  const fs::path dir =
      fs::temp_directory_path() / ("giq-scenegen-test-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const std::string command = std::string("\"") + GIQ_SCENEGEN + "\" \"" + dir.string() +
                              "\" --doc \"" + (dir / "builtin-scenes.md").string() + "\"";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  for (const std::string& name : kScenes) {
    SCOPED_TRACE(name);
    EXPECT_TRUE(giq::test::read_bytes(dir / (name + ".gltf")) ==
                giq::test::read_bytes(scene_path(name)))
        << "scenes/" << name
        << ".gltf differs from the generator's output: run tools/scenes-update";
  }
  EXPECT_TRUE(giq::test::read_bytes(dir / "builtin-scenes.md") ==
              giq::test::read_bytes(fs::path(GIQ_SOURCE_DIR) / "docs" / "builtin-scenes.md"))
      << "docs/builtin-scenes.md differs from the generator's output: run tools/scenes-update";
  fs::remove_all(dir);
}

class BuiltinFile : public testing::TestWithParam<std::string> {
 protected:
  void SetUp() override { f = GltfFile::read(scene_path(GetParam())); }
  GltfFile f;
};

TEST_P(BuiltinFile, IsSelfContainedGltf20WithAlignedTightViews) {
  EXPECT_EQ(f.doc.at("asset").at("version"), "2.0");
  EXPECT_FALSE(f.doc.contains("extensionsRequired"));
  EXPECT_LT(f.doc.at("scene").get<size_t>(), f.doc.at("scenes").size());
  for (const auto& view : f.doc.at("bufferViews")) {
    const size_t offset = view.value("byteOffset", size_t{0});
    EXPECT_EQ(offset % 4, 0u) << view;
    EXPECT_LE(offset + view.at("byteLength").get<size_t>(), f.buffer.size());
    EXPECT_FALSE(view.contains("byteStride")) << "one accessor per view needs no stride";
  }
}

TEST_P(BuiltinFile, PositionBoundsAreDeclaredAndExact) {
  for (const auto& mesh : f.doc.at("meshes"))
    for (const auto& prim : mesh.at("primitives")) {
      const auto& acc = f.doc.at("accessors").at(prim.at("attributes").at("POSITION").get<int>());
      ASSERT_TRUE(acc.contains("min") && acc.contains("max")) << mesh.at("name");
      glm::vec3 lo(INFINITY), hi(-INFINITY);
      for (glm::vec3 p : f.vec3s(prim.at("attributes").at("POSITION").get<int>()))
        lo = glm::min(lo, p), hi = glm::max(hi, p);
      for (int k = 0; k < 3; ++k) {
        // glTF 2.0 §3.6.2.5: JSON min/max stand for single-precision floats.
        EXPECT_EQ(static_cast<float>(acc["min"][k].get<double>()), lo[k]) << mesh.at("name");
        EXPECT_EQ(static_cast<float>(acc["max"][k].get<double>()), hi[k]) << mesh.at("name");
      }
    }
}

TEST_P(BuiltinFile, NormalsAreUnitAndAgreeWithTheWinding) {
  for (const auto& mesh : f.doc.at("meshes"))
    for (const auto& prim : mesh.at("primitives")) {
      EXPECT_EQ(prim.value("mode", 4), 4);
      const auto pos = f.vec3s(prim.at("attributes").at("POSITION").get<int>());
      const auto nrm = f.vec3s(prim.at("attributes").at("NORMAL").get<int>());
      const auto idx = f.indices(prim.at("indices").get<int>());
      ASSERT_EQ(pos.size(), nrm.size());
      ASSERT_EQ(idx.size() % 3, 0u);
      for (glm::vec3 n : nrm) EXPECT_NEAR(glm::length(glm::dvec3(n)), 1.0, kUnitTolerance);
      for (size_t t = 0; t < idx.size(); t += 3) {
        ASSERT_LT(std::max({idx[t], idx[t + 1], idx[t + 2]}), pos.size());
        const glm::dvec3 a = pos[idx[t]], b = pos[idx[t + 1]], c = pos[idx[t + 2]];
        const glm::dvec3 g = glm::cross(b - a, c - a);
        ASSERT_GT(glm::length(g), 1e-8) << "degenerate triangle in " << mesh.at("name");
        // Flat shading: all three vertices carry the counter-clockwise face normal (§3.7.2.1).
        // Smooth shading: within 30 degrees of it (the atrium's coarsest curve, a curtain's
        // fold of 8 segments, turns its normals by up to 20 degrees across a triangle).
        const double least = kSmooth.count(GetParam()) ? std::cos(30.0 * M_PI / 180.0) : 1.0 - 1e-6;
        for (int k = 0; k < 3; ++k)
          EXPECT_GT(glm::dot(glm::normalize(g), glm::dvec3(nrm[idx[t + k]])), least)
              << mesh.at("name") << " triangle " << t / 3;
      }
    }
}

TEST_P(BuiltinFile, ExtensionsUsedListsExactlyTheExtensionsUsed) {
  std::set<std::string> used;
  collect_extensions(f.doc, used);
  std::set<std::string> declared;
  for (const auto& e : f.doc.value("extensionsUsed", json::array()))
    declared.insert(e.get<std::string>());
  EXPECT_EQ(declared, used);
}

TEST_P(BuiltinFile, NamesViewsAndExtrasFollowTheSchema) {
  std::set<std::string> nodes;
  for (const auto& n : f.doc.at("nodes")) {
    const std::string name = n.value("name", "");
    EXPECT_FALSE(name.empty());
    EXPECT_TRUE(nodes.insert(name).second) << "duplicate node name " << name;
  }
  const json& giq = f.doc.at("extras").at("giq");
  for (const auto& [key, ignored] : giq.items())
    EXPECT_TRUE(key == "views" || key == "sequence" || key == "leak_regions" ||
                key == "environment" || key == "emitters")
        << key;
  std::set<std::string> views;
  for (const auto& n : f.doc.at("nodes"))
    if (n.contains("camera")) views.insert(n.at("name").get<std::string>());
  for (const auto& v : giq.value("views", json::array())) {
    std::set<std::string> keys;
    for (const auto& [key, ignored] : v.items()) keys.insert(key);
    EXPECT_EQ(keys, (std::set<std::string>{"name", "eye", "target", "up", "yfov_deg"}));
    EXPECT_TRUE(views.insert(v.at("name").get<std::string>()).second) << "duplicate view";
    const double yfov = v.at("yfov_deg").get<double>();
    EXPECT_TRUE(yfov > 0.0 && yfov < 180.0);
  }
  EXPECT_GE(views.size(), 2u);
  for (const auto& r : giq.value("leak_regions", json::array())) {
    const int node = f.node(r.get<std::string>());
    ASSERT_GE(node, 0) << r;
    EXPECT_TRUE(f.doc["nodes"][node].contains("mesh")) << r;
  }
}

TEST_P(BuiltinFile, AnimationKeyTimesAreBoundedAndIncreasing) {
  for (const auto& anim : f.doc.value("animations", json::array()))
    for (const auto& sampler : anim.at("samplers")) {
      const int input = sampler.at("input").get<int>();
      const auto& acc = f.doc.at("accessors").at(input);
      const auto times = f.floats(input);
      ASSERT_FALSE(times.empty());
      ASSERT_TRUE(acc.contains("min") && acc.contains("max"));  // §3.11: required for inputs
      EXPECT_EQ(static_cast<float>(acc["min"][0].get<double>()), times.front());
      EXPECT_EQ(static_cast<float>(acc["max"][0].get<double>()), times.back());
      for (size_t i = 1; i < times.size(); ++i) EXPECT_LT(times[i - 1], times[i]);
      EXPECT_EQ(f.doc.at("accessors").at(sampler.at("output").get<int>()).at("count"),
                times.size());
    }
}

INSTANTIATE_TEST_SUITE_P(All, BuiltinFile, testing::ValuesIn(kScenes),
                         [](const auto& info) { return info.param; });
