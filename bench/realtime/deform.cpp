// giq-bench-deform: the deformation pass (skinning and morph targets, Deformer) and the BVH
// refit after it (BvhRefitter) on this machine's GPU, against refitting on the CPU.
//
// The mesh: a tube of `rings` x `segments` vertices (500 x 200: 100k vertices, 199k triangles),
// 2 m long, skinned to a chain of `joints` joints along its axis, each vertex weighted to the
// four joints nearest its height (smooth falloff, weights summing to 1), with `targets` morph
// targets (a bulge) at weight 0.5. Each frame the chain bends like the tail of
// giq-bench-bvh-refit: joint k turns by angle(t) k / joints about x, angle(t) = 80 degrees x
// sin(2 pi t), over one second at 30 fps. GPU times are timestamp pairs around each pass
// (GpuTimer), medians over every frame of `reps` runs; the CPU refit is refit_bvh on one thread.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <vector>

#include "giq/base/error.h"
#include "giq/realtime/bvh.h"
#include "giq/realtime/context.h"
#include "giq/realtime/scene_gpu.h"
#include "giq/realtime/shader.h"
#include "cpu_model.h"
#include "giq/realtime/timer.h"

namespace {

using namespace giq;

// The chain's joint matrices at time t (joint k at height 2k / (joints - 1), each turning the
// part above it): world times inverse bind, relative to the scene origin (0).
std::vector<glm::mat4> chain(int joints, double t) {
  const double angle = 80.0 * std::numbers::pi / 180.0 * std::sin(2.0 * std::numbers::pi * t) / double(joints);
  std::vector<glm::mat4> out;
  glm::dmat4 world(1.0);
  for (int k = 0; k < joints; ++k) {
    const double h = 2.0 * k / double(joints - 1), prev = k == 0 ? 0.0 : 2.0 * (k - 1) / double(joints - 1);
    glm::dmat4 local(1.0);
    local[3] = glm::dvec4(0.0, h - prev, 0.0, 1.0);
    const double c = std::cos(angle), s = std::sin(angle);
    glm::dmat4 turn(1.0);
    turn[1] = glm::dvec4(0.0, c, s, 0.0), turn[2] = glm::dvec4(0.0, -s, c, 0.0);
    world = world * local * turn;
    glm::dmat4 inverse_bind(1.0);
    inverse_bind[3] = glm::dvec4(0.0, -h, 0.0, 1.0);
    out.push_back(glm::mat4(world * inverse_bind));
  }
  return out;
}

scenes::Scene tube(int rings, int segments, int joints, int targets) {
  auto rest = std::make_shared<scenes::DeformationRest>();
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const float a = 2.0f * std::numbers::pi_v<float> * float(s) / float(segments);
      rest->positions.emplace_back(0.1f * std::cos(a), 2.0f * float(r) / float(rings - 1), 0.1f * std::sin(a));
      rest->normals.emplace_back(std::cos(a), 0.0f, std::sin(a));
    }
  for (int r = 0; r + 1 < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const uint32_t a = uint32_t(r * segments + s), b = uint32_t(r * segments + (s + 1) % segments);
      const uint32_t c = b + uint32_t(segments), d = a + uint32_t(segments);
      rest->triangles.emplace_back(a, c, b), rest->triangles.emplace_back(a, d, c);
    }
  // Four joints around each vertex's height, weighted by a smooth falloff.
  rest->joints.resize(1), rest->weights.resize(1);
  for (const glm::vec3& p : rest->positions) {
    const float x = p.y / 2.0f * float(joints - 1);
    const int first = std::clamp(int(std::floor(x)) - 1, 0, std::max(0, joints - 4));
    glm::uvec4 j;
    glm::vec4 w;
    for (int c = 0; c < 4; ++c) {
      j[c] = uint32_t(std::min(first + c, joints - 1));
      const float d = std::abs(x - float(first + c));
      w[c] = std::max(0.0f, 1.0f - d / 2.0f);
    }
    rest->joints[0].push_back(j), rest->weights[0].push_back(w / (w.x + w.y + w.z + w.w));
  }
  for (int k = 0; k < targets; ++k) {
    scenes::MorphTarget t;
    for (size_t i = 0; i < rest->positions.size(); ++i) {
      const glm::vec3 p = rest->positions[i];
      t.positions.push_back(0.02f * std::sin(float(k + 1) * 3.0f * p.y) * glm::vec3(p.x, 0.0f, p.z) / 0.1f);
    }
    rest->targets.push_back(std::move(t));
  }

