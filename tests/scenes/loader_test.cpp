// Loading the hand-made scenes of tests/data/scenes (written by generate.py there); every
// expected value below follows from the numbers in that script.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>

#include "giq/base/error.h"
#include "giq/scenes/scene.h"
#include "support/scratch.h"
#include "test_paths.h"

namespace giq::scenes {
namespace {

using test::data;
using test::world;

// Float rounding of coordinates of magnitude ~10 after a double-precision transform.
constexpr double kPos = 1e-5;

void expect_world(const Scene& s, glm::vec3 local, glm::dvec3 expected, double tol = kPos) {
  const glm::dvec3 w = world(s, local);
  EXPECT_NEAR(w.x, expected.x, tol);
  EXPECT_NEAR(w.y, expected.y, tol);
  EXPECT_NEAR(w.z, expected.z, tol);
}

void expect_vec(glm::vec3 a, glm::vec3 b, float tol = 1e-6f) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

glm::vec3 face_normal(const Mesh& m, size_t t) {
  const auto& i = m.triangles[t];
  return glm::normalize(glm::cross(m.positions[i.y] - m.positions[i.x], m.positions[i.z] - m.positions[i.x]));
}

TEST(Loader, TransformsComposeInTheLocalFrame) {
  const Scene s = load(data("transforms.gltf"));
  ASSERT_EQ(s.meshes.size(), 4u);
  // World bounds at t = 0: x in [-1, 12], y in [0, 4], z in [-3, 2]; origin = their centre.
  EXPECT_EQ(s.origin, glm::dvec3(5.5, 2.0, -0.5));
  expect_world(s, s.bounds.lo, {-1, 0, -3});
  expect_world(s, s.bounds.hi, {12, 4, 2});

  // Depth-first order from the roots: parent, child, mirror, unnamed node 3.
  const Mesh& quad = s.meshes[0];
  EXPECT_EQ(quad.name, "parent");
  EXPECT_EQ(quad.node, 0);
  EXPECT_EQ(quad.object_id, 1u);
  ASSERT_EQ(quad.positions.size(), 4u);  // indexed: normals came with the file
  expect_world(s, quad.positions[0], {8, 0, -2});  // (-1, 0, -1) * 2 + (10, 0, 0)
  for (const auto& n : quad.normals) expect_vec(n, {0, 1, 0});

  // child: parent * T(0,1,0) * Rz(90): (0,0,0) -> (10,2,0), (1,0,0) -> (10,4,0), (0,1,0) -> (8,2,0).
  const Mesh& child = s.meshes[1];
  EXPECT_EQ(child.name, "child");
  EXPECT_EQ(child.object_id, 2u);
  ASSERT_EQ(child.positions.size(), 3u);
  expect_world(s, child.positions[0], {10, 2, 0});
  expect_world(s, child.positions[1], {10, 4, 0});
  expect_world(s, child.positions[2], {8, 2, 0});
  // No normals in the file: flat normals, de-indexed, along the face normal (+Z).
  for (const auto& n : child.normals) expect_vec(n, {0, 0, 1});
  EXPECT_EQ(s.meshes[3].name, "node3");
  expect_world(s, s.meshes[3].positions[0], {0, 0, -3});  // from the node's matrix
  EXPECT_EQ(s.stats.triangles, 5u);
  EXPECT_EQ(s.stats.degenerate_triangles_dropped, 0u);
  // No material in the file: the glTF default one (metallic 1, roughness 1).
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].metallic, 1.0f);
  EXPECT_EQ(s.materials[0].roughness, 1.0f);
  EXPECT_TRUE(s.features.specular);
  for (const auto& m : s.meshes) EXPECT_EQ(m.material, 0);
}

TEST(Loader, MirroredTransformKeepsFrontFacesOutward) {
  const Scene s = load(data("transforms.gltf"));
  const Mesh& mirror = s.meshes[2];
  ASSERT_EQ(mirror.triangles.size(), 1u);
  // scale (-1, 1, 1) maps the triangle (0,0,0), (1,0,0), (0,1,0) to x <= 0; with the
  // winding swapped its counter-clockwise normal is still +Z.
  expect_vec(face_normal(mirror, 0), {0, 0, 1});
  expect_vec(mirror.normals[0], {0, 0, 1});
  expect_world(s, mirror.positions[mirror.triangles[0].y], {0, 1, 0});
  expect_world(s, mirror.positions[mirror.triangles[0].z], {-1, 0, 0});
}

