// The GPU BVH (binned SAH build, compute traversal, watertight triangle test) against Embree
// on the same triangles. Embree is used here only, as an independent ray tracer.
#include <embree3/rtcore.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "giq/realtime/bvh.h"
#include "giq/realtime/ray_query.h"
#include "giq/realtime/scene_gpu.h"
#include "test_scenes.h"

namespace giq::realtime {
namespace {

struct EmbreeScene {
  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene scene = rtcNewScene(device);
  explicit EmbreeScene(const FlatGeometry& g) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), g.positions.size()));
    for (size_t i = 0; i < g.positions.size(); ++i)
      v[3 * i] = g.positions[i].x, v[3 * i + 1] = g.positions[i].y, v[3 * i + 2] = g.positions[i].z;
    auto* idx = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                               3 * sizeof(uint32_t), g.triangles.size()));
    for (size_t i = 0; i < g.triangles.size(); ++i)
      idx[3 * i] = g.triangles[i].x, idx[3 * i + 1] = g.triangles[i].y, idx[3 * i + 2] = g.triangles[i].z;
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene);
  }
  ~EmbreeScene() {
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
  }
  // Closest hit: (triangle, t) or (~0, inf).
  std::pair<uint32_t, float> intersect(glm::vec3 o, glm::vec3 d, float tmax) const {
    RTCIntersectContext c;
    rtcInitIntersectContext(&c);
    RTCRayHit rh{};
    rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z;
    rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = tmax;
    rh.ray.mask = ~0u;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &c, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {~0u, INFINITY};
    return {rh.hit.primID, rh.ray.tfar};
  }
};

scenes::Scene test_scene() {
  scenes::Scene s = test::cornell_box();
  const int m = test::add_material(s, glm::vec3(0.5f));
  test::add_sphere(s, {0.4f, 0.3f, -0.4f}, 0.35f, 24, 48, m);
  test::add_sphere(s, {-0.5f, -0.6f, 0.5f}, 0.2f, 12, 16, m);
  s.derive();
  return s;
}

class BvhTest : public test::VulkanTest {};

TEST(Bvh, EveryTriangleIsInExactlyOneLeafAndBoxesContainTheirTriangles) {
  const auto g = flatten(test_scene());
  const Bvh bvh = build_bvh(g.positions, g.triangles);
  ASSERT_FALSE(bvh.nodes.empty());
  EXPECT_LE(bvh.depth, Bvh::kMaxDepth);
  std::vector<int> seen(g.triangles.size(), 0);
  for (const auto& n : bvh.nodes) {
    if (n.count == 0) continue;
    for (uint32_t i = 0; i < n.count; ++i) {
      const uint32_t t = bvh.prims[n.index + i];
      ++seen[t];
      for (int k = 0; k < 3; ++k) {
        const glm::vec3 p = g.positions[g.triangles[t][k]];
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(p, n.lo)) && glm::all(glm::lessThanEqual(p, n.hi)));
      }
    }
  }
  for (size_t t = 0; t < seen.size(); ++t) EXPECT_EQ(seen[t], 1) << "triangle " << t;
}

