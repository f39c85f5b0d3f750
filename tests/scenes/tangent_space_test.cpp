// Tangents for normal maps where a glTF primitive has none (scenes/src/tangent_space.h):
// glTF's sign convention on a plane in closed form, the split of a vertex on a mirrored seam,
// triangles without UV area, hostile geometry, MikkTSpace as Blender's own exporter computes it
// on meshes with mirrored seams, poles and sheared UVs (tests/data/scenes/blender_tangents.py)
// through the loader, and the loader's split of a skinned, morphing primitive.

#include "tangent_space.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "giq/scenes/scene.h"
#include "gltf_builder.h"
#include "support/scratch.h"
#include "test_paths.h"

namespace giq::scenes {
namespace {

namespace fs = std::filesystem;

// A unit square in the xy plane facing +z, its UVs as Blender's exporter writes a plane's:
// glTF's v runs down the image, so v = 1 - y; `mirrored` runs u the other way (u = 1 - x).
GeneratedTangents square(bool mirrored) {
  const std::vector<glm::vec3> p{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, n(4, glm::vec3(0, 0, 1));
  std::vector<glm::vec2> uv;
  for (const glm::vec3& q : p) uv.emplace_back(mirrored ? 1.0f - q.x : q.x, 1.0f - q.y);
  return generate_tangents(p, n, uv, {{0, 1, 2}, {0, 2, 3}});
}

TEST(TangentSpace, TangentIsDpDuAndTheSignKeepsTheBitangentUpTheImage) {
  // Unmirrored: +u (the image's right) is +x and the image's up is +y = cross(n, t), sign +1,
  // as Blender exports this plane. Mirrored: +u is -x, the image's up still +y = -cross(n, t).
  const GeneratedTangents plain = square(false), mirrored = square(true);
  ASSERT_EQ(plain.tangents.size(), 4u);
  ASSERT_EQ(mirrored.tangents.size(), 4u);
  for (const glm::vec4& t : plain.tangents) EXPECT_EQ(t, glm::vec4(1, 0, 0, 1));
  for (const glm::vec4& t : mirrored.tangents) EXPECT_EQ(t, glm::vec4(-1, 0, 0, -1));
  EXPECT_EQ(plain.triangles, (std::vector<glm::uvec3>{{0, 1, 2}, {0, 2, 3}}));
}

TEST(TangentSpace, AMirroredSeamSplitsTheVerticesOnIt) {
  // Two unit squares side by side sharing the edge x = 1, the UVs mirrored there (u = x, then
  // u = 2 - x): the shared vertices 1 and 4 are each one vertex with two tangents.
  const std::vector<glm::vec3> p{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 0}}, n(6, glm::vec3(0, 0, 1));
  std::vector<glm::vec2> uv;
  for (const glm::vec3& q : p) uv.emplace_back(q.x <= 1.0f ? q.x : 2.0f - q.x, 1.0f - q.y);
  const std::vector<glm::uvec3> tris{{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}};
  const GeneratedTangents g = generate_tangents(p, n, uv, tris);
  ASSERT_EQ(g.tangents.size(), 8u);
  EXPECT_EQ(g.source, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5, 1, 4}));
  for (size_t f = 0; f < tris.size(); ++f)
    for (int c = 0; c < 3; ++c) {
      const uint32_t v = g.triangles[f][c];
      EXPECT_EQ(g.source[v], tris[f][c]);
      EXPECT_EQ(g.tangents[v], f < 2 ? glm::vec4(1, 0, 0, 1) : glm::vec4(-1, 0, 0, -1)) << "triangle " << f << " corner " << c;
    }
}

