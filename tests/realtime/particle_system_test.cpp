// The GPU particle system (ParticleSystem) against the scene library's particles
// (scenes/particles.h, in double precision) on the generated fountain over 120 frames at 30 fps
// (four seconds: the fountain fills, then every frame has deaths and births): the same ids
// alive, no slot lost or held twice, each particle's stage exactly, and its position and
// velocity within float rounding.
//
// The bound: each GPU value is a short chain of float operations (the emission point's
// interpolation, the direction's polynomials and square roots, the closed form's products and
// sums, the age as the anchor's less a small multiple of 1 / rate) on terms no larger than
// |p0|, |v0| a, |g| a^2 and |v| for the age's own rounding; 64 roundings of their sum covers
// the chain with Vulkan's precision for exp (3 + 2|x| ulp) and sqrt and normalize (a few ulp)
// to spare, and stays a thousand times below the particles' size.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <set>

#include "giq/realtime/context.h"
#include "giq/realtime/particle_system.h"
#include "giq/realtime/scene_gpu.h"
#include "scene_gpu_checks.h"
#include "shaders/scene_shared.h"
#include "techniques/vct/voxel_scale.h"
#include "test_scenes.h"

namespace giq::realtime {
namespace {

constexpr double kU = 0x1p-24;

class ParticleSystemTest : public test::VulkanTest {};

// How far the GPU's corners of particle `id` at time t (and a frame dt earlier) may be from the
// scene library's: the system's own bound (above) at the older of the two ages, plus the
// rounding of the corner's sum.
double corner_bound(const scenes::Emitter& e, uint32_t id, double t, double dt) {
  const scenes::Particle p = scenes::particle_at(e, id, t), birth = scenes::particle_at(e, id, id / e.rate);
  const double a = std::max(std::abs(p.age), std::abs(p.age - dt));
  const double scale = glm::length(birth.position) + glm::length(birth.velocity) * a + glm::length(e.gravity) * a * a + glm::length(p.velocity);
  return 64.0 * kU * scale + 2.0 * kU * (glm::length(p.position) + e.size);
}

TEST_F(ParticleSystemTest, AgreesWithTheSceneLibraryOver120Frames) {
  const scenes::Scene scene = scenes::load(std::filesystem::path(GIQ_TEST_DATA) / "scenes" / "fountain.gltf");
  const scenes::Emitter& e = scene.emitters.at(0);
  ParticleSystem gpu(*ctx, *compiler, e);
  double worst_position = 0.0, worst_velocity = 0.0;
  size_t compared = 0;
  for (int frame = 0; frame < 120; ++frame) {
    const double t = frame / 30.0;
    gpu.prepare(t);
    ctx->submit_and_wait([&](VkCommandBuffer cmd) { gpu.record(cmd); });

    // Bookkeeping: as many alive as the scene library says, and every slot either alive or
    // dead, once.
    const ParticleSystem::Counts c = gpu.counts();
    const scenes::AliveRange range = scenes::alive_range(e, t);
    ASSERT_EQ(c.alive, range.count()) << "frame " << frame;
    ASSERT_EQ(c.alive + c.dead, gpu.capacity()) << "frame " << frame;
    std::vector<ParticleSystem::State> alive = gpu.alive();
    std::vector<uint32_t> slots = gpu.dead_slots();
    for (const auto& p : alive) slots.push_back(p.slot);
    std::sort(slots.begin(), slots.end());
    for (uint32_t s = 0; s < gpu.capacity(); ++s) ASSERT_EQ(slots[s], s) << "frame " << frame << ": a slot lost or held twice";

    // Each particle against the CPU's.
    std::sort(alive.begin(), alive.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
    for (size_t k = 0; k < alive.size(); ++k) {
      const ParticleSystem::State& g = alive[k];
      ASSERT_EQ(g.id, range.first + k) << "frame " << frame;
      const scenes::Particle p = scenes::particle_at(e, g.id, t);
      EXPECT_EQ(int(g.stage), p.stage) << "frame " << frame << ", id " << g.id;
      const scenes::Particle birth = scenes::particle_at(e, g.id, g.id / e.rate);
      const double a = p.age;
      const double scale = glm::length(birth.position) + glm::length(birth.velocity) * a + glm::length(e.gravity) * a * a + glm::length(p.velocity);
      const double bound_p = 64.0 * kU * scale, bound_v = 64.0 * kU * (glm::length(birth.velocity) + glm::length(e.gravity) * a + glm::length(p.velocity));
      const double dp = glm::length(glm::dvec3(g.position) - p.position), dv = glm::length(glm::dvec3(g.velocity) - p.velocity);
      EXPECT_LE(dp, bound_p) << "frame " << frame << ", id " << g.id;
      EXPECT_LE(dv, bound_v) << "frame " << frame << ", id " << g.id;
      EXPECT_NEAR(double(g.age), a, 8.0 * kU * (a + e.lifetime)) << "frame " << frame << ", id " << g.id;
      worst_position = std::max(worst_position, dp / bound_p), worst_velocity = std::max(worst_velocity, dv / bound_v);
      ++compared;
    }
  }
  EXPECT_GT(compared, 10000u);
  std::printf("particles: %zu compared over 120 frames; worst position error %.3f of its bound, velocity %.3f\n", compared, worst_position,
              worst_velocity);
}

TEST_F(ParticleSystemTest, GoingBackInTimeStartsOver) {
  const scenes::Scene scene = scenes::load(std::filesystem::path(GIQ_TEST_DATA) / "scenes" / "fountain.gltf");
  const scenes::Emitter& e = scene.emitters.at(0);
  ParticleSystem gpu(*ctx, *compiler, e);
  for (double t : {0.5, 1.0, 0.25}) {
    gpu.prepare(t);
    ctx->submit_and_wait([&](VkCommandBuffer cmd) { gpu.record(cmd); });
    EXPECT_EQ(gpu.counts().alive, scenes::alive_range(e, t).count()) << t;
  }
}

// The particles' tree (LinearBvh) over more leaves than one workgroup sorts in shared memory
// (1024), so that the bitonic sort's dispatches over all keys run too: the fountain at forty
// times its rate, two consecutive frames.
TEST_F(ParticleSystemTest, TheParticlesTreeHoldsThousandsOfParticles) {
  scenes::Scene scene = scenes::load(std::filesystem::path(GIQ_TEST_DATA) / "scenes" / "fountain.gltf");
  scenes::Emitter& e = scene.emitters.at(0);
  e.rate *= 40.0;
  e.max_particles = uint32_t(std::floor(e.rate * e.lifetime) + 1.0);
  SceneGpu gpu(*ctx, *compiler, scene.at_frame(90));
  EXPECT_GT(gpu.particle_vertex_count(), 2048u * scenes::kParticleVertices);
  test::expect_tree_exact(gpu, "fountain x40, frame 90");
  gpu.update(scene.at_frame(91));
  test::expect_tree_exact(gpu, "fountain x40, frame 91");
  RecordProperty("particles", int(gpu.particle_vertex_count() / scenes::kParticleVertices));
}

TEST_F(ParticleSystemTest, TheSceneOnTheGpuDrawsTheSystemsParticles) {
  const scenes::Scene scene = scenes::load(std::filesystem::path(GIQ_TEST_DATA) / "scenes" / "fountain.gltf");
  const scenes::Emitter& e = scene.emitters.at(0);
  SceneGpu gpu(*ctx, *compiler, scene.at_frame(0));
  size_t compared = 0, own = 0;
  double worst = 0.0;
  // Filling, full, consecutive frames, a jump, and back in time (the system starts over).
  for (int frame : {0, 20, 45, 46, 90, 119, 30}) {
    const scenes::Scene posed = scene.at_frame(frame);
    if (frame > 0) gpu.update(posed);
    const std::vector<gpu::GpuVertex> now = test::vertex_rows(gpu.vertices()), was = test::vertex_rows(gpu.previous_vertices());
    // The scene library's order: ids ascending within each stage's mesh.
    const double t = posed.time, dt = 1.0 / posed.sequence.fps;
    const scenes::AliveRange range = scenes::alive_range(e, t);
    std::vector<std::vector<uint32_t>> ids(size_t(e.stages));
    for (uint64_t id = range.first; id < range.end; ++id) ids[size_t(scenes::particle_at(e, uint32_t(id), t).stage)].push_back(uint32_t(id));
    uint32_t vertices = 0;
    for (size_t m = 0; m < posed.meshes.size(); ++m) {
      const scenes::Mesh& mesh = posed.meshes[m];
      if (mesh.emitter != 0) continue;
      const std::vector<uint32_t>& stage_ids = ids.at(size_t(mesh.material - e.first_material));
      ASSERT_EQ(mesh.positions.size(), 6 * stage_ids.size()) << "frame " << frame;
      for (size_t i = 0; i < mesh.positions.size(); ++i) {
        const uint32_t id = stage_ids[i / 6];
        const double bound = corner_bound(e, id, t, dt);
        const size_t v = gpu.geometry().mesh_first_vertex[m] + i;
        const double d_now = glm::length(glm::dvec3(glm::vec3(now[v].position)) - glm::dvec3(mesh.positions[i]));
        const double d_was = glm::length(glm::dvec3(glm::vec3(was[v].position)) - glm::dvec3(mesh.previous_positions[i]));
        EXPECT_LE(d_now, bound) << "frame " << frame << ", particle " << id << ", vertex " << i % 6;
        EXPECT_LE(d_was, bound) << "frame " << frame << ", particle " << id << ", vertex " << i % 6 << " a frame earlier";
        EXPECT_EQ(glm::vec3(now[v].normal), mesh.normals[i]) << "frame " << frame << ", particle " << id;
        worst = std::max({worst, d_now / bound, d_was / bound});
        own += glm::vec3(now[v].position) != mesh.positions[i];
        ++compared, ++vertices;
      }
    }
    EXPECT_EQ(vertices, gpu.particle_vertex_count()) << "frame " << frame;
    test::expect_tree_exact(gpu, "fountain frame " + std::to_string(frame));
  }
  EXPECT_GT(compared, 1000u);
  // The vertices are the GPU's own, not the CPU's upload left in place: float evaluation of
  // the closed form leaves many a last bit different from the double one rounded.
  EXPECT_GT(own, compared / 10) << "the particle pass wrote nothing";
  std::printf("particle vertices: %zu compared, %zu not the CPU's bits; worst error %.3f of its bound\n", compared, own, worst);
}

// The particles' triangle records, indices and emissive triangles, which the GPU writes, are
// what the host listed when the scene placed them, and the file's stay what the host listed:
// `dynamic`, whose rectangle light's emissive triangles come first and whose CDF the
// particles' continue, and whose walker moves every frame; the fountain, whose file does not
// move, so that from frame to frame only the particles are written (and the arrays grow,
// keeping the file's part). Areas, probabilities and the CDF differ by the faces' areas:
// closed form on the GPU, from float corners on the host, each corner rounded to half an ulp
// of its distance r from the origin, a face's edge size sqrt(2) long: relative 8 u r / size
// bounds that, and the float sums besides.
void expect_lists_like_host(Context& ctx, ShaderCompiler& compiler, const scenes::Scene& scene, int first, const std::vector<int>& frames) {
  SceneGpu gpu(ctx, compiler, scene.at_frame(first, scenes::ParticleDetail::Counted));
  for (int frame : frames) {
    const scenes::Scene placed = scene.at_frame(frame);
    gpu.update(scene.at_frame(frame, scenes::ParticleDetail::Counted));
    const FlatGeometry g = flatten(placed, true);
    ASSERT_EQ(gpu.triangle_count(), g.triangle_count);
    float reach = 0.0f;
    for (const scenes::Mesh& m : placed.meshes)
      for (const glm::vec3& v : m.positions) reach = m.emitter >= 0 ? std::max(reach, glm::length(v)) : reach;
    const double rel = 8.0 * kU * reach / scene.emitters.at(0).size;
    const std::vector<uint8_t> tb = gpu.triangles().download(), ib = gpu.index_buffer().download(), eb = gpu.emissive().download();
    ASSERT_GE(tb.size(), g.triangle_count * sizeof(gpu::GpuTriangle));
    ASSERT_GE(ib.size(), g.triangle_count * 3 * sizeof(uint32_t));
    // The host's list: every emissive triangle by power, in the scene library's order.
    double total = 0.0;
    for (const scenes::EmissiveTriangle& e : placed.emissive_triangles) total += e.power;
    ASSERT_EQ(gpu.emissive_count(), placed.emissive_triangles.size());
    std::vector<uint32_t> emissive_of(g.triangle_count, 0);
    double acc = 0.0;
    size_t particle_triangles = 0;
    for (size_t k = 0; k < placed.emissive_triangles.size(); ++k) {
      const scenes::EmissiveTriangle& e = placed.emissive_triangles[k];
      const uint32_t tri = g.mesh_first_triangle[e.mesh] + e.triangle;
      emissive_of[tri] = uint32_t(k + 1);
      acc += e.power;
      gpu::GpuEmissive r;
      std::memcpy(&r, eb.data() + k * sizeof(r), sizeof(r));
      ASSERT_EQ(r.triangle.x, tri) << "frame " << frame << ", emissive " << k;
      EXPECT_EQ(glm::vec3(r.radiance), e.radiance) << "emissive " << k;
      EXPECT_NEAR(r.radiance.w, e.area, rel * e.area) << "emissive " << k;
      EXPECT_NEAR(r.sampling.x, k + 1 == placed.emissive_triangles.size() ? 1.0 : acc / total, rel) << "emissive " << k;
      EXPECT_NEAR(r.sampling.y, e.power / total, rel * e.power / total) << "emissive " << k;
      particle_triangles += placed.meshes[e.mesh].emitter >= 0;
    }
    EXPECT_GT(particle_triangles, 1000u) << "frame " << frame;
    for (size_t m = 0; m < placed.meshes.size(); ++m) {
      const scenes::Mesh& mesh = placed.meshes[m];
      for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        const uint32_t tri = g.mesh_first_triangle[m] + uint32_t(t);
        gpu::GpuTriangle r;
        std::memcpy(&r, tb.data() + tri * sizeof(r), sizeof(r));
        const glm::uvec3 v = g.triangles[tri];
        ASSERT_EQ(r.v, glm::uvec4(v, uint32_t(mesh.material))) << "frame " << frame << ", triangle " << tri;
        ASSERT_EQ(glm::uvec2(r.extra), glm::uvec2(emissive_of[tri], mesh.object_id)) << "frame " << frame << ", triangle " << tri;
        if (mesh.emitter >= 0) ASSERT_EQ(r.extra.z, GIQ_TRIANGLE_HAS_NORMALS) << "triangle " << tri;
        uint32_t idx[3];
        std::memcpy(idx, ib.data() + 3 * sizeof(uint32_t) * tri, sizeof(idx));
        ASSERT_EQ(glm::uvec3(idx[0], idx[1], idx[2]), v) << "frame " << frame << ", triangle " << tri;
      }
    }
  }
}

TEST_F(ParticleSystemTest, TheGpuListsTheParticlesTrianglesAsTheHostDid) {
  expect_lists_like_host(*ctx, *compiler, scenes::load(std::filesystem::path(GIQ_SCENES_DIR) / "dynamic.gltf"), 29, {30, 31});
  expect_lists_like_host(*ctx, *compiler, scenes::load(std::filesystem::path(GIQ_TEST_DATA) / "scenes" / "fountain.gltf"), 5, {20, 21, 45});
}

// A scene that only counted its particles, completed from where the GPU drew them, has the
// area lights and bounds of the same scene placed by the scene library: each stage's centroid
// and extent, and the box. The GPU's corners are within corner_bound of the library's (B,
// the stage's largest); a centroid of n particles then within B plus its sums' rounding, a few
// dozen roundings of its coordinates on the GPU (a loop of 16, a tree of 256) and one an
// addend on the host's float sum over 8n triangles; an extent within that plus B. `dynamic`,
// and the fountain emitting 100 times as fast, whose stages hold more particles than the
// GPU reduces in one chunk (4096).
// `most`: the most particles a stage held.
void expect_completed_like_placed(Context& ctx, ShaderCompiler& compiler, const scenes::Scene& scene, const std::vector<int>& frames,
                                  uint32_t& most) {
  const scenes::Emitter& e = scene.emitters.at(0);
  scenes::Scene counted = scene.at_frame(frames[0], scenes::ParticleDetail::Counted);
  SceneGpu gpu(ctx, compiler, counted);
  most = 0;
  for (int frame : frames) {
    if (frame != frames[0]) {
      counted = scene.at_frame(frame, scenes::ParticleDetail::Counted);
      gpu.update(counted);
    }
    gpu.complete(counted);
    const scenes::Scene placed = scene.at_frame(frame);
    const double t = placed.time, dt = 1.0 / placed.sequence.fps;
    const scenes::AliveRange alive = scenes::alive_range(e, t);
    double bound = 0.0;
    for (uint64_t id = alive.first; id < alive.end; ++id) bound = std::max(bound, corner_bound(e, uint32_t(id), t, dt));
    ASSERT_EQ(counted.area_lights.size(), placed.area_lights.size());
    size_t stages = 0;
    for (size_t i = 0; i < placed.area_lights.size(); ++i) {
      const scenes::AreaLight &p = placed.area_lights[i], &c = counted.area_lights[i];
      const scenes::Mesh& mesh = placed.meshes[p.mesh];
      if (mesh.emitter < 0 || mesh.particles == 0) {
        EXPECT_EQ(c.centroid, p.centroid) << "light " << i;
        continue;
      }
      float reach = 0.0f;
      for (const glm::vec3& v : mesh.positions) reach = std::max(reach, glm::length(v));
      const double tol = bound + (64.0 + 8.0 * mesh.particles) * kU * reach;
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(c.centroid[k], p.centroid[k], tol) << "frame " << frame << ", light " << i;
        EXPECT_NEAR(c.representative[k], p.representative[k], tol) << "frame " << frame << ", light " << i;
      }
      EXPECT_NEAR(c.extent, p.extent, tol + bound + 4.0 * kU * p.extent) << "frame " << frame << ", light " << i;
      EXPECT_GT(c.extent, 0.0f);
      most = std::max(most, mesh.particles);
      ++stages;
    }
    EXPECT_GE(stages, 2u) << "frame " << frame;
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(counted.bounds.lo[k], placed.bounds.lo[k], bound) << "frame " << frame;
      EXPECT_NEAR(counted.bounds.hi[k], placed.bounds.hi[k], bound) << "frame " << frame;
    }
    EXPECT_EQ(gpu.bounds().lo, counted.bounds.lo);
    EXPECT_EQ(gpu.bounds().hi, counted.bounds.hi);
  }
}