// Random rays through `scene` on the GPU and in Embree; fails the test on any disagreement
// that is not a tie, and on more than 0.1% edge ties. With `before`, the GPU scene is made for
// it and updated to `scene` (the same triangles moved: the BVH is refitted). Returns how many
// rays both found on a particle.
int compare_with_embree(Context& ctx, ShaderCompiler& compiler, const scenes::Scene& scene, int n_inside, int n_outside,
                         const scenes::Scene* before = nullptr) {

  SceneGpu gpu(ctx, compiler, before ? *before : scene);
  if (before) {
    gpu.update(scene);
    EXPECT_EQ(gpu.last_bvh_update(), SceneGpu::BvhUpdate::Refitted);
    ::testing::Test::RecordProperty("sah_cost_growth", std::to_string(gpu.bvh_cost_growth()));
  }
  // Embree gets the scene library's particles, which the GPU's are to float rounding.
  const FlatGeometry g = flatten(scene, true);
  EmbreeScene embree(g);
  RayQuery query(ctx, compiler, gpu);

  std::mt19937 rng(1234);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  auto unit = [&] {
    glm::vec3 d;
    do d = {u(rng), u(rng), u(rng)};
    while (glm::dot(d, d) > 1.0f || glm::dot(d, d) < 1e-4f);
    return glm::normalize(d);
  };
  // Origins inside the scene's bounds and outside them (aimed at points inside).
  const glm::vec3 c = 0.5f * (scene.bounds.lo + scene.bounds.hi), half = 0.5f * scene.bounds.extent();
  const float radius = glm::length(half);
  auto inside = [&] { return c + 0.98f * half * glm::vec3(u(rng), u(rng), u(rng)); };
  std::vector<QueryRay> rays;
  for (int i = 0; i < n_inside; ++i) rays.push_back({glm::vec4(inside(), 1e30f), glm::vec4(unit(), 0.0f)});
  for (int i = 0; i < n_outside; ++i) {
    const glm::vec3 o = c + 3.0f * radius * unit(), target = inside();
    rays.push_back({glm::vec4(o, 1e30f), glm::vec4(glm::normalize(target - o), 0.0f)});
  }
  // Particles are small: four rays aimed near each one's centre (its first two vertices are
  // on the x axis), from inside the scene.
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    if (scene.meshes[m].emitter < 0) continue;
    const auto& p = scene.meshes[m].positions;
    for (size_t v = 0; v + 1 < p.size(); v += scenes::kParticleVertices)
      for (int k = 0; k < 4; ++k) {
        const glm::vec3 centre = 0.5f * (p[v] + p[v + 1]), o = inside();
        const glm::vec3 target = centre + 0.4f * glm::length(p[v] - centre) * glm::vec3(u(rng), u(rng), u(rng));
        rays.push_back({glm::vec4(o, 1e30f), glm::vec4(glm::normalize(target - o), 0.0f)});
      }
  }
  const auto hits = query.trace(rays);

  // Agreement: same triangle (or both miss) with distances within float rounding. A different
  // triangle is explained by a tie: the watertight test hits both triangles at the same
  // distance (a shared edge or vertex), so either answer is a correct closest hit.
  // Coplanar overlapping triangles (a block's bottom face lying on the floor) are hit at the
  // same distance everywhere: ties by construction, counted apart from edge ties.
  int same = 0, ties = 0, coplanar = 0, unexplained = 0, on_particles = 0;
  uint32_t first_particle_triangle = uint32_t(g.triangles.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m)
    if (scene.meshes[m].emitter >= 0) first_particle_triangle = std::min(first_particle_triangle, g.mesh_first_triangle[m]);
  std::vector<QueryRay> shadow;
  std::vector<bool> shadow_expect;
  for (size_t i = 0; i < rays.size(); ++i) {
    const glm::vec3 o(rays[i].org_tmax), d(rays[i].dir_any);
    const auto [et, ed] = embree.intersect(o, d, 1e30f);
    const auto& h = hits[i];
    const float tol = 1e-5f * std::max(1.0f, ed);
    if (h.triangle == et && (et == ~0u || std::abs(h.t - ed) <= tol)) {
      ++same;
      on_particles += et != ~0u && et >= first_particle_triangle;
    } else if (h.triangle != ~0u && et != ~0u) {
      BvhHit a, b;
      auto tri = [&](uint32_t t, int k) { return g.positions[g.triangles[t][k]]; };
      const bool ha = intersect_triangle(o, d, tri(h.triangle, 0), tri(h.triangle, 1), tri(h.triangle, 2), 1e30f, a);
      const bool hb = intersect_triangle(o, d, tri(et, 0), tri(et, 1), tri(et, 2), 1e30f, b);
      const glm::vec3 na = glm::normalize(glm::cross(tri(h.triangle, 1) - tri(h.triangle, 0), tri(h.triangle, 2) - tri(h.triangle, 0)));
      const glm::vec3 nb = glm::normalize(glm::cross(tri(et, 1) - tri(et, 0), tri(et, 2) - tri(et, 0)));
      const bool same_plane = std::abs(glm::dot(na, nb)) > 0.99999f &&
                              std::abs(glm::dot(na, tri(et, 0) - tri(h.triangle, 0))) < 1e-6f;
      if (ha && std::abs(a.t - ed) <= tol && (!hb || std::abs(b.t - a.t) <= tol))
        ++(same_plane ? coplanar : ties);
      else
        ++unexplained, ADD_FAILURE() << "ray " << i << ": gpu tri " << h.triangle << " t " << h.t << ", embree tri " << et << " t " << ed;
    } else {
      // One hit, one miss: only acceptable for a ray grazing an edge, where the hit
      // triangle's barycentrics are on its boundary.
      const bool grazing = h.triangle != ~0u && std::min({h.u, h.v, 1.0f - h.u - h.v}) < 1e-5f;
      if (grazing) ++ties;
      else ++unexplained, ADD_FAILURE() << "ray " << i << ": gpu tri " << int(h.triangle) << ", embree tri " << int(et);
    }
    // Any-hit: occluded before 99.9% of Embree's distance must be false, after 100.1% true.
    if (et != ~0u && ed > 1e-3f) {
      shadow.push_back({glm::vec4(o, 0.999f * ed), glm::vec4(d, 1.0f)});
      shadow_expect.push_back(false);
      shadow.push_back({glm::vec4(o, 1.001f * ed), glm::vec4(d, 1.0f)});
      shadow_expect.push_back(true);
    }
  }
  EXPECT_EQ(unexplained, 0);
  // Ties need a ray through an edge to float precision: a handful in 16000 at most.
  EXPECT_LE(ties, int(rays.size() / 1000)) << ties << " edge ties";
  EXPECT_EQ(same + ties + coplanar, int(rays.size()));
  ::testing::Test::RecordProperty("edge_ties", ties);
  ::testing::Test::RecordProperty("coplanar_ties", coplanar);

  const auto occl = query.trace(shadow);
  int wrong = 0;
  for (size_t i = 0; i < shadow.size(); ++i) wrong += (occl[i].triangle != ~0u) != shadow_expect[i];
  EXPECT_EQ(wrong, 0) << "of " << shadow.size() << " any-hit queries";
  return on_particles;
}