TEST(TangentSpace, TrianglesWithoutUvAreaAddNothing) {
  // The square's second triangle squashed to a line in UV: its corners take the first
  // triangle's tangent where they share a vertex, and vertex 3, which only it uses, a unit
  // vector in the normal's plane.
  const std::vector<glm::vec3> p{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, n(4, glm::vec3(0, 0, 1));
  const std::vector<glm::vec2> uv{{0, 1}, {1, 1}, {1, 0}, {0.5f, 0.5f}};
  const GeneratedTangents g = generate_tangents(p, n, uv, {{0, 1, 2}, {0, 2, 3}});
  ASSERT_EQ(g.tangents.size(), 4u);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(g.tangents[size_t(i)], glm::vec4(1, 0, 0, 1)) << i;
  EXPECT_NEAR(glm::length(glm::vec3(g.tangents[3])), 1.0f, 1e-6f);
  EXPECT_EQ(g.tangents[3].z, 0.0f);
}

TEST(TangentSpace, HostileGeometryGivesUnitTangents) {
  // What a file can hold past the loader's checks: a zero normal, normals of huge magnitude,
  // positions at the float range's edge (their differences overflow in float), UVs of 1e30, a non-manifold edge shared by three triangles, a triangle repeated, and one whose
  // corners are one welded vertex twice. Every tangent comes out finite and unit length, in
  // its normal's plane where the normal has a direction.
  const float big = 3e38f;
  const std::vector<glm::vec3> p{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {big, 0, 0}, {-big, big, 0}, {1, 0, 0}, {2, 2, 2}};
  const std::vector<glm::vec3> n{{0, 0, 0}, {0, 0, 1e30f}, {0, 0, 1}, {0, 1, 0}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1e30f}, {1, 0, 0}};
  const std::vector<glm::vec2> uv{{0, 0}, {1, 0}, {0, 1}, {1e30f, -1e30f}, {0.5f, 0.5f}, {0, 2}, {1, 0}, {3, 3}};
  const std::vector<glm::uvec3> tris{{0, 1, 2}, {1, 0, 3}, {0, 1, 7}, {0, 1, 2}, {4, 5, 2}, {1, 6, 2}, {5, 4, 7}};
  const GeneratedTangents g = generate_tangents(p, n, uv, tris);
  ASSERT_EQ(g.triangles.size(), tris.size());
  ASSERT_EQ(g.source.size(), g.tangents.size());
  for (size_t i = 0; i < g.tangents.size(); ++i) {
    const glm::vec4 t = g.tangents[i];
    ASSERT_TRUE(std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z)) << i;
    EXPECT_NEAR(glm::length(glm::vec3(t)), 1.0f, 1e-6f) << i;
    EXPECT_TRUE(t.w == 1.0f || t.w == -1.0f) << i;
    const glm::vec3 normal = n[g.source[i]];
    if (glm::length(normal) > 0.0f) {
      EXPECT_NEAR(glm::dot(glm::vec3(t), glm::normalize(normal)), 0.0f, 1e-6f) << i;
    }
  }
  for (size_t f = 0; f < tris.size(); ++f)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(g.source[g.triangles[f][c]], tris[f][c]);
}

// A copy of a .glb in `dir` with every primitive's TANGENT attribute removed from its JSON chunk.
fs::path without_tangents(const fs::path& glb, const fs::path& dir) {
  const std::string bytes = giq::test::slurp(glb);
  uint32_t json_length = 0;
  std::memcpy(&json_length, bytes.data() + 12, 4);
  nlohmann::json doc = nlohmann::json::parse(bytes.substr(20, json_length));
  for (auto& mesh : doc["meshes"])
    for (auto& prim : mesh["primitives"]) prim["attributes"].erase("TANGENT");
  std::string json = doc.dump();
  json.resize((json.size() + 3) / 4 * 4, ' ');
  const std::string rest = bytes.substr(20 + json_length);  // the BIN chunk, header included
  auto u32 = [](size_t v) {
    const uint32_t x = uint32_t(v);
    return std::string(reinterpret_cast<const char*>(&x), 4);
  };
  const fs::path out = dir / glb.filename();
  std::ofstream(out, std::ios::binary) << bytes.substr(0, 8) << u32(20 + json.size() + rest.size()) << u32(json.size()) << "JSON" << json
                                       << rest;
  return out;
}