TEST_F(ParticleSystemTest, ACountedSceneIsCompletedFromTheGpusParticles) {
  uint32_t most = 0;
  expect_completed_like_placed(*ctx, *compiler, scenes::load(std::filesystem::path(GIQ_SCENES_DIR) / "dynamic.gltf"), {40, 41, 75}, most);
  scenes::Scene fountain = scenes::load(std::filesystem::path(GIQ_TEST_DATA) / "scenes" / "fountain.gltf");
  scenes::Emitter& e = fountain.emitters.at(0);
  e.rate *= 100.0;
  e.max_particles = uint32_t(std::floor(e.rate * e.lifetime) + 1.0);
  expect_completed_like_placed(*ctx, *compiler, fountain, {90, 91}, most);
  EXPECT_GT(most, 4096u);
}

// How near the particles come to each punctual light, from where the GPU drew them
// (SceneGpu::particle_light_distances), is the least over the particles of the bound the
// shader takes for each octahedron (particle_bounds.comp): the larger of |q - c| - s and
// (|q - c|_1 - s) / sqrt(3), worked here in double from the scene library's particles. Each
// term moves by at most its centre's and size's error (sqrt(3) B each for corners within B per
// coordinate), so 4 B plus a few roundings of |q - c|. A point light two sizes beside a
// particle's centre on the x axis is one size from that particle's nearest corner (exactly,
// by both terms), and no farther from the nearest; one at s (1, 1, 1) from another's centre is
// exactly 2 s / sqrt(3) from its face, which only the second term sees (the first says
// (sqrt(3) - 1) s); a directional light has no distance. The fountain at 100 times its rate, so that the minimum runs over
// chunks. The voxel radiance scale then bounds the irradiance by that distance (voxel_scale.h).
TEST_F(ParticleSystemTest, TheGpuMeasuresHowNearTheParticlesComeToEachLight) {
  scenes::Scene fountain = scenes::load(std::filesystem::path(GIQ_TEST_DATA) / "scenes" / "fountain.gltf");
  scenes::Emitter& e = fountain.emitters.at(0);
  e.rate *= 100.0;
  e.max_particles = uint32_t(std::floor(e.rate * e.lifetime) + 1.0);
  const int frame = 90;
  const scenes::Scene before = fountain.at_frame(frame);
  const double t = before.time, dt = 1.0 / before.sequence.fps;
  const scenes::AliveRange alive = scenes::alive_range(e, t);
  ASSERT_GT(alive.count(), 3 * 4096u);
  const scenes::Particle near = scenes::particle_at(e, uint32_t(alive.first + alive.count() / 2), t);
  scenes::Light point;
  point.position = glm::vec3(near.position + glm::dvec3(2.0 * e.size, 0.0, 0.0));
  point.intensity = 5.0f;
  // Off the axes the faces are nearer than the circumsphere says: s (1, 1, 1) from a centre is
  // 2 s / sqrt(3) from the face x + y + z = s, against sqrt(3) s - s from the sphere.
  const scenes::Particle other = scenes::particle_at(e, uint32_t(alive.first + alive.count() / 3), t);
  scenes::Light diagonal = point;
  diagonal.position = glm::vec3(other.position + glm::dvec3(e.size));
  scenes::Light sun;
  sun.type = scenes::LightType::Directional;
  scenes::Light spot;
  spot.type = scenes::LightType::Spot;
  spot.position = glm::vec3(before.bounds.hi) + glm::vec3(1.0f);
  fountain.add_light(point, "a point light beside a particle");
  fountain.add_light(diagonal, "a point light off a particle's face");
  fountain.add_light(sun, "a sun");
  fountain.add_light(spot, "a spot light beyond the bounds");
  const size_t first = fountain.lights.size() - 4;

  scenes::Scene counted = fountain.at_frame(frame, scenes::ParticleDetail::Counted);
  SceneGpu gpu(*ctx, *compiler, counted);
  gpu.complete(counted);
  const std::vector<float>& got = gpu.particle_light_distances();
  ASSERT_EQ(got.size(), fountain.lights.size());

  for (size_t i = first; i < fountain.lights.size(); ++i) {
    const scenes::Light& l = fountain.lights[i];
    if (l.type == scenes::LightType::Directional) {
      EXPECT_TRUE(std::isinf(got[i])) << "light " << i;
      continue;
    }
    const glm::dvec3 q(l.position);
    double want = std::numeric_limits<double>::infinity(), tol = 0.0;
    for (uint64_t id = alive.first; id < alive.end; ++id) {
      const glm::dvec3 c = scenes::particle_at(e, uint32_t(id), t).position, d = glm::abs(q - c);
      const double bound = std::max({glm::length(d) - e.size, (d.x + d.y + d.z - e.size) / std::sqrt(3.0), 0.0});
      if (bound < want) {
        want = bound;
        tol = 4.0 * corner_bound(e, uint32_t(id), t, dt) + 16.0 * kU * (glm::length(q) + glm::length(c) + e.size);
      }
    }
    EXPECT_NEAR(got[i], want, tol) << "light " << i;
    // (The lights' positions are floats: within a rounding of |q| per coordinate.)
    const double placed = 2.0 * kU * glm::length(q);
    if (i == first) {
      EXPECT_LE(want, e.size + placed) << "the point light two sizes from a particle's centre";
    }
    if (i == first + 1) {
      EXPECT_LE(want, 2.0 / std::sqrt(3.0) * e.size + placed) << "the point light off a face";
    }
  }

  // The scale of vct's voxels, 2^floor(log2(pi / E)) for E the bound on irradiance, takes the
  // point lights' from their distances d to the particles (the basin is farther): E is the
  // sum of their I / d^2, the sun's irradiance, and the spot's, at most its intensity over
  // 3 m^2 (it is over 1 m beyond the bounds on each axis), which the scale's rounding down
  // hardly ever sees. With voxels 4 d wide (d the nearer's) both lights are nearer than half a
  // voxel: each takes I / (2 d)^2 instead.
  auto scale_of = [](double irradiance) { return float(std::exp2(std::floor(std::log2(M_PI / irradiance)))); };
  const double d = std::min(got[first], got[first + 1]);
  for (double voxel : {1e-3 * d, 4.0 * d}) {
    double e_points = sun.intensity;
    for (size_t i : {first, first + 1}) {
      const double near = std::max(double(got[i]), 0.5 * voxel);
      e_points += point.intensity / (near * near);
    }
    const float scale = voxel_radiance_scale(counted, {}, 1, float(voxel), got);
    EXPECT_LE(scale, scale_of(e_points)) << "voxel " << voxel;
    EXPECT_GE(scale, scale_of(e_points + spot.intensity / 3.0)) << "voxel " << voxel;
  }
  EXPECT_GE(voxel_radiance_scale(counted, {}, 1, float(1e-3 * d)), 4.0f * voxel_radiance_scale(counted, {}, 1, float(1e-3 * d), got))
      << "the particles are the nearest surfaces";
}

}  // namespace
}  // namespace giq::realtime
