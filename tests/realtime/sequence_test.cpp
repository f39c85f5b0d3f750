// Sequences: one technique instance lives through an animated scene and follows what moves
// (the GPU scene is updated in place), and the G-buffer's motion vectors point to where each
// pixel's surface point was in the previous frame.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <functional>

#include "giq/realtime/renderer.h"
#include "giq/scenes/scene.h"
#include "giq/realtime/scene_gpu.h"
#include "giq/realtime/timer.h"
#include "passes/gbuffer.h"
#include "scene_gpu_checks.h"
#include "test_scenes.h"

namespace giq::realtime {
namespace {

class SequenceTest : public test::VulkanTest {};

// The mesh of the test Cornell box's tall block (its first block quad: see scene_builders).
constexpr size_t kTallBlockFirstMesh = 7;

struct Frame {
  std::vector<float> position, ids, motion;
};

// Records the G-buffer with motion vectors for each (pose, camera) in turn; returns the last.
Frame gbuffer_sequence(Context& ctx, ShaderCompiler& compiler, const std::vector<scenes::Scene>& poses,
                       const std::vector<scenes::Camera>& cameras, uint32_t size, bool ray_traced) {
  SceneGpu gpu(ctx, compiler, poses[0]);
  GBufferPass gbuffer(ctx, compiler, gpu, poses[0].features, size, size,
                      ray_traced ? PassBuilder::RayTraced : PassBuilder::Raster);
  gbuffer.enable_motion_vectors();
  GpuTimer timer(ctx);
  for (size_t f = 0; f < poses.size(); ++f) {
    if (f > 0) gpu.update(poses[f]);
    ctx.submit_and_wait([&](VkCommandBuffer cmd) {
      timer.reset(cmd);
      gbuffer.record(cmd, cameras[f], timer);
    });
  }
  return {gbuffer.position().read_floats(), {}, gbuffer.motion().read_floats()};
}

// The defining property, checked with the C++ camera (scenes::Camera::ray_direction, the
// contract both renderers share) rather than the shader's projection formula: the previous
// camera's ray through (pixel centre + motion) points at where the surface point was.
// Positions are O(1) and float: directions agree to ~1e-6; 1e-4 leaves room for the
// barycentric reconstruction on long thin triangles.
void expect_motion(const Frame& f, const scenes::Camera& previous, uint32_t size,
                   const std::function<glm::vec3(glm::vec3, size_t)>& previous_point, int min_checked = -1) {
  int checked = 0;
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; ++x) {
      const size_t i = size_t(y) * size + x;
      const float* p = &f.position[4 * i];
      const float* m = &f.motion[4 * i];
      if (p[3] == 0.0f || m[3] == 0.0f) continue;
      const glm::vec3 was = previous_point(glm::vec3(p[0], p[1], p[2]), i);
      const float px = x + 0.5f + m[0], py = y + 0.5f + m[1];
      const glm::vec3 want = glm::normalize(was - previous.ray_origin(px, py, size, size));
      const glm::vec3 got = previous.ray_direction(px, py, size, size);
      ASSERT_LT(glm::length(got - want), 1e-4f) << "pixel " << x << "," << y;
      ++checked;
    }
  EXPECT_GT(checked, min_checked >= 0 ? min_checked : int(size * size / 2));
}

TEST_F(SequenceTest, MotionVectorsFollowTheCamera) {
  const scenes::Scene box = test::cornell_box();
  const scenes::Camera a = box.views[0].camera;
  const scenes::Camera b =
      scenes::Camera::look_at({0.15f, -0.1f, 0.85f}, {0.05f, 0.05f, -1.0f}, {0.05f, 1.0f, 0.0f}, a.yfov * 0.9f);
  for (bool ray_traced : {false, true}) {
    const Frame f = gbuffer_sequence(*ctx, *compiler, {box, box}, {a, b}, 64, ray_traced);
    expect_motion(f, a, 64, [](glm::vec3 p, size_t) { return p; });
  }
  // Orthographic cameras: every ray starts on the camera's plane.
  scenes::Camera oa = a, ob = b;
  oa.ymag = 0.9f, ob.ymag = 0.8f;
  for (bool ray_traced : {false, true}) {
    SCOPED_TRACE(ray_traced ? "orthographic, ray traced" : "orthographic, rasterised");
    const Frame f = gbuffer_sequence(*ctx, *compiler, {box, box}, {oa, ob}, 64, ray_traced);
    expect_motion(f, oa, 64, [](glm::vec3 p, size_t) { return p; });
  }
}

TEST_F(SequenceTest, MotionVectorsFollowMovingGeometry) {
  const scenes::Scene box = test::cornell_box();
  scenes::Scene moved = box;
  const glm::vec3 v(0.08f, 0.0f, 0.05f);
  std::vector<char> moved_mesh(box.meshes.size(), 0);
  for (size_t m = kTallBlockFirstMesh; m < kTallBlockFirstMesh + 6; ++m) {
    for (auto& p : moved.meshes[m].positions) p += v;
    moved_mesh[m] = 1;
  }
  moved.derive();
  const scenes::Camera cam = box.views[0].camera;
  const Frame f = gbuffer_sequence(*ctx, *compiler, {box, moved}, {cam, cam}, 64, false);
  // Which mesh a pixel shows: from the triangle id the G-buffer stores.
  SceneGpu gpu(*ctx, *compiler, moved);
  GBufferPass gb(*ctx, *compiler, gpu, moved.features, 64, 64);
  GpuTimer timer(*ctx);
  ctx->submit_and_wait([&](VkCommandBuffer cmd) {
    timer.reset(cmd);
    gb.record(cmd, cam, timer);
  });
  std::vector<float> ids_raw = gb.ids().read_floats();
  const auto& first = gpu.geometry().mesh_first_triangle;
  int on_block = 0;
  expect_motion(f, cam, 64, [&](glm::vec3 p, size_t i) {
    uint32_t tri;
    std::memcpy(&tri, &ids_raw[4 * i], sizeof tri);
    const size_t mesh = size_t(std::upper_bound(first.begin(), first.end(), tri - 1) - first.begin()) - 1;
    if (!moved_mesh[mesh]) return p;
    ++on_block;
    return p - v;
  });
  EXPECT_GT(on_block, 100);  // the block is in view and its motion was checked
}

// Geometry that moved from `before` to `after` (seen by `cam` both times): a surface point of
// `after` was at its barycentric coordinates in its triangle applied to that triangle's
// previous vertices, `was` (indexed like flatten(after)), and the motion vectors, rasterised
// and ray traced, must point there. Returns, per builder, the checked pixels that moved by
// more than 1 cm.
std::vector<int> expect_motion_follows_vertices(Context& ctx, ShaderCompiler& compiler, const scenes::Scene& before,
                                                const scenes::Scene& after, const scenes::Camera& cam, const std::vector<glm::vec3>& was) {
  const FlatGeometry now = flatten(after, true);
  std::vector<int> moved;
  for (bool ray_traced : {false, true}) {
    SCOPED_TRACE(ray_traced ? "ray traced" : "rasterised");
    const Frame f = gbuffer_sequence(ctx, compiler, {before, after}, {cam, cam}, 64, ray_traced);
    SceneGpu gpu(ctx, compiler, after);
    GBufferPass gb(ctx, compiler, gpu, after.features, 64, 64, ray_traced ? PassBuilder::RayTraced : PassBuilder::Raster);
    GpuTimer timer(ctx);
    ctx.submit_and_wait([&](VkCommandBuffer cmd) {
      timer.reset(cmd);
      gb.record(cmd, cam, timer);
    });
    const std::vector<float> ids = gb.ids().read_floats();
    moved.push_back(0);
    expect_motion(
        f, cam, 64,
        [&](glm::vec3 p, size_t i) {
          uint32_t tri;
          std::memcpy(&tri, &ids[4 * i], sizeof tri);
          const glm::uvec3 t = now.triangles[tri - 1];
          // Barycentrics of p in the current triangle, by sub-triangle areas.
          const glm::vec3 a = now.positions[t.x], b = now.positions[t.y], c = now.positions[t.z];
          const glm::vec3 n = glm::cross(b - a, c - a);
          const float area = glm::dot(n, n);
          const float wb = glm::dot(glm::cross(p - a, c - a), n) / area, wc = glm::dot(glm::cross(b - a, p - a), n) / area;
          const glm::vec3 old = (1.0f - wb - wc) * was[t.x] + wb * was[t.y] + wc * was[t.z];
          moved.back() += glm::length(old - p) > 0.01f;
          return old;
        },
        200);
  }
  return moved;
}

// A skinned, morphing mesh (tests/data/scenes/blender_figure.glb, Blender's export) deforms
// between frames 7 and 15 of its walk; its vertices keep their indices (docs/scene-format.md),
// so the previous vertices are frame 7's.
TEST_F(SequenceTest, MotionVectorsFollowSkinnedGeometry) {
  const scenes::Scene figure = scenes::load(std::filesystem::path(GIQ_TEST_DATA) / "scenes" / "blender_figure.glb");
  ASSERT_TRUE(figure.features.skinning);
  const scenes::Scene before = figure.at_frame(7), after = figure.at_frame(15);
  const glm::vec3 eye = glm::vec3(glm::dvec3(1.6, 1.0, 1.6) - figure.origin), target = glm::vec3(glm::dvec3(0.0, 0.9, -0.3) - figure.origin);
  const scenes::Camera cam = scenes::Camera::look_at(eye, target, {0, 1, 0}, 1.1f);
  const FlatGeometry was = flatten(before);
  ASSERT_EQ(was.positions.size(), flatten(after).positions.size());
  for (int moved : expect_motion_follows_vertices(*ctx, *compiler, before, after, cam, was.positions))
    EXPECT_GT(moved, 100);  // the figure's limbs moved by more than 1 cm where they were checked
}

// Particles of the fountain (made 10 cm wide so that they cover pixels) between frames 19 and
// 20: a particle is not at the same vertex index from frame to frame, so its previous vertices
// are where the scene library says it was a frame earlier (Mesh::previous_positions); the
// floor's are where they are.
TEST_F(SequenceTest, MotionVectorsFollowParticles) {
  scenes::Scene fountain = scenes::load(std::filesystem::path(GIQ_TEST_DATA) / "scenes" / "fountain.gltf");
  fountain.emitters[0].size = 0.1;
  const scenes::Scene before = fountain.at_frame(19), after = fountain.at_frame(20);
  const FlatGeometry now = flatten(after, true);
  std::vector<glm::vec3> was(now.positions);
  for (size_t m = 0; m < after.meshes.size(); ++m)
    for (size_t i = 0; i < after.meshes[m].previous_positions.size(); ++i) was[now.mesh_first_vertex[m] + i] = after.meshes[m].previous_positions[i];
  for (int moved : expect_motion_follows_vertices(*ctx, *compiler, before, after, after.view("side").camera, was))
    EXPECT_GT(moved, 20);  // pixels on particles, which move by 3 cm or more a frame
}

TEST_F(SequenceTest, UpdateReportsWhatMoved) {
  scenes::Scene s = test::cornell_box();
  scenes::Light l;
  l.type = scenes::LightType::Point;
  l.position = {0.0f, 0.5f, 0.0f};
  s.lights = {l};
  s.derive();
  SceneGpu gpu(*ctx, *compiler, s);
  EXPECT_EQ(gpu.update(s), SceneChange::None);
  scenes::Scene lit = s;
  lit.lights[0].position.x = 0.25f;
  EXPECT_EQ(gpu.update(lit), SceneChange::Lights);
  EXPECT_EQ(gpu.update(lit), SceneChange::None);
  scenes::Scene moved = lit;
  moved.meshes[kTallBlockFirstMesh].positions[0].y += 0.01f;
  moved.derive();
  EXPECT_EQ(gpu.update(moved), SceneChange::Geometry);
  // The update compares the file's meshes with what it uploaded in place: a normal, a
  // material and an object id are each a change too, and the GPU then holds them.
  const auto& g = gpu.geometry();
  const uint32_t v = g.mesh_first_vertex[kTallBlockFirstMesh], t = g.mesh_first_triangle[kTallBlockFirstMesh];
  scenes::Scene turned = moved;
  const glm::vec3 normal = glm::normalize(glm::vec3(1.0f, 2.0f, 3.0f));
  ASSERT_NE(moved.meshes[kTallBlockFirstMesh].normals[0], normal);
  turned.meshes[kTallBlockFirstMesh].normals[0] = normal;
  EXPECT_EQ(gpu.update(turned), SceneChange::Geometry);
  EXPECT_EQ(test::vertex_rows(gpu.vertices())[v].normal, glm::vec4(normal, 0.0f));
  auto triangle = [&] {
    const std::vector<uint8_t> bytes = gpu.triangles().download();
    gpu::GpuTriangle tri;
    std::memcpy(&tri, bytes.data() + t * sizeof(tri), sizeof(tri));
    return tri;
  };
  scenes::Scene recoloured = turned;
  auto& block = recoloured.meshes[kTallBlockFirstMesh];
  block.material = block.material == 0 ? 1 : 0;
  EXPECT_EQ(gpu.update(recoloured), SceneChange::Geometry);
  EXPECT_EQ(triangle().v.w, uint32_t(block.material));
  scenes::Scene renamed = recoloured;
  renamed.meshes[kTallBlockFirstMesh].object_id += 100;
  EXPECT_EQ(gpu.update(renamed), SceneChange::Geometry);
  EXPECT_EQ(triangle().extra.y, renamed.meshes[kTallBlockFirstMesh].object_id);
  // Moved at the last update and not at this one: the previous vertices are the vertices.
  EXPECT_EQ(gpu.update(lit), SceneChange::Geometry);
  EXPECT_NE(gpu.previous_vertices().download(), gpu.vertices().download());
  EXPECT_EQ(gpu.update(lit), SceneChange::None);
  EXPECT_EQ(gpu.previous_vertices().download(), gpu.vertices().download());
}

// Meshes turned a quarter about the vertical through their first vertex, one set per update,
// with the file's layout kept: only they go up (SceneGpu::upload_meshes), and the GPU then
// holds what uploading the whole pose would have given. Its vertices are the pose's, to the
// bit; their previous vertices are the last pose's (a mesh that moved at the last update but
// not at this one: its vertices); a turned mesh's tangents turned with it; the tree is the
// one the CPU refitted over the moved triangles alone, which is refit_bvh's over all of them
// (bit for bit: min and max round nothing), every box exactly its triangles' on the GPU. The
// Cornell box's two blocks, then the textured room's wall, which has tangents.
TEST_F(SequenceTest, OnlyTheMeshesThatMovedGoUp) {
  auto turn = [](scenes::Mesh& m) {
    const glm::vec3 c = m.positions.at(0);
    auto quarter = [](glm::vec3 v) { return glm::vec3(-v.z, v.y, v.x); };
    for (glm::vec3& p : m.positions) p = c + quarter(p - c);
    for (glm::vec3& n : m.normals) n = quarter(n);
    for (glm::vec4& t : m.tangents) t = glm::vec4(quarter(glm::vec3(t)), t.w);
  };
  auto rows = [](const scenes::Scene& s) {
    std::vector<gpu::GpuVertex> out;
    const FlatGeometry g = flatten(s);
    for (size_t i = 0; i < g.positions.size(); ++i) out.push_back({glm::vec4(g.positions[i], 1.0f), glm::vec4(g.normals[i], 0.0f)});
    return out;
  };
  auto expect_rows = [](const std::vector<gpu::GpuVertex>& got, const std::vector<gpu::GpuVertex>& want, const std::string& what) {
    ASSERT_GE(got.size(), want.size()) << what;
    for (size_t i = 0; i < want.size(); ++i)
      ASSERT_TRUE(got[i].position == want[i].position && got[i].normal == want[i].normal) << what << ", vertex " << i;
  };
  struct Case {
    std::string name;
    scenes::Scene scene;
    std::vector<std::vector<size_t>> steps;  // the meshes turned at each update
  };
  std::vector<Case> cases;
  cases.push_back({"cornell", test::cornell_box(), {{kTallBlockFirstMesh, kTallBlockFirstMesh + 1}, {kTallBlockFirstMesh - 1}, {}}});
  scenes::Scene room = scenes::load(std::filesystem::path(GIQ_TEST_DATA) / "scenes" / "textured_room.gltf");
  size_t wall = 0;
  while (wall < room.meshes.size() && room.meshes[wall].tangents.empty()) ++wall;
  ASSERT_LT(wall, room.meshes.size());
  cases.push_back({"textured_room", room, {{wall}, {}}});

  for (const Case& c : cases) {
    SceneGpu gpu(*ctx, *compiler, c.scene);
    scenes::Scene before = c.scene;
    int step = 0;
    for (const std::vector<size_t>& meshes : c.steps) {
      const std::string what = c.name + " step " + std::to_string(step++);
      scenes::Scene now = before;
      for (size_t m : meshes) turn(now.meshes.at(m));
      now.derive();
      const Bvh built = gpu.bvh();
      EXPECT_EQ(gpu.update(now), meshes.empty() ? SceneChange::None : SceneChange::Geometry) << what;
      expect_rows(test::vertex_rows(gpu.vertices()), rows(now), what + ", vertices");
      // Unmoved meshes' previous vertices are their vertices; a moved one's its last pose's.
      expect_rows(test::vertex_rows(gpu.previous_vertices()), rows(meshes.empty() ? now : before), what + ", previous vertices");
      if (!meshes.empty()) {
        EXPECT_EQ(gpu.last_bvh_update(), SceneGpu::BvhUpdate::Refitted) << what;
        Bvh full = built;
        const FlatGeometry g = flatten(now);
        refit_bvh(full, g.positions, g.triangles);
        ASSERT_EQ(full.nodes.size(), gpu.bvh().nodes.size()) << what;
        EXPECT_EQ(std::memcmp(full.nodes.data(), gpu.bvh().nodes.data(), full.nodes.size() * sizeof(BvhNode)), 0) << what;
      }
      test::expect_tree_exact(gpu, what);
      for (size_t m : meshes) {
        const scenes::Mesh& mesh = now.meshes[m];
        if (mesh.tangents.empty()) continue;
        const std::vector<uint8_t> bytes = gpu.vertex_extra().download();
        const size_t first = gpu.geometry().mesh_first_vertex[m];
        for (size_t i = 0; i < mesh.tangents.size(); ++i) {
          gpu::GpuVertexExtra e;
          std::memcpy(&e, bytes.data() + (first + i) * sizeof(e), sizeof(e));
          ASSERT_EQ(e.tangent, mesh.tangents[i]) << what << ", vertex " << i;
        }
      }
      before = now;
    }
  }
}

// A technique that lives through the sequence gives, at every frame, what a technique created
// for that frame's pose alone gives: `direct` on the moving light of `movinglight` (its cube
// shadow map must follow the light). Same commands on the same data: identical bits.
TEST_F(SequenceTest, APersistentTechniqueFollowsTheMovingLight) {
  RenderOptions o;
  o.technique = "direct";
  o.width = o.height = 48;
  o.frames = 3;
  o.parameters = {"shadow_map_size=256"};
  expect_persistent_matches_fresh(scenes::load(std::filesystem::path(GIQ_SCENES_DIR) / "movinglight.gltf"), o, "R");
}

}  // namespace
}  // namespace giq::realtime
