// giq-bench-particles: the GPU particle system (ParticleSystem: simulate, emit and their
// bookkeeping, one emitter) on this machine's GPU, with about a million particles alive.
//
// The emitter: a 1 m square facing up emits `rate` particles a second (500k), each living
// `lifetime` seconds (2: 1M alive once full), at 4 m/s within 20 degrees of the normal, under
// gravity and drag, in 8 stages of life. Frames at 30 fps; the first `lifetime` seconds fill
// the system and are not timed. GPU times are timestamp pairs around the passes (GpuTimer:
// simulation and emission apart, and the frame), the median over the timed frames of every run. At the last frame a sample of particles is compared
// with the scene library's double-precision particles (scenes::particle_at), as the tests do.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "giq/realtime/context.h"
#include "giq/realtime/particle_system.h"
#include "giq/realtime/shader.h"
#include "giq/realtime/timer.h"

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
    std::vector<double> ms, simulate_ms, emit_ms;
    uint32_t alive = 0;
    double worst = 0.0;
    for (int r = 0; r < reps; ++r) {
      realtime::ParticleSystem system(ctx, compiler, e);
      for (int f = 0; f < frames; ++f) {
        const double t = f / 30.0;
        system.prepare(t);
        ctx.submit_and_wait([&](VkCommandBuffer cmd) {
          timer.reset(cmd);
          system.record(cmd, &timer);
        });
        if (t >= lifetime) {
          const auto passes = timer.resolve();
          ms.push_back(timer.frame_ms()), simulate_ms.push_back(passes.at(0).second), emit_ms.push_back(passes.at(1).second);
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
    return 0;
  } catch (const std::exception& ex) {
    std::fprintf(stderr, "giq-bench-particles: %s\n", ex.what());
    return 1;
  }
}