TEST(TangentSpace, TangentsAreBlendersMikkTSpace) {
  const Scene blender = load(test::data("blender_tangents.glb"));
  const giq::test::ScratchDir dir("tangents_stripped");
  const Scene giq = load(without_tangents(test::data("blender_tangents.glb"), dir.path));
  ASSERT_EQ(blender.meshes.size(), 3u);
  ASSERT_EQ(giq.meshes.size(), 3u);
  for (size_t m = 0; m < blender.meshes.size(); ++m) {
    const Mesh &b = blender.meshes[m], &g = giq.meshes[m];
    SCOPED_TRACE(b.name);
    // Blender's exporter already splits vertices whose tangents differ, so none is split here.
    ASSERT_EQ(g.positions.size(), b.positions.size());
    ASSERT_EQ(g.tangents.size(), b.tangents.size());
    EXPECT_EQ(g.triangles, b.triangles);
    size_t mirrored = 0;
    double worst = 0.0;
    for (size_t i = 0; i < b.tangents.size(); ++i) {
      EXPECT_EQ(g.tangents[i].w, b.tangents[i].w) << "vertex " << i;
      mirrored += b.tangents[i].w < 0.0f;
      const glm::dvec3 x(glm::vec3(g.tangents[i])), y(glm::vec3(b.tangents[i]));
      worst = std::max(worst, std::atan2(glm::length(glm::cross(x, y)), glm::dot(x, y)));
    }
    std::printf("%s: %zu vertices, %zu mirrored, largest angle to Blender's tangent %.3g rad\n", b.name.c_str(), b.tangents.size(), mirrored, worst);
    // Blender computes in float. Suzanne's smallest edges are 1/50 of its coordinates, so a
    // coordinate's rounding (2^-24) turns an edge by up to 3e-6 rad, and dp/du, a difference of
    // two edges weighted by the UV triangle's inverse, by ten times that where the mapping is
    // stretched: 3e-5 rad measured there, 4e-7 on the grid. Weighting the triangles uniformly
    // instead of by their angle moves tangents by up to 0.6 rad on Suzanne, 0.036 on the
    // sphere and 0.005 on the grid.
    EXPECT_LT(worst, 1e-4);
  }
}

