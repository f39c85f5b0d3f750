// Particle emitters (scenes/particles.h) on the generated fountain (tests/data/scenes/
// generate.py, fountain()): which particles are alive against exact rational arithmetic, the
// closed-form motion against a numerical integration of its differential equation, emission
// against the surface and the cone, and the particles as geometry in posed scenes.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>

#include "giq/scenes/scene.h"
#include "test_paths.h"

namespace giq::scenes {
namespace {

Scene fountain() { return load(std::filesystem::path(GIQ_TEST_DATA) / "scenes" / "fountain.gltf"); }

TEST(Particles, EmitterIsReadAsDeclared) {
  const Scene s = fountain();
  ASSERT_EQ(s.emitters.size(), 1u);
  const Emitter& e = s.emitters[0];
  EXPECT_EQ(e.name, "fountain");
  EXPECT_EQ(e.rate, 200.0);
  EXPECT_EQ(e.lifetime, 1.2);
  EXPECT_NEAR(e.spread, 15.0 * std::numbers::pi / 180.0, 1e-15);
  EXPECT_EQ(e.gravity, glm::dvec3(0.0, -9.81, 0.0));
  EXPECT_EQ(e.stages, 4);
  EXPECT_EQ(e.max_particles, 241u);  // floor(200 x 1.2) + 1
  EXPECT_EQ(e.object_id, 3u);        // two nodes, then the emitter
  EXPECT_EQ(e.surface.size(), 6u);   // the nozzle's two triangles
  ASSERT_EQ(e.choice.size(), 2u);
  EXPECT_EQ(e.choice[1], 0xffffffffu);
  EXPECT_NEAR(double(e.choice[0]), 0x1p31, 1.0);  // two triangles of equal area
  EXPECT_TRUE(s.features.particles);
  EXPECT_TRUE(s.features.animation);
  // Strength at the stages' middles (1/8, 3/8, 5/8, 7/8 of life) on the keys (0, 0), (0.1, 1), (1, 0).
  for (int k = 0; k < 4; ++k) {
    const double life = (k + 0.5) / 4.0, want = life <= 0.1 ? life / 0.1 : 1.0 - (life - 0.1) / 0.9;
    EXPECT_NEAR(e.stage_strength(k), want, 1e-15) << k;
    EXPECT_EQ(s.materials[size_t(e.first_material + k)].emissive, glm::vec3(glm::dvec3(8.0, 5.0, 2.0) * want)) << k;
  }
}

TEST(Particles, AliveIdsAreThoseBornWithinALifetime) {
  // Frame k at 30 fps: id alive when id / 200 <= k / 30 < id / 200 + 1.2, i.e. in integers
  // 3 id <= 20 k and 3 id > 20 k - 720. Births and deaths exactly at a frame's instant (3 id =
  // 20 k, or 20 k - 720) may fall either way with the rounding of rate x t.
  const Scene s = fountain();
  const Emitter& e = s.emitters[0];
  for (int k = 0; k <= 400; k += 7) {
    const AliveRange r = alive_range(e, k / 30.0);
    for (int64_t id = 0; id < 3000; ++id) {
      const int64_t a = 3 * id, born = 20 * k, dies = 20 * k - 720;
      if (a == born || a == dies) continue;
      const bool alive = a <= born && a > dies;
      EXPECT_EQ(uint64_t(id) >= r.first && uint64_t(id) < r.end, alive) << "frame " << k << ", id " << id;
    }
    EXPECT_LE(r.count(), e.max_particles);
  }
}

TEST(Particles, MotionSolvesItsDifferentialEquation) {
  // dp/dt = v, dv/dt = g - k v from the state at birth, by classical Runge-Kutta with 1e-4 s
  // steps (error O(h^4) of the velocity's scale: below 1e-12 m here), against the closed form.
  const Scene s = fountain();
  const Emitter& e = s.emitters[0];
  for (uint32_t id : {0u, 17u, 199u}) {
    const Particle birth = particle_at(e, id, id / e.rate);
    EXPECT_NEAR(birth.age, 0.0, 1e-15);
    glm::dvec3 p = birth.position, v = birth.velocity;
    const double h = 1e-4;
    const auto accel = [&](const glm::dvec3& u) { return e.gravity - e.drag * u; };
    for (int step = 0; step < 10000; ++step) {  // one second
      const glm::dvec3 k1v = accel(v), k1p = v;
      const glm::dvec3 k2v = accel(v + 0.5 * h * k1v), k2p = v + 0.5 * h * k1v;
      const glm::dvec3 k3v = accel(v + 0.5 * h * k2v), k3p = v + 0.5 * h * k2v;
      const glm::dvec3 k4v = accel(v + h * k3v), k4p = v + h * k3v;
      v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
      p += h / 6.0 * (k1p + 2.0 * k2p + 2.0 * k3p + k4p);
    }
    const Particle later = particle_at(e, id, id / e.rate + 1.0);
    EXPECT_NEAR(later.age, 1.0, 1e-12);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(later.position[c], p[c], 1e-9) << "id " << id;
      EXPECT_NEAR(later.velocity[c], v[c], 1e-9) << "id " << id;
    }
  }
}

TEST(Particles, WithoutDragTheyFallFreely) {
  Emitter e = fountain().emitters[0];
  e.drag = 0.0;
  const Particle birth = particle_at(e, 5, 5 / e.rate), later = particle_at(e, 5, 5 / e.rate + 0.75);
  const glm::dvec3 want = birth.position + 0.75 * birth.velocity + 0.5 * 0.75 * 0.75 * e.gravity;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(later.position[c], want[c], 1e-12);
}

TEST(Particles, EmissionCoversTheSurfaceAndTheCone) {
  // 20000 births: every one on the nozzle (y = 0.1, |x|, |z| <= 0.1) at 3 m/s within 15 degrees
  // of +y; the means of x, z (uniform on the square: 0, variance 0.2^2 / 12) and of cos(theta)
  // (uniform over the cone's solid angle: (1 + cos 15deg) / 2, variance (1 - cos 15deg)^2 / 12)
  // within 4 standard errors.
  const Scene s = fountain();
  const Emitter& e = s.emitters[0];
  const int n = 20000;
  double sx = 0.0, sz = 0.0, sc = 0.0;
  for (uint32_t id = 0; id < uint32_t(n); ++id) {
    const Particle p = particle_at(e, id, id / e.rate);
    // The nozzle's corners are floats, in the file and in the local frame (coordinates below
    // 2: within 2 x 2^-24 each).
    ASSERT_NEAR(p.position.y + s.origin.y, 0.1, 2.5e-7) << id;
    ASSERT_LE(std::abs(p.position.x + s.origin.x), 0.1 + 2.5e-7) << id;
    ASSERT_LE(std::abs(p.position.z + s.origin.z), 0.1 + 2.5e-7) << id;
    ASSERT_NEAR(glm::length(p.velocity), 3.0, 1e-12) << id;
    const double c = p.velocity.y / 3.0;
    ASSERT_GE(c, std::cos(e.spread) - 1e-12) << id;
    sx += p.position.x + s.origin.x, sz += p.position.z + s.origin.z, sc += c;
  }
  const double se_xz = 0.2 / std::sqrt(12.0 * n), cs = std::cos(e.spread);
  EXPECT_NEAR(sx / n, 0.0, 4.0 * se_xz);
  EXPECT_NEAR(sz / n, 0.0, 4.0 * se_xz);
  EXPECT_NEAR(sc / n, 0.5 * (1.0 + cs), 4.0 * (1.0 - cs) / std::sqrt(12.0 * n));
}

TEST(Particles, PosedScenesHoldTheAliveParticlesAsOctahedra) {
  const Scene s = fountain();
  const Emitter& e = s.emitters[0];
  for (int frame : {0, 1, 15, 30}) {
    const Scene posed = s.at_frame(frame);
    const double t = frame / 30.0;
    const AliveRange r = alive_range(e, t);
    const std::vector<uint64_t> starts = stage_starts(e, t);
    size_t particles = 0;
    for (const Mesh& m : posed.meshes) {
      if (m.emitter < 0) continue;
      EXPECT_EQ(m.emitter, 0);
      EXPECT_EQ(m.object_id, e.object_id);
      EXPECT_EQ(m.positions.size() % 6, 0u);
      EXPECT_EQ(m.triangles.size(), m.positions.size() / 6 * 8);
      particles += m.positions.size() / 6;
      // Each octahedron's centre is its particle's position; its stage the mesh's material.
      const int stage = m.material - e.first_material;
      ASSERT_GE(stage, 0);
      ASSERT_LT(stage, e.stages);
      const std::vector<glm::vec3> centres = particle_centres(m);
      ASSERT_EQ(centres.size(), m.positions.size() / 6);
      // Its particles are the stage's ids, which the integers give.
      EXPECT_EQ(centres.size(), stage_range(r, starts, stage).count()) << "stage " << stage;
      for (size_t k = 0; k < centres.size(); ++k) {
        for (size_t v = 6 * k; v < 6 * k + 6; ++v)
          EXPECT_NEAR(glm::length(glm::dvec3(m.positions[v]) - glm::dvec3(centres[k])), e.size, 1e-6);
        // Float positions a few metres from the origin: within 1e-6 m of a particle of this stage.
        double nearest = 1e30;
        for (uint64_t id = r.first; id < r.end; ++id) {
          const Particle p = particle_at(e, uint32_t(id), t);
          if (p.stage == stage) nearest = std::min(nearest, glm::length(p.position - glm::dvec3(centres[k])));
        }
        EXPECT_LT(nearest, 1e-6) << "particle " << k << " of stage " << stage;
      }
    }
    EXPECT_EQ(particles, r.count()) << "frame " << frame;
    // Stages by integers agree with the age, away from the boundaries.
    for (uint64_t id = r.first; id < r.end; ++id) {
      const Particle p = particle_at(e, uint32_t(id), t);
      const double x = p.age / e.lifetime * e.stages;
      if (std::abs(x - std::round(x)) > 1e-9) EXPECT_EQ(p.stage, int(std::floor(x))) << "id " << id;
    }
    EXPECT_EQ(starts.size(), size_t(e.stages - 1));
  }
  // Any frame alone, from any other: the same particles.
  const Scene a = s.at_frame(20), b = s.at_frame(7).at_frame(20);
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (size_t m = 0; m < a.meshes.size(); ++m) EXPECT_EQ(a.meshes[m].positions, b.meshes[m].positions);
  // Every stage glows (its middle is past the strength's rise at 0.1 of life): emissive triangles.
  EXPECT_GT(a.emissive_triangles.size(), 0u);
}

// Counted particles (ParticleDetail::Counted): the same meshes, counts, features, stats and
// lights' power as the placed ones, with no vertex; the area lights' area and intensity are
// the placed octahedra's to float rounding (each face's area there comes from float corners a
// few metres from the origin: relative 1e-6 would hold; 1e-5 leaves room for the sums).
TEST(Particles, CountedPosesHoldTheSameParticlesWithoutVertices) {
  const Scene s = fountain();
  for (int frame : {0, 15, 30}) {
    const Scene placed = s.at_frame(frame), counted = s.at_frame(frame, ParticleDetail::Counted);
    ASSERT_EQ(placed.meshes.size(), counted.meshes.size());
    for (size_t m = 0; m < placed.meshes.size(); ++m) {
      const Mesh &p = placed.meshes[m], &c = counted.meshes[m];
      EXPECT_EQ(p.emitter, c.emitter);
      EXPECT_EQ(p.material, c.material);
      EXPECT_EQ(p.particles, c.particles);
      if (p.emitter < 0) {
        EXPECT_EQ(p.positions, c.positions);
        continue;
      }
      EXPECT_EQ(p.positions.size(), size_t(6) * p.particles) << "mesh " << m;
      EXPECT_TRUE(c.positions.empty() && c.triangles.empty() && c.previous_positions.empty()) << "mesh " << m;
    }
    EXPECT_EQ(placed.features, counted.features) << "frame " << frame;
    EXPECT_EQ(placed.stats.triangles, counted.stats.triangles);
    EXPECT_EQ(placed.stats.vertices, counted.stats.vertices);
    EXPECT_NEAR(counted.stats.total_light_power, placed.stats.total_light_power, 1e-5 * placed.stats.total_light_power);
    // The file's emissive triangles only; the particles' none.
    for (const EmissiveTriangle& e : counted.emissive_triangles) EXPECT_LT(counted.meshes[e.mesh].emitter, 0);
    ASSERT_EQ(placed.area_lights.size(), counted.area_lights.size());
    for (size_t i = 0; i < placed.area_lights.size(); ++i) {
      const AreaLight &p = placed.area_lights[i], &c = counted.area_lights[i];
      EXPECT_EQ(p.mesh, c.mesh);
      EXPECT_EQ(p.two_sided, c.two_sided);
      EXPECT_NEAR(c.area, p.area, 1e-5 * p.area) << "light " << i;
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(c.intensity[k], p.intensity[k], 1e-5 * p.intensity[k]) << "light " << i;
      if (counted.meshes[c.mesh].emitter < 0) {
        EXPECT_EQ(p.centroid, c.centroid);
      }
    }
  }
}

// Posing into a scene posed before (Scene::at's third form, whose arrays are reused) gives
// the scene a fresh pose gives, whatever the earlier pose was: `dynamic` (a skinned figure,
// animated nodes, the fountain's particles), placed and counted in turn, at frames out of
// order.
TEST(Particles, PosingIntoAPosedSceneGivesTheFreshPose) {
  const Scene s = load(std::filesystem::path(GIQ_SCENES_DIR) / "dynamic.gltf");
  ASSERT_TRUE(s.features.skinning && s.features.particles && s.features.animation);
  Scene into = s.at_frame(90);
  const std::pair<int, ParticleDetail> poses[] = {{3, ParticleDetail::Counted}, {119, ParticleDetail::Counted},
                                                  {40, ParticleDetail::Placed}, {41, ParticleDetail::Counted},
                                                  {0, ParticleDetail::Placed}};
  for (const auto& [frame, detail] : poses) {
    SCOPED_TRACE("frame " + std::to_string(frame) + (detail == ParticleDetail::Placed ? " placed" : " counted"));
    const double t = frame / s.sequence.fps;
    const Scene fresh = s.at(t, detail);
    s.at(t, detail, into);
    EXPECT_EQ(into.time, fresh.time);
    ASSERT_EQ(into.meshes.size(), fresh.meshes.size());
    for (size_t m = 0; m < fresh.meshes.size(); ++m) {
      const Mesh &a = into.meshes[m], &b = fresh.meshes[m];
      EXPECT_TRUE(a.name == b.name && a.node == b.node && a.material == b.material && a.emitter == b.emitter &&
                  a.particles == b.particles && a.object_id == b.object_id)
          << "mesh " << m;
      EXPECT_TRUE(a.positions == b.positions && a.normals == b.normals && a.tangents == b.tangents && a.uvs == b.uvs &&
                  a.colors == b.colors && a.triangles == b.triangles && a.previous_positions == b.previous_positions)
          << "mesh " << m;
      ASSERT_EQ(a.deformation.has_value(), b.deformation.has_value()) << "mesh " << m;
      if (a.deformation) EXPECT_TRUE(a.deformation->joints == b.deformation->joints && a.deformation->weights == b.deformation->weights);
    }
    ASSERT_EQ(into.lights.size(), fresh.lights.size());
    for (size_t i = 0; i < fresh.lights.size(); ++i)
      EXPECT_TRUE(into.lights[i].position == fresh.lights[i].position && into.lights[i].direction == fresh.lights[i].direction);
    ASSERT_EQ(into.views.size(), fresh.views.size());
    for (size_t i = 0; i < fresh.views.size(); ++i) EXPECT_EQ(into.views[i].camera.position, fresh.views[i].camera.position);
    ASSERT_EQ(into.area_lights.size(), fresh.area_lights.size());
    for (size_t i = 0; i < fresh.area_lights.size(); ++i)
      EXPECT_TRUE(into.area_lights[i].centroid == fresh.area_lights[i].centroid && into.area_lights[i].area == fresh.area_lights[i].area &&
                  into.area_lights[i].intensity == fresh.area_lights[i].intensity);
    EXPECT_EQ(into.emissive_triangles.size(), fresh.emissive_triangles.size());
    EXPECT_TRUE(into.bounds.lo == fresh.bounds.lo && into.bounds.hi == fresh.bounds.hi);
    EXPECT_EQ(into.features, fresh.features);
    EXPECT_EQ(into.stats.triangles, fresh.stats.triangles);
  }
}

// Posing keeps the meshes whose nodes are where they were when the scene being posed was
// (pose's `was`): the room of `dynamic` stays while its walker walks. Kept or emitted anew, a
// mesh is the same: `dynamic` posed at a frame from scenes posed at other frames (other
// meshes kept) equals it posed from the loaded scene, to the bit, degenerate triangles
// counted alike; one whose node moved is where the node puts it. A kept mesh is the same
// object: its arrays do not move.
TEST(Particles, PosingKeepsTheMeshesWhoseNodesStayed) {
  const Scene s = load(std::filesystem::path(GIQ_SCENES_DIR) / "dynamic.gltf");
  for (int frame : {5, 64, 119}) {
    const double t = frame / s.sequence.fps;
    const Scene direct = s.at(t, ParticleDetail::Counted);
    for (int from : {0, 30, 118}) {
      SCOPED_TRACE("frame " + std::to_string(frame) + " from frame " + std::to_string(from));
      const Scene mid = s.at_frame(from, ParticleDetail::Counted);
      const Scene posed = mid.at(t, ParticleDetail::Counted);
      ASSERT_EQ(posed.meshes.size(), direct.meshes.size());
      for (size_t m = 0; m < direct.meshes.size(); ++m) {
        const Mesh &a = posed.meshes[m], &b = direct.meshes[m];
        EXPECT_TRUE(a.name == b.name && a.node == b.node && a.material == b.material && a.object_id == b.object_id &&
                    a.positions == b.positions && a.normals == b.normals && a.tangents == b.tangents && a.uvs == b.uvs &&
                    a.triangles == b.triangles && a.deformation.has_value() == b.deformation.has_value())
            << "mesh " << m;
      }
      EXPECT_EQ(posed.stats.degenerate_triangles_dropped, direct.stats.degenerate_triangles_dropped);
    }
    // A mesh whose node moved is where the node now puts it: the lamp steps from (3.6, 2.4, 3)
    // to (5.4, 2.4, 2.4) at 0.98 s (within float rounding of the local frame's coordinates).
    size_t lamp = 0;
    while (lamp < s.meshes.size() && s.meshes[lamp].name != "lamp") ++lamp;
    ASSERT_LT(lamp, s.meshes.size());
    const glm::vec3 step = t > 0.99 ? glm::vec3(1.8f, 0.0f, -0.6f) : glm::vec3(0.0f);
    for (size_t i = 0; i < s.meshes[lamp].positions.size(); ++i)
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(direct.meshes[lamp].positions[i][k] - s.meshes[lamp].positions[i][k], step[k], 1e-5f) << "frame " << frame;
  }
  // The room's floor (a node no animation moves) kept, posing into a scene posed before.
  Scene into = s.at_frame(10, ParticleDetail::Counted);
  size_t floor = 0;
  while (floor < into.meshes.size() && into.meshes[floor].name != "room_floor") ++floor;
  ASSERT_LT(floor, into.meshes.size());
  const glm::vec3* where = into.meshes[floor].positions.data();
  s.at(20 / s.sequence.fps, ParticleDetail::Counted, into);
  EXPECT_EQ(into.meshes[floor].positions.data(), where);
}

}  // namespace
}  // namespace giq::scenes