TEST(Loader, StripsFansDegenerateAndSparse) {
  const Scene s = load(data("strip_fan.gltf"));
  ASSERT_EQ(s.meshes.size(), 4u);
  // Strip of 4 vertices: (v0 v1 v2), (v1 v3 v2).
  const Mesh& strip = s.meshes[0];
  ASSERT_EQ(strip.triangles.size(), 2u);
  const auto& t1 = strip.triangles[1];
  expect_world(s, strip.positions[t1.x], {1, 0, 0});
  expect_world(s, strip.positions[t1.y], {1, 1, 0});
  expect_world(s, strip.positions[t1.z], {0, 1, 0});
  // Fan of 5 vertices: (v1 v2 v0), (v2 v3 v0), (v3 v4 v0).
  const Mesh& fan = s.meshes[1];
  ASSERT_EQ(fan.triangles.size(), 3u);
  expect_world(s, fan.positions[fan.triangles[0].z], {0, 0, 0});
  expect_world(s, fan.positions[fan.triangles[2].x], {0, 1, 0});
  for (const Mesh* m : {&strip, &fan})
    for (size_t t = 0; t < m->triangles.size(); ++t) expect_vec(face_normal(*m, t), {0, 0, 1});
  // Two of three indexed triangles have no area: dropped and counted.
  EXPECT_EQ(s.meshes[2].triangles.size(), 1u);
  EXPECT_EQ(s.stats.degenerate_triangles_dropped, 2u);
  // Sparse accessor over zeros: vertices 1 and 2 substituted.
  const Mesh& sparse = s.meshes[3];
  ASSERT_EQ(sparse.triangles.size(), 1u);
  expect_world(s, sparse.positions[1], {1, 0, 0});
  expect_world(s, sparse.positions[2], {0, 1, 0});
  EXPECT_EQ(s.stats.triangles, 7u);
}

TEST(Loader, CollapsedTrianglesAreDroppedOncePerPrimitiveNotPerInstance) {
  // A sparse accessor over 2^20 - 1 implicit zeros with one vertex moved: 349525 triangles,
  // each with two equal corners, instanced by 40 nodes. They are counted as dropped for every
  // instance, as before, but dropped when loaded rather than posed per instance (found by the
  // gltf fuzzer: 12 million such triangles took seconds to pose).
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("giq_scenes_collapsed_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::string nodes, roots;
  for (int i = 0; i < 40; ++i) {
    nodes += std::string(i ? "," : "") + R"({"mesh": 0, "translation": [)" + std::to_string(i) + ", 0, 0]}";
    roots += std::string(i ? "," : "") + std::to_string(i);
  }
  std::ofstream(dir / "collapsed.gltf") << R"({"asset": {"version": "2.0"},
    "buffers": [{"byteLength": 16, "uri": "data:application/octet-stream;base64,AQAAAAAAgD8AAAAAAAAAAA=="}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 2}, {"buffer": 0, "byteOffset": 4, "byteLength": 12}],
    "accessors": [{"componentType": 5126, "count": 1048575, "type": "VEC3",
                   "sparse": {"count": 1, "indices": {"bufferView": 0, "componentType": 5123}, "values": {"bufferView": 1}}}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "nodes": [)" + nodes + R"(], "scenes": [{"nodes": [)" + roots + R"(]}]})";
  const Scene s = load(dir / "collapsed.gltf");
  EXPECT_EQ(s.stats.triangles, 0u);
  EXPECT_EQ(s.stats.degenerate_triangles_dropped, 40u * 349525u);
  for (const Mesh& m : s.meshes) EXPECT_TRUE(m.positions.empty());
  fs::remove_all(dir);
}

// IEC 61966-2-1 decoding of the 8-bit values in textured.gltf's PNG, computed by hand:
// ((c/255 + 0.055) / 1.055)^2.4.
constexpr float kLin128 = 0.21586050f, kLin188 = 0.50288646f, kLin64 = 0.05126946f, kLin32 = 0.01444384f;