TEST(TangentSpace, SplitVerticesKeepTheirJointsWeightsAndMorphTargets) {
  // The mirrored strip above as a skinned, morphing, normal-mapped glTF primitive without
  // TANGENT: the loader gives it tangents in its rest pose, and the two vertices split on the
  // seam carry their position, normal, UV, joints, weights and morph displacements along.
  const std::vector<float> pos{0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0, 1, 1, 0, 2, 1, 0}, nrm{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  std::vector<float> uv, weights, morph;
  std::vector<uint8_t> joints;
  for (int i = 0; i < 6; ++i) {
    const float x = pos[size_t(3 * i)], y = pos[size_t(3 * i + 1)];
    uv.insert(uv.end(), {x <= 1.0f ? x : 2.0f - x, 1.0f - y});
    const float w = 0.1f * float(i + 1);
    weights.insert(weights.end(), {w, 1.0f - w, 0.0f, 0.0f});
    joints.insert(joints.end(), {uint8_t(i % 2), uint8_t(1 - i % 2), 0, 0});
    morph.insert(morph.end(), {0.0f, 0.0f, 0.01f * float(i + 1)});
  }
  const std::vector<uint16_t> idx{0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4};
  giq::test::Doc d;
  auto accessor = [&](const void* data, size_t bytes, int component, size_t count, const char* type) {
    const int v = d.view({{"buffer", 0}, {"byteOffset", d.append(data, bytes)}, {"byteLength", bytes}});
    return d.accessor({{"bufferView", v}, {"componentType", component}, {"count", count}, {"type", type}});
  };
  const int p = accessor(pos.data(), pos.size() * 4, 5126, 6, "VEC3");
  d.j["accessors"][size_t(p)]["min"] = {0, 0, 0};
  d.j["accessors"][size_t(p)]["max"] = {2, 1, 0};
  const int n = accessor(nrm.data(), nrm.size() * 4, 5126, 6, "VEC3"), t = accessor(uv.data(), uv.size() * 4, 5126, 6, "VEC2");
  const int j = accessor(joints.data(), joints.size(), 5121, 6, "VEC4"), w = accessor(weights.data(), weights.size() * 4, 5126, 6, "VEC4");
  const int m = accessor(morph.data(), morph.size() * 4, 5126, 6, "VEC3");
  d.primitive({{"POSITION", p}, {"NORMAL", n}, {"TEXCOORD_0", t}, {"JOINTS_0", j}, {"WEIGHTS_0", w}}, accessor(idx.data(), idx.size() * 2, 5123, 12, "SCALAR"));
  d.j["meshes"][0]["primitives"][0]["targets"] = {{{"POSITION", m}}};
  d.j["meshes"][0]["weights"] = {0.5};
  d.j["nodes"] = {{{"mesh", 0}, {"skin", 0}}, {{"translation", {0, 0, 0}}}, {{"translation", {0, 0, 0.5}}}};
  d.j["scenes"][0]["nodes"] = {0, 1, 2};
  d.j["skins"] = {{{"joints", {1, 2}}}};
  d.j["images"] = {{{"uri", "normal.png"}}};
  d.j["textures"] = {{{"source", 0}}};
  d.j["materials"][0]["normalTexture"] = {{"index", 0}};
  const giq::test::ScratchDir dir("tangent_split");
  fs::copy_file(fs::path(GIQ_TEST_DATA) / "flip/pairs/ldr_png_scene.ref.png", dir.path / "normal.png");
  const Scene s = load(d.write(dir.path, "strip.gltf", false));
  ASSERT_EQ(s.meshes.size(), 1u);
  const Mesh& mesh = s.meshes[0];
  ASSERT_TRUE(mesh.deformation && mesh.deformation->rest);
  const DeformationRest& rest = *mesh.deformation->rest;
  ASSERT_EQ(mesh.positions.size(), 8u);
  ASSERT_EQ(rest.tangents.size(), 8u);
  ASSERT_EQ(rest.joints.size(), 1u);
  ASSERT_EQ(rest.joints[0].size(), 8u);
  ASSERT_EQ(rest.weights[0].size(), 8u);
  ASSERT_EQ(rest.targets.size(), 1u);
  ASSERT_EQ(rest.targets[0].positions.size(), 8u);
  const uint32_t source[8] = {0, 1, 2, 3, 4, 5, 1, 4};
  for (uint32_t i = 0; i < 8; ++i) {
    const uint32_t o = source[i];
    EXPECT_EQ(rest.positions[i], glm::vec3(pos[3 * o], pos[3 * o + 1], pos[3 * o + 2])) << i;
    EXPECT_EQ(rest.normals[i], glm::vec3(0, 0, 1)) << i;
    EXPECT_EQ(mesh.uvs[i], glm::vec2(uv[2 * o], uv[2 * o + 1])) << i;
    EXPECT_EQ(rest.joints[0][i], glm::uvec4(o % 2, 1 - o % 2, 0, 0)) << i;
    EXPECT_EQ(rest.weights[0][i].x, weights[4 * o]) << i;
    EXPECT_EQ(rest.targets[0].positions[i], glm::vec3(0, 0, morph[3 * o + 2])) << i;
    // Posed: the copies sit where the vertex they were split from does.
    EXPECT_EQ(mesh.positions[i], mesh.positions[o]) << i;
  }
  EXPECT_EQ(rest.tangents[1], glm::vec4(1, 0, 0, 1));
  EXPECT_EQ(rest.tangents[6], glm::vec4(-1, 0, 0, -1));
  EXPECT_EQ(mesh.tangents[1].w, 1.0f);
  EXPECT_EQ(mesh.tangents[6].w, -1.0f);
}

}  // namespace
}  // namespace giq::scenes
