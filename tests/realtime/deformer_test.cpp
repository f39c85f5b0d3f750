// The deformation pass (realtime/shaders/deform.comp) against the scene library's posing on
// the CPU in double precision (scenes/src/placement.cpp): every deformed vertex's position,
// normal and tangent within a bound derived from float rounding; and the BVH bounds the GPU
// refits from those vertices against refit_bvh over the same vertices, bit for bit.
//
// The bounds (Higham 2002, "Accuracy and Stability of Numerical Algorithms", §3.1: a sum or dot
// product of n terms in float is within gamma_n = n u / (1 - n u) of its exact value, relative to
// the sum of the terms' magnitudes; u = 2^-24): the position sums K morph displacements (two
// roundings each, the product and the sum), up to 4 x `sets` weighted matrices (two each), then
// a matrix-vector product (four); the matrices and weights are rounded from double once each.
// So |gpu - cpu| <= (2K + 8 sets + 8) u A + u |p|, where A = sum_j w_j |J_j| (|r| + sum_k |w_k|
// |d_k|, 1) bounds every term's magnitude, and u |p| is the CPU's own rounding of its double
// result. A normal is the cofactor matrix times the morphed normal, normalised: its error is
// that count times u times the condition kappa = || |C| |r| || / || C r || (|C| the cofactor of
// |L|), doubled for the normalisation. Flat normals are cross products of the corners, whose
// errors are the positions' bounds.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "giq/realtime/bvh_refitter.h"
#include "giq/realtime/scene_gpu.h"
#include "scene_gpu_checks.h"
#include "shaders/scene_shared.h"
#include "test_scenes.h"