TEST(Loader, TexturesDecodeSrgbToLinearOnlyForColour) {
  const Scene s = load(data("textured.gltf"));
  ASSERT_EQ(s.materials.size(), 1u);
  const Material& m = s.materials[0];
  ASSERT_GE(m.base_color_texture, 0);
  ASSERT_GE(m.metallic_roughness_texture, 0);
  EXPECT_EQ(m.emissive_texture, m.base_color_texture);  // same image, sampler and colour space
  EXPECT_EQ(s.textures.size(), 2u);
  const Texture& colour = s.textures[size_t(m.base_color_texture)];
  const Texture& data_tex = s.textures[size_t(m.metallic_roughness_texture)];
  ASSERT_EQ(colour.width, 2);
  ASSERT_EQ(colour.height, 2);
  // One 8-bit image, stored once and read as colour (sRGB) or as data.
  EXPECT_EQ(colour.format, TexelFormat::Rgba8Srgb);
  EXPECT_EQ(data_tex.format, TexelFormat::Rgba8Unorm);
  EXPECT_EQ(colour.words, data_tex.words);
  auto texels = [](const Texture& t) {
    std::vector<glm::vec4> v;
    for (int y = 0; y < t.height; ++y)
      for (int x = 0; x < t.width; ++x) v.push_back(t.texel(x, y));
    return v;
  };
  const std::vector<glm::vec4> c = texels(colour), d = texels(data_tex);
  // 8-bit values decoded in float: within a few ulps.
  constexpr float tol = 1e-6f;
  EXPECT_NEAR(c[0].r, 1.0f, tol);
  EXPECT_NEAR(c[0].g, kLin128, tol);
  EXPECT_NEAR(c[1].r, kLin188, tol);
  EXPECT_NEAR(c[1].g, kLin64, tol);
  EXPECT_NEAR(c[1].b, kLin32, tol);
  EXPECT_NEAR(c[1].a, 128.0f / 255.0f, tol);  // alpha is linear
  EXPECT_NEAR(d[0].g, 128.0f / 255.0f, tol);  // metallic-roughness: as stored
  EXPECT_NEAR(d[1].r, 188.0f / 255.0f, tol);
  EXPECT_EQ(c[2], glm::vec4(0, 0, 0, 1));
  EXPECT_EQ(c[3], glm::vec4(1, 1, 1, 1));
  // Sampler: NEAREST, CLAMP_TO_EDGE in s, MIRRORED_REPEAT in t.
  EXPECT_EQ(colour.filter, Filter::Nearest);
  EXPECT_EQ(colour.wrap_s, Wrap::ClampToEdge);
  EXPECT_EQ(colour.wrap_t, Wrap::MirroredRepeat);
  EXPECT_EQ(m.emissive, glm::vec3(2.0f));  // emissiveFactor 1 x KHR_materials_emissive_strength 2
  EXPECT_EQ(m.metallic, 0.0f);
  EXPECT_TRUE(s.features.textures);
  EXPECT_FALSE(s.features.normal_maps);
}

TEST(Loader, EmissiveRadianceIsTextureAveraged) {
  const Scene s = load(data("textured.gltf"));
  ASSERT_EQ(s.emissive_triangles.size(), 2u);
  // The unit quad's UVs cover the 2x2 texture; T00 = (1, lin128, 0), T10 = (lin188, lin64,
  // lin32), T01 = black, T11 = white. Triangle 0 (v >= u) covers a quarter of T00, half of
  // T01 and a quarter of T11 by area; triangle 1 (v <= u) a quarter of T00, half of T10 and
  // a quarter of T11. Radiance = 2 (emissive) x that mean.
  const glm::vec3 t00(1.0f, kLin128, 0.0f), t10(kLin188, kLin64, kLin32), t11(1.0f);
  const glm::vec3 expected[2] = {2.0f * (0.25f * t00 + 0.25f * t11), 2.0f * (0.25f * t00 + 0.5f * t10 + 0.25f * t11)};
  for (int k = 0; k < 2; ++k) {
    const auto& e = s.emissive_triangles[size_t(k)];
    EXPECT_EQ(e.triangle, uint32_t(k));
    EXPECT_FLOAT_EQ(e.area, 0.5f);
    expect_vec(e.radiance, expected[k], 1e-5f);
    const double lum = 0.2126 * expected[k].r + 0.7152 * expected[k].g + 0.0722 * expected[k].b;
    EXPECT_NEAR(e.power, std::numbers::pi * 0.5 * lum, 1e-5);  // one-sided
  }
}

TEST(Loader, MaterialsAndExtensions) {
  const Scene s = load(data("materials.gltf"));
  ASSERT_EQ(s.materials.size(), 3u);
  const Material& lambert = s.materials[0];
  EXPECT_EQ(lambert.name, "lambert");
  EXPECT_EQ(lambert.base_color, glm::vec4(0.5f, 0.25f, 0.125f, 1.0f));
  EXPECT_EQ(lambert.metallic, 0.0f);
  EXPECT_EQ(lambert.roughness, 1.0f);  // glTF default
  EXPECT_EQ(lambert.specular, 0.0f);
  EXPECT_FALSE(lambert.has_specular_lobe());  // KHR_materials_specular factor 0: pure Lambert
  EXPECT_EQ(lambert.alpha_mode, AlphaMode::Opaque);
  EXPECT_FALSE(lambert.double_sided);

  const Material& masked = s.materials[1];
  EXPECT_EQ(masked.alpha_mode, AlphaMode::Mask);
  EXPECT_EQ(masked.alpha_cutoff, 0.25f);
  EXPECT_TRUE(masked.double_sided);
  EXPECT_EQ(masked.roughness, 0.3f);
  EXPECT_EQ(masked.specular, 0.5f);
  EXPECT_EQ(masked.specular_color, glm::vec3(1.0f, 0.5f, 0.25f));
  EXPECT_TRUE(masked.has_specular_lobe());
  EXPECT_EQ(masked.normal_scale, 0.5f);
  ASSERT_GE(masked.normal_texture, 0);
  ASSERT_GE(masked.specular_color_texture, 0);
  // One image (texel 128, 128, 255) in two colour spaces: the normal map as stored, the
  // specular colour decoded from sRGB.
  EXPECT_EQ(s.textures.size(), 2u);
  const glm::vec4 n = s.textures[size_t(masked.normal_texture)].texel(0, 0);
  const glm::vec4 c = s.textures[size_t(masked.specular_color_texture)].texel(0, 0);
  EXPECT_NEAR(n.r, 128.0f / 255.0f, 1e-6f);
  EXPECT_NEAR(c.r, kLin128, 1e-6f);
  EXPECT_NEAR(c.b, 1.0f, 1e-6f);

  EXPECT_EQ(s.materials[2].emissive, glm::vec3(8.0f, 4.0f, 2.0f));  // factor x strength 8
  EXPECT_EQ(s.materials[2].alpha_mode, AlphaMode::Blend);
  EXPECT_EQ(s.materials[2].coverage(s.materials[2].base_color.a), 0.5f);
  EXPECT_TRUE(s.features.alpha_mask && s.features.double_sided && s.features.one_sided);
  EXPECT_TRUE(s.features.normal_maps && s.features.textures && s.features.specular && s.features.emissive_meshes);
}

