// giq-bench-particles: the GPU particle system (ParticleSystem: simulate, emit and their
// bookkeeping, one emitter) on this machine's GPU, with about a million particles alive.
//
// The emitter: a 1 m square facing up emits `rate` particles a second (500k), each living
// `lifetime` seconds (2: 1M alive once full), at 4 m/s within 20 degrees of the normal, under
// gravity and drag, in 8 stages of life. Frames at 30 fps; the first `lifetime` seconds fill
// the system and are not timed. GPU times are timestamp pairs around the passes (GpuTimer:
// simulation and emission apart, and the frame), the median over the timed frames of every run. At the last frame a sample of particles is compared
// with the scene library's double-precision particles (scenes::particle_at), as the tests do.
// After the system's passes, as in the scene on the GPU, the particles are written as their
// octahedra, glowing (ParticleSystem::record_vertices: vertices, previous vertices, triangle
// records, indices and emissive triangles) and a tree is built over them (LinearBvh), each
// timed apart from the system's frame.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "giq/realtime/context.h"
#include "giq/realtime/linear_bvh.h"
#include "giq/realtime/particle_system.h"
#include "giq/realtime/shader.h"
#include "giq/realtime/timer.h"
#include "shaders/particles_shared.h"
#include "shaders/scene_shared.h"

using namespace giq;