TEST_F(BvhTest, ClosestAndAnyHitAgreeWithEmbree) { compare_with_embree(*ctx, *compiler, test_scene(), 12000, 4000); }

// A refit keeps every triangle in its leaf and makes every box hold its triangles again; a
// deformation makes the tree costlier than a fresh build over the moved triangles.
TEST(Bvh, RefitBoundsTheMovedTrianglesAndCostsWhatTheMotionCosts) {
  const auto g = flatten(test_scene());
  Bvh bvh = build_bvh(g.positions, g.triangles);
  std::vector<glm::vec3> moved = g.positions;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-0.05f, 0.05f);
  for (glm::vec3& p : moved) p = glm::vec3(p.x * 1.3f, p.y, p.z * 0.8f) + glm::vec3(u(rng), u(rng), u(rng));
  refit_bvh(bvh, moved, g.triangles);
  for (size_t i = 0; i < bvh.nodes.size(); ++i) {
    const BvhNode& n = bvh.nodes[i];
    const auto inside = [&](glm::vec3 lo, glm::vec3 hi) { return glm::all(glm::greaterThanEqual(lo, n.lo)) && glm::all(glm::lessThanEqual(hi, n.hi)); };
    if (n.count == 0) {
      EXPECT_TRUE(inside(bvh.nodes[i + 1].lo, bvh.nodes[i + 1].hi) && inside(bvh.nodes[n.index].lo, bvh.nodes[n.index].hi)) << "node " << i;
      continue;
    }
    for (uint32_t k = 0; k < n.count; ++k)
      for (int c = 0; c < 3; ++c) {
        const glm::vec3 p = moved[g.triangles[bvh.prims[n.index + k]][c]];
        EXPECT_TRUE(inside(p, p)) << "node " << i;
      }
  }
  // The SAH cost is a sum of positive terms over the same tree: not below a fresh build's by
  // more than the binned build's own suboptimality, and positive.
  const double refitted = sah_cost(bvh), fresh = sah_cost(build_bvh(moved, g.triangles));
  EXPECT_GT(fresh, 0.0);
  EXPECT_GE(refitted, 0.9 * fresh);
}

// Skinned geometry (Blender's export, frame 0 then 15 of the walk): the GPU scene refits its
// BVH and the traversal still finds what Embree finds in the moved triangles.
TEST_F(BvhTest, RefittedSkinnedGeometryAgreesWithEmbree) {
  const scenes::Scene figure = scenes::load(std::filesystem::path(GIQ_TEST_DATA) / "scenes" / "blender_figure.glb");
  const scenes::Scene before = figure.at_frame(0), after = figure.at_frame(15);
  compare_with_embree(*ctx, *compiler, after, 6000, 6000, &before);
}

class BuiltinBvhTest : public test::VulkanTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(BuiltinBvhTest, AgreesWithEmbree) {
  const scenes::Scene s = scenes::load(std::filesystem::path(GIQ_SCENES_DIR) / (GetParam() + ".gltf"));
  compare_with_embree(*ctx, *compiler, s, 12000, 4000);
}

// The built-in scene with particles, mid-sequence: the rays reach the tree the GPU built over
// the particles (LinearBvh) beside the CPU's tree of the room and the refitted walker.
TEST_F(BvhTest, ParticlesTreeBuiltOnTheGpuAgreesWithEmbree) {
  const scenes::Scene s = scenes::load(std::filesystem::path(GIQ_SCENES_DIR) / "dynamic.gltf");
  const scenes::Scene posed = s.at_frame(60);
  size_t particles = 0;
  for (const auto& m : posed.meshes) particles += m.emitter >= 0 ? m.positions.size() / scenes::kParticleVertices : 0;
  ASSERT_GT(particles, 50u);
  const int on_particles = compare_with_embree(*ctx, *compiler, posed, 4000, 2000);
  // Most of the rays aimed at particles reach one (the others are blocked by the walker or
  // the fountain's basin on the way).
  EXPECT_GT(on_particles, int(particles));
  RecordProperty("particles", int(particles));
  RecordProperty("rays_on_particles", on_particles);
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, BuiltinBvhTest, ::testing::Values("cornell", "leak", "movinglight", "sunroom", "atrium"));

}  // namespace
}  // namespace giq::realtime