// Two mappings in one material (MultiUVTest, TextureTransformMultiTest): the base colour on
// TEXCOORD_0 as it is, the emissive and normal textures on TEXCOORD_1 with a transform, which
// lands in Mesh::uvs2 with their slots marked.
TEST(Loader, TexturesOnTwoMappingsKeepBoth) {
  const Scene s = load(data("two_uv_sets.gltf"));
  EXPECT_TRUE(s.warnings.empty());
  const Material& m = s.materials[0];
  ASSERT_EQ(m.name, "two_sets");
  EXPECT_EQ(m.uv2_slots, uint32_t(kEmissiveSlot | kNormalSlot));
  EXPECT_GE(m.base_color_texture, 0);
  EXPECT_GE(m.emissive_texture, 0);
  EXPECT_GE(m.normal_texture, 0);
  EXPECT_EQ(s.materials[1].uv2_slots, 0u);
  const Mesh& floor = s.meshes[0];
  ASSERT_EQ(floor.name, "floor");
  ASSERT_EQ(floor.uvs.size(), 4u);
  ASSERT_EQ(floor.uvs2.size(), 4u);
  const glm::vec2 uv0[4] = {{0, 2}, {2, 2}, {2, 0}, {0, 0}}, uv1[4] = {{1, 0}, {1, 1}, {0, 1}, {0, 0}};
  // KHR_texture_transform: offset + R(rotation) * scale * uv, R = [cos sin; -sin cos].
  const double c = std::cos(0.5), sn = std::sin(0.5);
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(floor.uvs[i], uv0[i]);
    const double x = 2.0 * uv1[i].x, y = 1.5 * uv1[i].y;
    EXPECT_NEAR(floor.uvs2[i].x, 0.25 + c * x + sn * y, 1e-6);
    EXPECT_NEAR(floor.uvs2[i].y, -sn * x + c * y, 1e-6);
  }
  EXPECT_TRUE(s.meshes[1].uvs.empty() && s.meshes[1].uvs2.empty());
  // Mesh::uv_at interpolates the mapping asked for.
  EXPECT_NEAR(floor.uv_at(floor.triangles[0], 0.25f, 0.5f, true).x,
              0.25f * floor.uvs2[floor.triangles[0].x].x + 0.25f * floor.uvs2[floor.triangles[0].y].x + 0.5f * floor.uvs2[floor.triangles[0].z].x,
              1e-6);
}

TEST(Loader, TextureTransformAndSecondUvSetAreAppliedToTheUvs) {
  const Scene s = load(data("uv_sets.gltf"));
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_TRUE(s.warnings.empty());
  // Both quads carry TEXCOORD_1 = ((x + 1) / 2, (z + 1) / 2) and a TEXCOORD_0 shifted by 7 that
  // no material reads.
  auto uv1 = [&](const Mesh& m, size_t i) {
    const glm::dvec3 p = world(s, m.positions[i]) - glm::dvec3(m.name == "override" ? 3.0 : 0.0, 0.0, 0.0);
    return glm::dvec2((p.x + 1.0) / 2.0, (p.z + 1.0) / 2.0);
  };
  // KHR_texture_transform's own example (offset (0, 1), rotation pi/2, scale 0.5): the unit
  // square maps onto the image's lower-left quadrant, turned clockwise: (u, v) -> (v/2, 1 - u/2).
  const Mesh& t = s.meshes[0];
  ASSERT_EQ(t.uvs.size(), t.positions.size());
  for (size_t i = 0; i < t.uvs.size(); ++i) {
    const glm::dvec2 a = uv1(t, i);
    EXPECT_NEAR(t.uvs[i].x, a.y / 2.0, 1e-6);
    EXPECT_NEAR(t.uvs[i].y, 1.0 - a.x / 2.0, 1e-6);
    EXPECT_TRUE(t.uvs[i].x >= -1e-6f && t.uvs[i].x <= 0.5f + 1e-6f && t.uvs[i].y >= 0.5f - 1e-6f && t.uvs[i].y <= 1.0f + 1e-6f);
  }
  // The transform's texCoord overrides the textureInfo's: TEXCOORD_1 shifted by (0.25, 0).
  const Mesh& o = s.meshes[1];
  ASSERT_EQ(o.uvs.size(), o.positions.size());
  for (size_t i = 0; i < o.uvs.size(); ++i) {
    EXPECT_NEAR(o.uvs[i].x, uv1(o, i).x + 0.25, 1e-6);
    EXPECT_NEAR(o.uvs[i].y, uv1(o, i).y, 1e-6);
  }
}