int main(int argc, char** argv) {
  CLI::App app{"The GPU particle system with a million particles alive (Markdown on stdout)", "giq-bench-particles"};
  double rate = 500000.0, lifetime = 2.0;
  int frames = 120, reps = 3;
  std::string device;
  app.add_option("--rate", rate, "particles emitted per second")->capture_default_str();
  app.add_option("--lifetime", lifetime, "seconds")->capture_default_str();
  app.add_option("--frames", frames, "frames at 30 fps, the first lifetime x 30 not timed")->capture_default_str();
  app.add_option("--reps", reps)->capture_default_str();
  app.add_option("--device", device, "Vulkan device index or name substring");
  CLI11_PARSE(app, argc, argv);

  try {
    realtime::ContextOptions co;
    co.device = device;
    realtime::Context ctx(co);
    realtime::ShaderCompiler compiler;
    scenes::Emitter e;
    e.name = "bench";
    e.rate = rate, e.lifetime = lifetime, e.speed = 4.0, e.spread = 20.0 * 3.14159265358979 / 180.0, e.drag = 0.2, e.stages = 8, e.seed = 11;
    e.max_particles = uint32_t(std::floor(rate * lifetime) + 1.0);
    e.surface = {{-0.5, 0.0, 0.5}, {0.5, 0.0, 0.5}, {0.5, 0.0, -0.5}, {-0.5, 0.0, 0.5}, {0.5, 0.0, -0.5}, {-0.5, 0.0, -0.5}};
    e.choice = {0x7fffffffu, 0xffffffffu};

    std::printf("# GPU particle system: %.0f particles a second, %.3g s each (%u alive at most)\n\n", rate, lifetime, e.max_particles);
    std::printf("GPU: %s; %d frames at 30 fps, the first %d not timed; %d runs\n\n", ctx.properties().deviceName, frames, int(lifetime * 30.0), reps);
    realtime::GpuTimer timer(ctx);
    std::vector<double> ms, simulate_ms, emit_ms, vertices_ms, tree_ms, keys_ms, sort_ms, nodes_ms;

    // The particles' place in a scene: octahedron p at vertices 6p.. and triangles 8p..; their
    // tree beside an empty one, as SceneGpu lays it out for a scene of particles alone.
    const uint32_t capacity = e.max_particles;
    const realtime::Buffer vertices(ctx, uint64_t(capacity) * scenes::kParticleVertices * sizeof(realtime::gpu::GpuVertex),
                                    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    const realtime::Buffer previous(ctx, vertices.size(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    const uint64_t max_triangles = uint64_t(capacity) * scenes::kParticleTriangles;
    const realtime::Buffer triangle_buffer(ctx, max_triangles * sizeof(realtime::gpu::GpuTriangle), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    const realtime::Buffer indices(ctx, 3 * max_triangles * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    const realtime::Buffer emissive(ctx, max_triangles * sizeof(realtime::gpu::GpuEmissive), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    realtime::LinearBvh tree(ctx, compiler, capacity, scenes::kParticleTriangles);
    std::vector<realtime::BvhNode> nodes;
    std::vector<uint32_t> prims;
    tree.place_beside(nodes, prims);
    const realtime::Buffer node_buffer = realtime::Buffer::storage(ctx, nodes), prim_buffer = realtime::Buffer::storage(ctx, prims);
    nodes = {}, prims = {};
    uint32_t alive = 0;
    double worst = 0.0;
    for (int r = 0; r < reps; ++r) {
      realtime::ParticleSystem system(ctx, compiler, e);
      for (int f = 0; f < frames; ++f) {
        const double t = f / 30.0;
        system.prepare(t);
        // Each stage's place: stages in order, each holding its ids in [lowest, the previous
        // stage's lowest), as scenes::Scene::at places them; every triangle glows alike.
        const scenes::AliveRange alive = scenes::alive_range(e, t);
        const std::vector<uint32_t>& counts = system.stage_counts();
        std::vector<realtime::gpu::GpuParticleStage> stages(counts.size());
        uint32_t particle = 0;
        const float each = 1.0f / float(std::max<uint64_t>(1, scenes::kParticleTriangles * alive.count()));
        for (size_t st = 0; st < stages.size(); ++st) {
          const uint32_t triangle = scenes::kParticleTriangles * particle;
          stages[st].first = glm::uvec4(scenes::kParticleVertices * particle, 0u, triangle, triangle + 1);
          stages[st].triangle = glm::uvec4(0u, 1u, GIQ_TRIANGLE_HAS_NORMALS, uint32_t(scenes::kParticleTriangles * alive.count()));
          stages[st].radiance = glm::vec4(1.0f, 1.0f, 1.0f, float(e.face_area()));
          stages[st].sampling = glm::vec4(float(triangle) * each, each, 0.0f, 0.0f);
          particle += counts[st];
        }
        ctx.submit_and_wait([&](VkCommandBuffer cmd) {
          timer.reset(cmd);
          system.record(cmd, &timer);
          timer.begin(cmd, "particle vertices");
          system.record_vertices(cmd, {vertices, previous, triangle_buffer, indices, emissive}, stages, 1.0 / 30.0);
          timer.end(cmd);
          tree.record(cmd, vertices, triangle_buffer, node_buffer, prim_buffer, 0, uint32_t(alive.count()), &timer);
        });
        if (t >= lifetime) {
          const auto passes = timer.resolve();
          simulate_ms.push_back(passes.at(0).second), emit_ms.push_back(passes.at(1).second);
          ms.push_back(simulate_ms.back() + emit_ms.back());
          vertices_ms.push_back(passes.at(2).second);
          keys_ms.push_back(passes.at(3).second), sort_ms.push_back(passes.at(4).second), nodes_ms.push_back(passes.at(5).second);
          tree_ms.push_back(keys_ms.back() + sort_ms.back() + nodes_ms.back());
        }
      }
      // A sample of the last frame's particles against the CPU's: |gpu - cpu| / |cpu's scale|.
      const std::vector<realtime::ParticleSystem::State> states = system.alive();
      alive = uint32_t(states.size());
      const double t = (frames - 1) / 30.0;
      for (size_t k = 0; k < states.size(); k += 997) {
        const scenes::Particle p = scenes::particle_at(e, states[k].id, t);
        const double scale = 1.0 + glm::length(p.velocity) * p.age + 9.81 * p.age * p.age;
        worst = std::max(worst, glm::length(glm::dvec3(states[k].position) - p.position) / scale);
      }
    }
    std::printf("| | value |\n|---|---:|\n");
    std::printf("| particles alive at the last frame | %u |\n", alive);
    std::printf("| GPU ms per frame (median) | %.4f |\n", realtime::percentile(ms, 0.5));
    std::printf("| of which simulation (bookkeeping and simulate pass) | %.4f |\n", realtime::percentile(simulate_ms, 0.5));
    std::printf("| of which emission (%.0f a frame, bookkeeping and emit pass) | %.4f |\n", rate / 30.0, realtime::percentile(emit_ms, 0.5));
    std::printf("| min | %.4f |\n| max | %.4f |\n", *std::min_element(ms.begin(), ms.end()), *std::max_element(ms.begin(), ms.end()));
    std::printf("| worst position error against the CPU, relative to 1 m + |v| a + g a^2 (1 in 997 particles) | %.2e |\n", worst);
    std::printf("| the particles' octahedra written (ms, median) | %.4f |\n", realtime::percentile(vertices_ms, 0.5));
    std::printf("| their tree built (LinearBvh, ms, median) | %.4f |\n", realtime::percentile(tree_ms, 0.5));
    std::printf("| of which leaf boxes and Morton codes | %.4f |\n", realtime::percentile(keys_ms, 0.5));
    std::printf("| of which the bitonic sort | %.4f |\n", realtime::percentile(sort_ms, 0.5));
    std::printf("| of which the nodes (hierarchy, boxes, depth-first layout) | %.4f |\n", realtime::percentile(nodes_ms, 0.5));
    return 0;
  } catch (const std::exception& ex) {
    std::fprintf(stderr, "giq-bench-particles: %s\n", ex.what());
    return 1;
  }
}