  scenes::Scene s;
  s.materials.emplace_back();
  scenes::Mesh m;
  m.name = "tube";
  m.positions = rest->positions, m.normals = rest->normals, m.triangles = rest->triangles;
  scenes::Deformation d;
  d.rest = rest;
  d.skinned = true;
  d.joints = chain(joints, 0.0);
  d.weights.assign(size_t(targets), 0.5f);
  m.deformation = d;
  s.meshes.push_back(std::move(m));
  s.derive();
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"The GPU deformation pass and BVH refit on a skinned tube (Markdown on stdout)", "giq-bench-deform"};
  int rings = 500, segments = 200, joints = 32, targets = 2, reps = 5, frames = 31;
  std::string device;
  app.add_option("--rings", rings)->capture_default_str();
  app.add_option("--segments", segments)->capture_default_str();
  app.add_option("--joints", joints)->capture_default_str()->check(CLI::Range(4, 1024));
  app.add_option("--targets", targets)->capture_default_str()->check(CLI::Range(0, 64));
  app.add_option("--reps", reps)->capture_default_str();
  app.add_option("--frames", frames, "frames of the one-second motion (30 fps: 31)")->capture_default_str();
  app.add_option("--device", device, "Vulkan device index or name substring");
  CLI11_PARSE(app, argc, argv);

  try {
    realtime::ContextOptions co;
    co.device = device;
    realtime::Context ctx(co);
    realtime::ShaderCompiler compiler;
    scenes::Scene scene = tube(rings, segments, joints, targets);
    realtime::SceneGpu gpu(ctx, compiler, scene);
    realtime::GpuTimer timer(ctx);

    std::printf("# GPU deformation and BVH refit: a skinned tube of %u vertices, %u triangles\n\n", gpu.deformed_vertex_count(), gpu.triangle_count());
    std::printf("GPU: %s; CPU: %s (refit_bvh, one thread)\n\n", ctx.properties().deviceName, bench::cpu_model().c_str());
    std::printf("%d joints, 4 influences a vertex, %d morph targets; medians over %d frames x %d runs\n\n", joints, targets, frames, reps);

    std::vector<double> deform_ms, refit_ms, cpu_refit_ms;
    realtime::Bvh cpu_bvh = gpu.bvh();
    std::vector<glm::vec3> positions;
    scenes::Scene posed = scene;
    for (int r = 0; r < reps; ++r)
      for (int f = 0; f < frames; ++f) {
        // The pose reaches the GPU as update() brings it (matrices and weights), then the two
        // passes are recorded again between timestamps.
        posed.meshes[0].deformation->joints = chain(joints, double(f) / 30.0);
        gpu.update(posed);
        ctx.submit_and_wait([&](VkCommandBuffer cmd) {
          timer.reset(cmd);
          gpu.record_deformation(cmd, true, true, &timer);
        });
        const auto passes = timer.resolve();
        deform_ms.push_back(passes.at(0).second), refit_ms.push_back(passes.at(1).second);
        // The CPU's refit of the same vertices.
        const std::vector<uint8_t> bytes = gpu.vertices().download();
        positions.resize(bytes.size() / sizeof(glm::vec4) / 2);
        for (size_t i = 0; i < positions.size(); ++i) std::memcpy(&positions[i], bytes.data() + 2 * sizeof(glm::vec4) * i, sizeof(glm::vec3));
        const auto t0 = std::chrono::steady_clock::now();
        realtime::refit_bvh(cpu_bvh, positions, gpu.geometry().triangles);
        cpu_refit_ms.push_back(1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      }
    std::printf("| pass | median ms | min | max |\n|---|---:|---:|---:|\n");
    for (const auto& [name, v] : {std::pair{"deform (GPU)", &deform_ms}, std::pair{"BVH refit (GPU)", &refit_ms}, std::pair{"BVH refit (CPU)", &cpu_refit_ms}})
      std::printf("| %s | %.4f | %.4f | %.4f |\n", name, realtime::percentile(*v, 0.5), *std::min_element(v->begin(), v->end()), *std::max_element(v->begin(), v->end()));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "giq-bench-deform: %s\n", e.what());
    return 1;
  }
}