TEST(Loader, UnlitIorSpecGlossPointsLinesAndIgnoredExtensions) {
  const Scene s = load(data("extensions.gltf"));
  ASSERT_EQ(s.materials.size(), 4u);
  // KHR_materials_unlit: the base colour is emitted and nothing is reflected; alpha stays.
  const Material& unlit = s.materials[0];
  EXPECT_EQ(unlit.emissive, glm::vec3(0.2f, 0.4f, 0.6f));
  EXPECT_EQ(unlit.base_color, glm::vec4(0.0f, 0.0f, 0.0f, 0.5f));
  EXPECT_FALSE(unlit.has_specular_lobe());
  // KHR_materials_ior 2: F0 = ((2 - 1) / (2 + 1))^2 = 1/9 where the renderers' default is 0.04.
  const float ratio = float((1.0 / 9.0) / 0.04);
  EXPECT_NEAR(s.materials[1].specular_color.r, ratio, 1e-6f * ratio);
  EXPECT_EQ(s.materials[1].specular_color.r, s.materials[1].specular_color.b);
  // KHR_materials_pbrSpecularGlossiness, converted: F0 = specular (min(0.04 x specular_color,
  // 1) in the renderers), base colour = diffuse, roughness = 1 - glossiness x texel A.
  for (int k : {2, 3}) {
    const Material& sg = s.materials[size_t(k)];
    EXPECT_EQ(sg.base_color, glm::vec4(0.5f, 0.25f, 0.125f, 1.0f));
    EXPECT_EQ(sg.metallic, 0.0f);
    EXPECT_EQ(sg.specular, 1.0f);
    EXPECT_NEAR(0.04f * sg.specular_color.r, 0.02f, 1e-8f);
    EXPECT_NEAR(0.04f * sg.specular_color.b, 0.08f, 1e-8f);
    ASSERT_GE(sg.specular_color_texture, 0);
    EXPECT_EQ(s.textures[size_t(sg.specular_color_texture)].format, TexelFormat::Rgba8Srgb);
    ASSERT_GE(sg.metallic_roughness_texture, 0);
    const Texture& r = s.textures[size_t(sg.metallic_roughness_texture)];
    const float gloss = k == 2 ? 1.0f : 0.75f;
    EXPECT_EQ(r.format, k == 2 ? TexelFormat::Rgba8Unorm : TexelFormat::Rgba32F);  // exact bytes when the factor is 1
    EXPECT_NEAR(sg.roughness * r.texel(0, 0).g, 1.0f - gloss * 64.0f / 255.0f, 1e-6f);
    EXPECT_NEAR(sg.roughness * r.texel(1, 0).g, 1.0f - gloss, 1e-6f);
    EXPECT_EQ(r.texel(0, 0).b, 1.0f);  // metallic texel 1 x factor 0
  }
  // Two triangles; the points and the line strip are dropped with one warning that counts them.
  EXPECT_EQ(s.stats.triangles, 2u);
  ASSERT_EQ(s.warnings.size(), 4u);
  EXPECT_NE(s.warnings[0].find("KHR_materials_clearcoat is not implemented and was ignored: materials have no clear-coat layer"), std::string::npos);
  EXPECT_NE(s.warnings[1].find("EXT_made_up is not implemented"), std::string::npos);  // KHR_xmp_json_ld: metadata, silent
  EXPECT_EQ(s.warnings[2].rfind("materials[2].extensions.KHR_materials_pbrSpecularGlossiness: converted", 0), 0u);
  EXPECT_NE(s.warnings[2].find("(2 times in the file)"), std::string::npos);
  EXPECT_EQ(s.warnings[3].rfind("meshes[0].primitives[2].mode: a primitive of points or lines", 0), 0u);
  EXPECT_NE(s.warnings[3].find("(2 times in the file)"), std::string::npos);
}

