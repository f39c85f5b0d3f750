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
#include <filesystem>
#include <set>

#include "giq/realtime/context.h"
#include "giq/realtime/particle_system.h"
#include "test_scenes.h"

namespace giq::realtime {
namespace {

constexpr double kU = 0x1p-24;

class ParticleSystemTest : public test::VulkanTest {};

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

}  // namespace
}  // namespace giq::realtime