namespace giq::realtime {
namespace {

constexpr double kU = 0x1p-24;

class DeformerTest : public test::VulkanTest {};

scenes::Scene test_scene(const char* file) { return scenes::load(std::filesystem::path(GIQ_TEST_DATA) / "scenes" / file); }

glm::dmat3 cofactor(const glm::dmat3& L) { return glm::dmat3(glm::cross(L[1], L[2]), glm::cross(L[2], L[0]), glm::cross(L[0], L[1])); }
glm::dmat3 abs(const glm::dmat3& L) { return glm::dmat3(glm::abs(L[0]), glm::abs(L[1]), glm::abs(L[2])); }
glm::dmat4 abs(const glm::mat4& M) {
  glm::dmat4 a;
  for (int c = 0; c < 4; ++c) a[c] = glm::abs(glm::dvec4(M[c]));
  return a;
}

// What one deformed vertex's float evaluation is bounded by.
struct VertexBound {
  double position = 0.0;  // max-norm
  double normal = 0.0;    // 2-norm of the unit normal's error
};

// Rest vertex v of `d` posed in double with the terms' magnitudes: the bound's A and the
// condition of its normal.
VertexBound bound(const scenes::Deformation& d, uint32_t v, const glm::vec3& cpu_position) {
  const scenes::DeformationRest& r = *d.rest;
  glm::dvec3 mag_p = glm::abs(glm::dvec3(r.positions[v])), morphed_n(0.0), mag_n(0.0);
  if (!r.normals.empty()) morphed_n = r.normals[v], mag_n = glm::abs(morphed_n);
  for (size_t k = 0; k < r.targets.size(); ++k) {
    const double w = d.weights[k];
    if (k < r.targets.size() && !r.targets[k].positions.empty()) mag_p += std::abs(w) * glm::abs(glm::dvec3(r.targets[k].positions[v]));
    if (!r.targets[k].normals.empty() && !r.normals.empty()) {
      morphed_n += w * glm::dvec3(r.targets[k].normals[v]);
      mag_n += std::abs(w) * glm::abs(glm::dvec3(r.targets[k].normals[v]));
    }
  }
  glm::dmat4 S(0.0), mag_S(0.0);
  size_t sets = 0;
  if (d.skinned) {
    sets = r.joints.size();
    for (size_t s = 0; s < sets; ++s)
      for (int c = 0; c < 4; ++c) {
        const double w = r.weights[s][v][c];
        if (w == 0.0) continue;
        S += w * glm::dmat4(d.joints[r.joints[s][v][c]]);
        mag_S += w * abs(d.joints[r.joints[s][v][c]]);
      }
  } else {
    S = glm::dmat4(d.joints[0]), mag_S = abs(d.joints[0]);
  }
  const double n = 2.0 * double(r.targets.size()) + 8.0 * double(sets) + 8.0;
  const glm::dvec4 A = mag_S * glm::dvec4(mag_p, 1.0);
  VertexBound b;
  b.position = n * kU * std::max({A.x, A.y, A.z}) + kU * double(std::max({std::abs(cpu_position.x), std::abs(cpu_position.y), std::abs(cpu_position.z)}));
  if (!r.normals.empty()) {
    const glm::dvec3 Cr = cofactor(glm::dmat3(S)) * morphed_n;
    const double kappa = glm::length(cofactor(abs(glm::dmat3(mag_S))) * mag_n) / glm::length(Cr);
    b.normal = 2.0 * (n + 12.0) * kU * kappa;
  }
  return b;
}

// Every deformed vertex of `posed` as the GPU holds it against the CPU's.
void expect_vertices_agree(const SceneGpu& gpu, const scenes::Scene& posed, const std::string& what) {
  const std::vector<gpu::GpuVertex> vertices = test::vertex_rows(gpu.vertices());
  const FlatGeometry& g = gpu.geometry();
  size_t checked = 0;
  double worst_position = 0.0, worst_normal = 0.0;  // error / bound
  for (size_t m = 0; m < posed.meshes.size(); ++m) {
    const scenes::Mesh& mesh = posed.meshes[m];
    if (!mesh.deformation) continue;
    const scenes::Deformation& d = *mesh.deformation;
    const bool faceted = d.rest->normals.empty();
    std::vector<VertexBound> bounds(mesh.positions.size());
    for (uint32_t i = 0; i < mesh.positions.size(); ++i) {
      glm::uvec3 t = faceted ? d.rest->triangles[i / 3] : glm::uvec3(i);
      if (faceted && d.mirrored) std::swap(t.y, t.z);
      bounds[i] = bound(d, t[i % 3], mesh.positions[i]);
    }
    for (uint32_t i = 0; i < mesh.positions.size(); ++i) {
      const gpu::GpuVertex& v = vertices[g.mesh_first_vertex[m] + i];
      const double ep = double(std::max({std::abs(v.position.x - mesh.positions[i].x), std::abs(v.position.y - mesh.positions[i].y),
                                         std::abs(v.position.z - mesh.positions[i].z)}));
      EXPECT_LE(ep, bounds[i].position) << what << ", " << mesh.name << " vertex " << i;
      worst_position = std::max(worst_position, ep / bounds[i].position);
      double normal_bound = bounds[i].normal;
      if (faceted) {
        // The face of the vertex's own triangle: errors of its corners' positions, through the
        // cross product (first order), doubled for the normalisation.
        const uint32_t k = 3 * (i / 3);
        const glm::dvec3 a = mesh.positions[k], b = mesh.positions[k + 1], c = mesh.positions[k + 2];
        const double ea = std::sqrt(3.0) * bounds[k].position, eb = std::sqrt(3.0) * bounds[k + 1].position,
                     ec = std::sqrt(3.0) * bounds[k + 2].position;
        const double area2 = glm::length(glm::cross(b - a, c - a));
        const double dcross = (ea + eb) * glm::length(c - a) + (ea + ec) * glm::length(b - a) + 6.0 * kU * glm::length(b - a) * glm::length(c - a);
        normal_bound = area2 > 0.0 ? 2.0 * dcross / area2 : 2.0;
      }
      const double en = glm::length(glm::dvec3(glm::vec3(v.normal) - mesh.normals[i]));
      EXPECT_LE(en, normal_bound) << what << ", " << mesh.name << " vertex " << i << " normal";
      worst_normal = std::max(worst_normal, en / std::max(normal_bound, 1e-300));
      ++checked;
    }
  }
  EXPECT_EQ(checked, gpu.deformed_vertex_count()) << what;
  EXPECT_GT(checked, 0u) << what;
  ::testing::Test::RecordProperty(what + " worst position error / bound", std::to_string(worst_position));
  ::testing::Test::RecordProperty(what + " worst normal error / bound", std::to_string(worst_normal));
}

void check_sequence(Context& ctx, ShaderCompiler& compiler, const scenes::Scene& scene, const std::vector<int>& frames, const std::string& name) {
  SceneGpu gpu(ctx, compiler, scene.at_frame(frames[0]));
  expect_vertices_agree(gpu, scene.at_frame(frames[0]), name + " frame " + std::to_string(frames[0]));
  test::expect_tree_exact(gpu, name + " frame " + std::to_string(frames[0]));
  for (size_t k = 1; k < frames.size(); ++k) {
    const scenes::Scene posed = scene.at_frame(frames[k]);
    gpu.update(posed);
    expect_vertices_agree(gpu, posed, name + " frame " + std::to_string(frames[k]));
    test::expect_tree_exact(gpu, name + " frame " + std::to_string(frames[k]));
  }
}

TEST_F(DeformerTest, SkinnedStripAgreesWithTheCpu) { check_sequence(*ctx, *compiler, test_scene("skinned.gltf"), {0, 10, 20, 30}, "skinned"); }

TEST_F(DeformerTest, MorphedQuadsAgreeWithTheCpu) { check_sequence(*ctx, *compiler, test_scene("morphed.gltf"), {0, 15, 30}, "morphed"); }

TEST_F(DeformerTest, CollapsingMorphAgreesWithTheCpu) {
  // Indexed and flat-shaded, up to the instant the triangle has no area.
  const scenes::Scene s = test_scene("collapsing.gltf");
  check_sequence(*ctx, *compiler, s, {0, s.sequence.frames / 2, s.sequence.frames - 1}, "collapsing");
}

TEST_F(DeformerTest, BlenderFigureAgreesWithTheCpu) {
  // 11 joints, up to 6 influences a vertex (JOINTS_1), two animated shape keys.
  check_sequence(*ctx, *compiler, test_scene("blender_figure.glb"), {0, 5, 15, 25}, "blender_figure");
}

TEST_F(DeformerTest, PreviousVerticesAreTheFrameBefore) {
  // The pass saves each vertex's value before overwriting it: after frames 3 then 9, the
  // previous vertices are frame 3's as the GPU deformed them.
  const scenes::Scene s = test_scene("blender_figure.glb");
  SceneGpu gpu(*ctx, *compiler, s.at_frame(3));
  const std::vector<uint8_t> frame3 = gpu.vertices().download();
  gpu.update(s.at_frame(9));
  EXPECT_EQ(gpu.previous_vertices().download(), frame3);
  EXPECT_NE(gpu.vertices().download(), frame3);
}

TEST_F(DeformerTest, TangentsOfATexturedMeshFollowItsMatrix) {
  // The normal-mapped back wall of the textured box given a morph-free deformation by one
  // matrix (rotation, non-uniform scale, shear, translation): the pass writes its tangents to
  // the vertex extras. Expected: the tangent by L, back in the tangent plane, normalised, in
  // double; its bound that of the normal (which it is projected against) plus its own
  // condition || |L| |t| || / || L t ||, over the projection's shrinking |t| / |t - n (n . t)|.
  scenes::Scene s = test::textured_box();
  auto wall = std::find_if(s.meshes.begin(), s.meshes.end(), [&](const scenes::Mesh& m) { return s.materials[size_t(m.material)].normal_texture >= 0; });
  ASSERT_NE(wall, s.meshes.end());
  // Tangents given (as a file's TANGENT would), along the wall's first edge, alternating in
  // handedness.
  const glm::vec3 edge = glm::normalize(wall->positions[wall->triangles[0].y] - wall->positions[wall->triangles[0].x]);
  for (size_t i = 0; i < wall->positions.size(); ++i) wall->tangents.emplace_back(edge, i % 2 ? -1.0f : 1.0f);
  auto rest = std::make_shared<scenes::DeformationRest>();
  rest->positions = wall->positions, rest->normals = wall->normals, rest->tangents = wall->tangents, rest->triangles = wall->triangles;
  rest->targets.push_back({});  // one target, weight 0: the morph path with nothing to add
  glm::dmat4 M(1.0);
  M[0] = {0.8, 0.3, 0.0, 0.0}, M[1] = {-0.2, 1.1, 0.4, 0.0}, M[2] = {0.1, 0.0, 1.7, 0.0}, M[3] = {0.25, -0.5, 0.75, 1.0};
  const glm::dmat3 L(M), C = cofactor(L);
  const double handedness = glm::determinant(L) < 0.0 ? -1.0 : 1.0;
  std::vector<glm::dvec3> normals, tangents;
  for (size_t i = 0; i < rest->positions.size(); ++i) {
    wall->positions[i] = glm::vec3(M * glm::dvec4(rest->positions[i], 1.0));
    normals.push_back(glm::normalize(handedness * (C * glm::dvec3(rest->normals[i]))));
    glm::dvec3 t = L * glm::dvec3(rest->tangents[i]);
    tangents.push_back(glm::normalize(t - normals.back() * glm::dot(normals.back(), t)));
    wall->normals[i] = glm::vec3(normals.back());
    wall->tangents[i] = glm::vec4(glm::vec3(tangents.back()), rest->tangents[i].w < 0.0f ? -handedness : handedness);
  }
  scenes::Deformation d;
  d.rest = rest;
  d.joints = {glm::mat4(M)};
  d.weights = {0.0f};
  wall->deformation = d;
  s.derive();
  ASSERT_TRUE(s.features.morph_targets);

  SceneGpu gpu(*ctx, *compiler, s);
  ASSERT_EQ(gpu.deformed_vertex_count(), rest->positions.size());
  const std::vector<uint8_t> bytes = gpu.vertex_extra().download();
  const size_t first = gpu.geometry().mesh_first_vertex[size_t(wall - s.meshes.begin())];
  for (size_t i = 0; i < rest->positions.size(); ++i) {
    gpu::GpuVertexExtra e;
    std::memcpy(&e, bytes.data() + (first + i) * sizeof(e), sizeof(e));
    const VertexBound b = bound(d, uint32_t(i), wall->positions[i]);
    const glm::dvec3 t = L * glm::dvec3(rest->tangents[i]);
    const double projected = glm::length(t - normals[i] * glm::dot(normals[i], t));
    const double kappa = glm::length(abs(L) * glm::abs(glm::dvec3(rest->tangents[i]))) / glm::length(t);
    const double tangent_bound = (2.0 * 20.0 * kU * kappa + 2.0 * b.normal) * glm::length(t) / projected;
    EXPECT_LE(glm::length(glm::dvec3(glm::vec3(e.tangent)) - tangents[i]), tangent_bound) << "vertex " << i;
    EXPECT_EQ(e.tangent.w, wall->tangents[i].w) << "vertex " << i;
  }
}

TEST(RefitOrder, ChildrenComeOneLevelBeforeTheirParent) {
  std::vector<glm::vec3> p;
  std::vector<glm::uvec3> t;
  for (int i = 0; i < 200; ++i) {
    const float x = float(i % 17), y = float(i / 17);
    p.insert(p.end(), {{x, y, 0.0f}, {x + 0.5f, y, 0.0f}, {x, y + 0.5f, float(i % 3)}});
    t.emplace_back(3 * i, 3 * i + 1, 3 * i + 2);
  }
  const Bvh bvh = build_bvh(p, t);
  std::vector<std::pair<uint32_t, uint32_t>> levels;
  const std::vector<uint32_t> order = refit_order(bvh, levels);
  ASSERT_EQ(order.size(), bvh.nodes.size());
  std::vector<int> level_of(bvh.nodes.size(), -1);
  for (size_t l = 0; l < levels.size(); ++l)
    for (uint32_t k = levels[l].first; k < levels[l].first + levels[l].second; ++k) level_of[order[k]] = int(l);
  EXPECT_EQ(level_of[0], int(levels.size()) - 1);  // the root last
  for (size_t i = 0; i < bvh.nodes.size(); ++i) {
    ASSERT_GE(level_of[i], 0);
    if (bvh.nodes[i].count == 0) {
      EXPECT_EQ(level_of[i + 1], level_of[i] - 1);
      EXPECT_EQ(level_of[bvh.nodes[i].index], level_of[i] - 1);
    }
  }
}

}  // namespace
}  // namespace giq::realtime