TEST(Loader, GpuInstancingAndQuantizedAttributes) {
  const Scene s = load(data("instancing.gltf"));
  ASSERT_EQ(s.meshes.size(), 3u);
  // Node: translate (0, 5, 0), scale 0.001; the positions are 16-bit integers (0..1000), the UVs
  // 8-bit integers, the normals 8-bit normalized (127 -> 1).
  const glm::dvec3 corners[3][3] = {{{0, 5, 0}, {1, 5, 0}, {0, 6, 0}},              // instance 0: identity
                                    {{0.01, 5, 0}, {0.01, 6, 0}, {-0.99, 5, 0}},     // T(10, 0, 0) Rz(90)
                                    {{0, 5, 0.01}, {2, 5, 0.01}, {0, 7, 0.01}}};     // T(0, 0, 10) S(2)
  for (size_t k = 0; k < 3; ++k) {
    const Mesh& m = s.meshes[k];
    EXPECT_EQ(m.name, "crowd");
    EXPECT_EQ(m.object_id, 1u);
    ASSERT_EQ(m.positions.size(), 3u);
    for (size_t i = 0; i < 3; ++i) expect_world(s, m.positions[i], corners[k][i]);
    for (const auto& n : m.normals) expect_vec(n, {0, 0, 1});
    EXPECT_EQ(m.uvs[1], glm::vec2(2.0f, 0.0f));
    EXPECT_EQ(m.uvs[2], glm::vec2(0.0f, 2.0f));
  }
}

TEST(Loader, VertexColoursMultiplyTheBaseColour) {
  const Scene s = load(data("textured_room.gltf"));
  EXPECT_TRUE(s.features.vertex_colors);
  const auto mesh = [&](const std::string& name) {
    return *std::find_if(s.meshes.begin(), s.meshes.end(), [&](const Mesh& m) { return m.name == name; });
  };
  const Mesh wall = mesh("wall"), grating = mesh("grating"), floor = mesh("floor");
  ASSERT_EQ(wall.colors.size(), wall.positions.size());
  EXPECT_EQ(wall.colors[0], glm::vec4(1.0f, 0.6f, 0.6f, 1.0f));
  EXPECT_TRUE(floor.colors.empty());  // no COLOR_0: white
  EXPECT_EQ(floor.color_at(floor.triangles[0], 0.3f, 0.3f), glm::vec4(1.0f));
  // Interpolated like every other attribute: the centre of the grating's diagonal is between
  // alpha 1 (vertices 0, 1) and 0.2 (vertices 2, 3).
  const glm::uvec3 t = grating.triangles[0];  // 0, 1, 2
  EXPECT_NEAR(grating.color_at(t, 0.0f, 0.5f).a, 0.5f * (grating.colors[t.x].a + grating.colors[t.z].a), 1e-6f);
}

TEST(Loader, TangentsFollowTheNodeAndItsHandedness) {
  const Scene s = load(data("materials.gltf"));
  ASSERT_EQ(s.meshes.size(), 4u);
  const Mesh& plain = s.meshes[1];
  const Mesh& mirror = s.meshes[3];
  EXPECT_EQ(mirror.name, "masked_mirror");
  ASSERT_EQ(plain.tangents.size(), 4u);
  ASSERT_EQ(mirror.tangents.size(), 4u);
  for (const auto& t : plain.tangents) EXPECT_EQ(t, glm::vec4(1, 0, 0, 1));
  // scale (-1, 1, 1): the tangent turns to -X and the bitangent sign flips with the mirror.
  for (const auto& t : mirror.tangents) EXPECT_EQ(t, glm::vec4(-1, 0, 0, -1));
  for (const auto& nrm : mirror.normals) expect_vec(nrm, {0, 1, 0});
  for (size_t t = 0; t < mirror.triangles.size(); ++t) expect_vec(face_normal(mirror, t), {0, 1, 0});
  EXPECT_EQ(mirror.uvs.size(), 4u);
}

