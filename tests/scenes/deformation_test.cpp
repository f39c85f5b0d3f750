// Skins and morph targets (glTF 2.0 spec, 3.7.2.2 and 3.7.3) posed at any time, against the
// closed forms of the two generated assets (tests/data/scenes/generate.py, skinned() and
// morphed()). Positions are posed in double and stored as floats relative to the scene's
// origin: within |p - origin| < 8 their rounding is below 2^-24 x 8 = 4.8e-7, so 1e-6 holds.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>

#include "giq/scenes/scene.h"
#include "support/scratch.h"
#include "test_paths.h"

namespace giq::scenes {
namespace {

using test::world;

constexpr double kTol = 1e-6;

void expect_near(glm::dvec3 got, glm::dvec3 want, const std::string& what) {
  EXPECT_NEAR(got.x, want.x, kTol) << what;
  EXPECT_NEAR(got.y, want.y, kTol) << what;
  EXPECT_NEAR(got.z, want.z, kTol) << what;
}

// skinned.gltf: vertex p with the knee turned by `angle` about +x through the knee joint, at
// (0, 1, -2) (the rig's z = -2; the strip hangs 2 in front of its joints), for knee weight `k`
// (the hip does not move).
glm::dvec3 bent(glm::dvec3 p, double angle, double k) {
  const glm::dvec3 pivot(0.0, 1.0, -2.0), d = p - pivot;
  const double c = std::cos(angle), s = std::sin(angle);
  const glm::dvec3 q = pivot + glm::dvec3(d.x, c * d.y - s * d.z, s * d.y + c * d.z);
  return (1.0 - k) * p + k * q;
}

TEST(Skinning, RestPoseIgnoresTheMeshNodeAndMatchesTheBind) {
  const Scene s = load(test::data("skinned.gltf"));
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_TRUE(s.features.skinning);
  EXPECT_TRUE(s.features.animation);
  EXPECT_FALSE(s.features.morph_targets);
  EXPECT_TRUE(s.warnings.empty());
  const Mesh& m = s.meshes[0];
  ASSERT_EQ(m.positions.size(), 10u);
  for (size_t i = 0; i < 10; ++i) {
    const glm::dvec3 rest(i % 2 ? 0.25 : -0.25, 0.5 * double(i / 2), 0.0);
    expect_near(world(s, m.positions[i]), rest, "vertex " + std::to_string(i));
    expect_near(glm::dvec3(m.normals[i]), glm::dvec3(0, 0, 1), "normal " + std::to_string(i));
  }
}

TEST(Skinning, JointsMoveTheirVerticesAndBlendAcrossTwoSets) {
  const Scene base = load(test::data("skinned.gltf"));
  for (double t : {0.25, 0.5, 1.0, 2.0}) {
    const Scene s = base.at(t);
    const double angle = 0.5 * std::numbers::pi * std::min(t, 1.0);  // slerp: the angle is linear in t
    const Mesh& m = s.meshes[0];
    ASSERT_EQ(m.positions.size(), 10u);
    for (size_t i = 0; i < 10; ++i) {
      const glm::dvec3 rest(i % 2 ? 0.25 : -0.25, 0.5 * double(i / 2), 0.0);
      // The row at y = 1 is half hip, half knee, its weights split over two sets.
      const double k = rest.y < 1.0 ? 0.0 : rest.y > 1.0 ? 1.0 : 0.5;
      const std::string what = "t " + std::to_string(t) + " vertex " + std::to_string(i);
      expect_near(world(s, m.positions[i]), bent(rest, angle, k), what);
      // Normals by the blended matrix's cofactor: the knee's rows turn with it.
      if (k == 1.0) expect_near(glm::dvec3(m.normals[i]), glm::dvec3(0, -std::sin(angle), std::cos(angle)), what + " normal");
      if (k == 0.0) expect_near(glm::dvec3(m.normals[i]), glm::dvec3(0, 0, 1), what + " normal");
    }
  }
}

// morphed.gltf: the quad's corners displaced by target 0 (top edge +0.5 z) and target 1
// (right edge +0.5 x), for weights (w0, w1), at `offset`.
glm::dvec3 morphed_corner(int i, double w0, double w1, glm::dvec3 offset) {
  const glm::dvec3 base[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const bool top = i >= 2, right = i == 1 || i == 2;
  return offset + base[i] + glm::dvec3(right ? 0.5 * w1 : 0.0, 0.0, top ? 0.5 * w0 : 0.0);
}

TEST(MorphTargets, WeightsFromTheMeshTheNodeAndBothInterpolations) {
  const Scene base = load(test::data("morphed.gltf"));
  EXPECT_TRUE(base.features.morph_targets);
  EXPECT_TRUE(base.features.animation);
  // (t, node a's weights (LINEAR from (0, 0) to (1, 0.5)), node b's (CUBICSPLINE from (0, 1) to
  // (1, 0), flat tangents: Hermite's 3s^2 - 2s^3)).
  const auto hermite = [](double s) { return 3 * s * s - 2 * s * s * s; };
  for (double t : {0.0, 0.3, 0.5, 1.0}) {
    const Scene s = base.at(t);
    ASSERT_EQ(s.meshes.size(), 2u);
    const double a0 = t, a1 = 0.5 * t, b0 = hermite(t), b1 = 1.0 - hermite(t);
    for (int i = 0; i < 4; ++i) {
      const std::string what = "t " + std::to_string(t) + " corner " + std::to_string(i);
      expect_near(world(s, s.meshes[0].positions[size_t(i)]), morphed_corner(i, a0, a1, {1, 2, 3}), "a " + what);
      expect_near(world(s, s.meshes[1].positions[size_t(i)]), morphed_corner(i, b0, b1, {0, 0, 0}), "b " + what);
      // Target 0's normal displacement (0, -0.4, 0), then normalised.
      expect_near(glm::dvec3(s.meshes[0].normals[size_t(i)]), glm::normalize(glm::dvec3(0, -0.4 * a0, 1)), "a normal " + what);
    }
  }
}

TEST(MorphTargets, RestWeightsWithoutAnAnimation) {
  // The mesh's weights (0.25, 0) for node a, the node's own (0, 1) for b, when nothing plays
  // (the same file with its sequence's animation set to -1, none).
  static const giq::test::ScratchDir dir("deformation");
  std::string text = giq::test::slurp(test::data("morphed.gltf"));
  const std::string plays = "\"animation\": \"breathe\"";
  ASSERT_NE(text.find(plays), std::string::npos);
  text.replace(text.find(plays), plays.size(), "\"animation\": -1");
  std::ofstream(dir.path / "rest.gltf") << text;
  const Scene rest = load(dir.path / "rest.gltf");
  EXPECT_FALSE(rest.features.animation);
  for (int i = 0; i < 4; ++i) {
    expect_near(world(rest, rest.meshes[0].positions[size_t(i)]), morphed_corner(i, 0.25, 0.0, {1, 2, 3}), "a");
    expect_near(world(rest, rest.meshes[1].positions[size_t(i)]), morphed_corner(i, 0.0, 1.0, {0, 0, 0}), "b");
  }
}

// collapsing.gltf: a morph target collapses one of a quad's two triangles at t = 1. The
// triangle is dropped, but a deforming mesh keeps its vertices at their indices (motion vectors
// read a vertex's previous position at its index), with and without normals in the file.
TEST(MorphTargets, ACollapsedTriangleKeepsTheVerticesAtTheirIndices) {
  const Scene base = load(test::data("collapsing.gltf"));
  ASSERT_EQ(base.meshes.size(), 2u);
  const Scene collapsed = base.at(1.0);
  EXPECT_EQ(collapsed.stats.degenerate_triangles_dropped, 2u);
  for (size_t k = 0; k < 2; ++k) {
    const Mesh &before = base.meshes[k], &after = collapsed.meshes[k];
    EXPECT_EQ(before.triangles.size(), 2u);
    EXPECT_EQ(after.triangles.size(), 1u);
    ASSERT_EQ(after.positions.size(), before.positions.size()) << "mesh " << k;
    ASSERT_EQ(after.normals.size(), after.positions.size());
    // Vertex by vertex, only corner 3 moved (onto corner 0).
    for (size_t i = 0; i < before.positions.size(); ++i) {
      const glm::dvec3 b = world(base, before.positions[i]), a = world(collapsed, after.positions[i]);
      if (b == glm::dvec3(0, 1, 0)) expect_near(a, glm::dvec3(0, 0, 0), "moved corner");
      else expect_near(a, b, "mesh " + std::to_string(k) + " vertex " + std::to_string(i));
      EXPECT_NEAR(glm::length(after.normals[i]), 1.0f, 1e-6f);
    }
  }
}

// blender_figure.glb, written by Blender's own glTF exporter (tests/data/scenes/blender_figure.py):
// eleven joints, up to six influences a vertex (JOINTS_1/WEIGHTS_1), two morph targets with
// animated weights, the armature moving. blender_figure.json holds the positions Blender's
// armature modifier and shape keys give its vertices at five frames. giq's vertices are paired
// with Blender's at frame 0 (nearest, and unambiguously so), then compared at every frame.
// Blender deforms in float32: a vertex within 2 m passes through a few matrix products of
// rounding 2^-22 m each, so ten such steps (2.4e-6 m) bound the difference; measured, it is
// below 2.6e-7 m.
constexpr double kBlenderTol = 10.0 * 0x1p-22;
TEST(Skinning, AgreesWithBlendersOwnDeformationOfItsExport) {
  const Scene base = load(test::data("blender_figure.glb"));
  EXPECT_TRUE(base.features.skinning);
  EXPECT_TRUE(base.features.morph_targets);
  EXPECT_TRUE(base.features.animation);
  ASSERT_EQ(base.meshes.size(), 1u);
  const nlohmann::json blender = nlohmann::json::parse(giq::test::slurp(test::data("blender_figure.json")));
  const double fps = blender.at("fps").get<double>();
  const auto frame = [&](const std::string& f) {
    std::vector<glm::dvec3> v;
    for (const auto& p : blender.at("frames").at(f)) v.emplace_back(p.at(0).get<double>(), p.at(1).get<double>(), p.at(2).get<double>());
    return v;
  };
  // Pairing at frame 0.
  const std::vector<glm::dvec3> first = frame("0");
  const Mesh& m0 = base.meshes[0];
  std::vector<size_t> pair(m0.positions.size());
  for (size_t i = 0; i < m0.positions.size(); ++i) {
    const glm::dvec3 p = world(base, m0.positions[i]);
    double best = std::numeric_limits<double>::infinity(), second = best;
    for (size_t k = 0; k < first.size(); ++k) {
      const double d = glm::length(first[k] - p);
      if (d < best) second = best, best = d, pair[i] = k;
      else if (d < second) second = d;
    }
    ASSERT_LT(best, kBlenderTol) << "vertex " << i << " has no counterpart in Blender's frame 0";
    ASSERT_GT(second, 1e-3) << "vertex " << i << " has two candidates in Blender's frame 0";
  }
  for (const auto& [f, positions] : blender.at("frames").items()) {
    const Scene s = base.at(std::stod(f) / fps);
    const std::vector<glm::dvec3> want = frame(f);
    ASSERT_EQ(s.meshes[0].positions.size(), m0.positions.size());
    double worst = 0.0;
    for (size_t i = 0; i < pair.size(); ++i) worst = std::max(worst, glm::length(world(s, s.meshes[0].positions[i]) - want[pair[i]]));
    EXPECT_LT(worst, kBlenderTol) << "frame " << f;
  }
}

}  // namespace
}  // namespace giq::scenes