TEST(Loader, LightsCamerasAndExtras) {
  const Scene s = load(data("lights_cameras.gltf"));
  EXPECT_EQ(s.origin, glm::dvec3(100, 0, 0));  // the floor, under the room node's translation
  ASSERT_EQ(s.lights.size(), 3u);
  const Light& sun = s.lights[0];
  EXPECT_EQ(sun.type, LightType::Directional);
  EXPECT_EQ(sun.name, "sun");
  expect_vec(sun.direction, {0, -1, 0});  // -Z turned -90 degrees about X
  expect_vec(sun.color, {1.0f, 0.9f, 0.8f});
  EXPECT_EQ(sun.intensity, 3.0f);
  const Light& bulb = s.lights[1];
  EXPECT_EQ(bulb.type, LightType::Point);
  EXPECT_EQ(bulb.name, "bulb");  // the light has no name: its node's
  expect_world(s, bulb.position, {100, 2, 0});
  EXPECT_EQ(bulb.range, 5.0f);
  const Light& spot = s.lights[2];
  EXPECT_EQ(spot.type, LightType::Spot);
  expect_world(s, spot.position, {100, 3, 0});
  expect_vec(spot.direction, {0, -1, 0});
  EXPECT_FLOAT_EQ(spot.inner_cone, 0.2f);
  EXPECT_FLOAT_EQ(spot.outer_cone, 0.5f);
  EXPECT_TRUE(s.features.directional_lights && s.features.point_lights && s.features.spot_lights);

  ASSERT_EQ(s.views.size(), 6u);
  const View& cam = s.views[0];
  EXPECT_EQ(cam.name, "cam");
  EXPECT_EQ(cam.node, 5);
  expect_world(s, cam.camera.position, {100, 1, 5});
  expect_vec(cam.camera.forward, {0, 0, -1});
  expect_vec(cam.camera.up, {0, 1, 0});
  expect_vec(cam.camera.right, {1, 0, 0});
  EXPECT_FLOAT_EQ(cam.camera.yfov, 0.8f);
  EXPECT_FLOAT_EQ(cam.camera.znear, 0.1f);
  EXPECT_FLOAT_EQ(cam.camera.zfar, 100.0f);
  const View& overview = s.views[1];
  EXPECT_EQ(overview.name, "overview");  // unnamed node: the camera's name
  expect_vec(overview.camera.forward, {0, -1, 0});
  expect_vec(overview.camera.up, {0, 0, -1});
  EXPECT_FALSE(overview.camera.orthographic());
  // Orthographic: |ymag| = 1.5 scaled by the node's 2; looking along the node's -Z.
  const View& plan = s.views[2];
  EXPECT_EQ(plan.name, "plan");
  EXPECT_TRUE(plan.camera.orthographic());
  EXPECT_FLOAT_EQ(plan.camera.ymag, 3.0f);
  expect_world(s, plan.camera.position, {100, 0, 8});
  expect_vec(plan.camera.forward, {0, 0, -1});
  EXPECT_EQ(std::count_if(s.warnings.begin(), s.warnings.end(),
                          [](const std::string& w) { return w.find("cameras[2].orthographic.ymag is negative") != std::string::npos; }),
            1);
  const View& corner = s.views[3];
  EXPECT_EQ(corner.name, "corner");
  EXPECT_EQ(corner.node, -1);
  expect_world(s, corner.camera.position, {104, 1, 4});
  expect_vec(corner.camera.forward, {-std::sqrt(0.5f), 0, -std::sqrt(0.5f)});
  EXPECT_NEAR(corner.camera.yfov, std::numbers::pi / 3, 1e-6);
  const View& top = s.views[4];
  expect_vec(top.camera.forward, {0, -1, 0});
  expect_vec(top.camera.up, {0, 0, -1});
  EXPECT_NEAR(top.camera.yfov, std::numbers::pi / 4, 1e-6);  // default 45 degrees
  EXPECT_FALSE(top.camera.orthographic());
  EXPECT_FLOAT_EQ(s.views[5].camera.ymag, 2.5f);  // an orthographic view from extras
  EXPECT_EQ(&s.view("corner"), &s.views[3]);
  EXPECT_EQ(&s.view("3"), &s.views[3]);
  EXPECT_THROW(s.view("kitchen"), InputError);

  EXPECT_EQ(s.leak_regions, std::vector<std::string>{"floor"});
  EXPECT_EQ(s.leak_object_ids, std::vector<uint32_t>{2});  // node 1 + 1
  EXPECT_EQ(s.meshes[0].object_id, 2u);
  EXPECT_EQ(s.environment, glm::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_TRUE(s.features.environment);
  EXPECT_EQ(s.sequence.frames, 1);
  EXPECT_EQ(s.sequence.fps, 24.0);
  EXPECT_EQ(s.sequence.animation, -1);
  EXPECT_FALSE(s.features.animation);
}

TEST(Loader, BinaryGltf) {
  const Scene s = load(data("quad_tri.glb"));
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.stats.triangles, 3u);
  EXPECT_EQ(s.meshes[1].name, "tri");
  expect_world(s, s.meshes[1].positions[0], {0, 0, 2});
}

TEST(Loader, BinaryGltfWithImageInTheBinChunk) {
  const Scene s = load(data("textured.glb"));
  ASSERT_EQ(s.textures.size(), 1u);
  const Texture& t = s.textures[0];
  ASSERT_EQ(t.width, 1);
  ASSERT_EQ(t.height, 2);
  EXPECT_EQ(t.texel(0, 0), glm::vec4(1, 0, 0, 1));  // sRGB 255 and 0 decode exactly
  EXPECT_EQ(t.texel(0, 1), glm::vec4(0, 0, 1, 1));
  EXPECT_EQ(s.materials[0].base_color_texture, 0);
}

TEST(Loader, ContentHashCoversReferencedFiles) {
  namespace fs = std::filesystem;
  const Scene original = load(data("external.gltf"));
  EXPECT_EQ(original.content_hash.size(), 16u);
  EXPECT_EQ(original.meshes.size(), 1u);
  const fs::path dir = fs::temp_directory_path() / ("giq_scenes_hash_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy_file(data("external.gltf"), dir / "external.gltf");
  fs::copy_file(data("external data.bin"), dir / "external data.bin");
  EXPECT_EQ(load(dir / "external.gltf").content_hash, original.content_hash);  // same bytes, other folder
  {
    std::fstream f(dir / "external data.bin", std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(0);
    f.put('\x01');  // changes the first vertex's x by a denormal: same geometry to the eye
  }
  const Scene changed = load(dir / "external.gltf");
  EXPECT_NE(changed.content_hash, original.content_hash);
  fs::remove_all(dir);
}

// A buffer saved under its URI's undecoded name ("external%20data.bin" on disk for the URI
// "external%20data.bin", which names "external data.bin") is read with a warning; where the
// decoded name exists too, it is the one read.
TEST(Loader, FileNamedAsItsUndecodedUriIsReadWithAWarning) {
  namespace fs = std::filesystem;
  const Scene original = load(data("external.gltf"));
  EXPECT_TRUE(original.warnings.empty());
  const fs::path dir = fs::temp_directory_path() / ("giq_scenes_literal_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy_file(data("external.gltf"), dir / "external.gltf");
  fs::copy_file(data("external data.bin"), dir / "external%20data.bin");
  const Scene literal = load(dir / "external.gltf");
  ASSERT_EQ(literal.meshes.size(), original.meshes.size());
  EXPECT_EQ(literal.meshes[0].positions, original.meshes[0].positions);
  EXPECT_EQ(literal.content_hash, original.content_hash);  // the same bytes under the same URI
  ASSERT_EQ(literal.warnings.size(), 1u);
  EXPECT_NE(literal.warnings[0].find("buffers[0].uri: no file 'external data.bin'"), std::string::npos) << literal.warnings[0];
  // The decoded name wins where both exist: one byte too many there fails the byteLength check.
  {
    std::ofstream f(dir / "external data.bin", std::ios::binary);
    f << std::ifstream(data("external data.bin"), std::ios::binary).rdbuf() << '\0';
  }
  try {
    load(dir / "external.gltf");
    ADD_FAILURE() << "loaded the literal file where the decoded one exists";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "buffers[0].byteLength") << e.what();
  }
  fs::remove_all(dir);
}

// Names in a legacy encoding (glTF's JSON is UTF-8): bytes of no UTF-8 sequence, a raw control
// character and a backslash that starts no escape (GBK's two-byte characters may end in 0x5C)
// are each replaced by U+FFFD, with a warning that counts them; well-formed UTF-8 (two-, three-
// and four-byte sequences) and escapes are kept as they are.
TEST(Loader, StringsThatAreNotUtf8AreRepaired) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("giq_scenes_utf8_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string json = giq::test::slurp(data("transforms.gltf"));
  const auto with_name = [&](const std::string& name) {
    // The first node's name, which its mesh takes.
    const size_t key = json.find("\"name\"", json.find("\"nodes\""));
    const size_t open = json.find('"', json.find(':', key)) + 1, close = json.find('"', open);
    std::string text = json;
    text.replace(open, close - open, name);
    std::ofstream(dir / "named.gltf", std::ios::binary) << text;
    return load(dir / "named.gltf");
  };
  const Scene good = with_name("Caf\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x94\xA5 \\\" \\u00e9");
  EXPECT_TRUE(good.warnings.empty());
  EXPECT_EQ(good.meshes[0].name, "Caf\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x94\xA5 \" \xC3\xA9");
  // 0xF3 0x77: a lead byte without its continuation; 0x17: a control character; 0xB9 0x5C 0x17:
  // GBK's two-byte character ending in a backslash, then what would be escaped; 0xC0 0x80: an
  // overlong NUL; 0xED 0xA0 0x80: a surrogate.
  const Scene bad = with_name("M\xF3w\x17 \xB9\\\x17 \xC0\x80 \xED\xA0\x80");
  ASSERT_EQ(bad.warnings.size(), 1u);
  EXPECT_EQ(bad.warnings[0].rfind("JSON: 10 bytes in strings replaced by U+FFFD", 0), 0u) << bad.warnings[0];
  const std::string r = "\xEF\xBF\xBD";
  EXPECT_EQ(bad.meshes[0].name, "M" + r + "w" + r + " " + r + r + r + " " + r + r + " " + r + r + r);
  EXPECT_EQ(bad.meshes.size(), good.meshes.size());
  fs::remove_all(dir);
}

}  // namespace
}  // namespace giq::scenes
