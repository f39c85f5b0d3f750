// giq-bench-bvh-refit: what refitting the real-time BVH costs against building it again, for
// a deforming mesh (SceneGpu::update refits while the moved tree's SAH cost stays within
// SceneGpu::kMaxRefitCost of a fresh build's; docs/realtime.md).
//
// The mesh: a tube of `rings` x `segments` quads (2 triangles each; 250 x 200 = 100k triangles),
// 2 m long, bending like a limb from the middle: vertex at height h turns by
// angle(t) * smoothstep(0.4, 0.6, h) about the x axis through the middle, with angle(t) =
// 80 degrees x sin(2 pi t), over one second at 30 fps. Times are medians of `reps` runs on
// this machine's CPU, one thread (build_bvh and refit_bvh are single-threaded).

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "cpu_model.h"
#include "giq/realtime/bvh.h"
#include "giq/realtime/timer.h"

namespace {

using Clock = std::chrono::steady_clock;

struct Tube {
  std::vector<glm::vec3> rest;
  std::vector<glm::uvec3> triangles;
};

Tube make_tube(int rings, int segments) {
  Tube t;
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const float a = 2.0f * std::numbers::pi_v<float> * float(s) / float(segments);
      t.rest.emplace_back(0.1f * std::cos(a), 2.0f * float(r) / float(rings), 0.1f * std::sin(a));
    }
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const uint32_t a = uint32_t(r * segments + s), b = uint32_t(r * segments + (s + 1) % segments);
      const uint32_t c = b + uint32_t(segments), d = a + uint32_t(segments);
      t.triangles.emplace_back(a, b, c), t.triangles.emplace_back(a, c, d);
    }
  return t;
}

std::vector<glm::vec3> pose(const Tube& tube, double t) {
  const float angle = float(80.0 * std::numbers::pi / 180.0 * std::sin(2.0 * std::numbers::pi * t));
  std::vector<glm::vec3> out(tube.rest.size());
  for (size_t i = 0; i < out.size(); ++i) {
    const glm::vec3 p = tube.rest[i];
    const float h = std::clamp((p.y / 2.0f - 0.4f) / 0.2f, 0.0f, 1.0f);
    const float w = h * h * (3.0f - 2.0f * h), c = std::cos(w * angle), s = std::sin(w * angle);
    const glm::vec3 q = p - glm::vec3(0.0f, 1.0f, 0.0f);
    out[i] = glm::vec3(q.x, c * q.y - s * q.z, s * q.y + c * q.z) + glm::vec3(0.0f, 1.0f, 0.0f);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Refitting the real-time BVH of a deforming mesh against building it again (Markdown on stdout)", "giq-bench-bvh-refit"};
  int rings = 250, segments = 200, reps = 5, frames = 31;
  app.add_option("--rings", rings)->capture_default_str();
  app.add_option("--segments", segments)->capture_default_str();
  app.add_option("--reps", reps)->capture_default_str();
  app.add_option("--frames", frames, "frames of the one-second motion (30 fps: 31)")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  const Tube tube = make_tube(rings, segments);
  std::printf("# BVH refit against build: a bending tube of %zu triangles\n\nMachine: %s, one thread\n\n", tube.triangles.size(),
              giq::bench::cpu_model().c_str());
  const auto seconds = [](Clock::time_point a) { return std::chrono::duration<double>(Clock::now() - a).count(); };

  // Times at the middle of the motion.
  const std::vector<glm::vec3> mid = pose(tube, 0.25);
  std::vector<double> build_ms, refit_ms;
  giq::realtime::Bvh base = giq::realtime::build_bvh(pose(tube, 0.0), tube.triangles);
  for (int r = 0; r < reps; ++r) {
    Clock::time_point t0 = Clock::now();
    const giq::realtime::Bvh b = giq::realtime::build_bvh(mid, tube.triangles);
    build_ms.push_back(1e3 * seconds(t0));
    giq::realtime::Bvh refitted = base;
    t0 = Clock::now();
    giq::realtime::refit_bvh(refitted, mid, tube.triangles);
    refit_ms.push_back(1e3 * seconds(t0));
  }
  std::printf("| | median ms | runs |\n|---|---:|---|\n");
  for (const auto* v : {&build_ms, &refit_ms}) {
    std::printf("| %s | %.2f |", v == &build_ms ? "build_bvh" : "refit_bvh", giq::realtime::percentile(*v, 0.5));
    for (double x : *v) std::printf(" %.2f", x);
    std::printf(" |\n");
  }
  std::printf("\nBuild / refit: %.1fx\n\n", giq::realtime::percentile(build_ms, 0.5) / giq::realtime::percentile(refit_ms, 0.5));

  // Quality over the motion: the SAH cost of the frame-0 tree refitted to each frame (never
  // rebuilt), against a fresh build for that frame, and what SceneGpu's policy does.
  std::printf("| frame | refitted from frame 0 / fresh build (SAH cost) | policy (rebuild above %.1fx of the last build) |\n|---:|---:|---|\n",
              1.3);
  giq::realtime::Bvh kept = base;
  double kept_cost = giq::realtime::sah_cost(kept);
  int rebuilds = 0;
  for (int f = 0; f < frames; ++f) {
    const std::vector<glm::vec3> p = pose(tube, double(f) / 30.0);
    giq::realtime::Bvh from_first = base;
    giq::realtime::refit_bvh(from_first, p, tube.triangles);
    const double fresh = giq::realtime::sah_cost(giq::realtime::build_bvh(p, tube.triangles));
    giq::realtime::refit_bvh(kept, p, tube.triangles);
    const char* what = "refit";
    if (giq::realtime::sah_cost(kept) > 1.3 * kept_cost) {
      kept = giq::realtime::build_bvh(p, tube.triangles);
      kept_cost = giq::realtime::sah_cost(kept);
      what = "rebuild";
      ++rebuilds;
    }
    std::printf("| %d | %.3f | %s, %.3f of a fresh build |\n", f, giq::realtime::sah_cost(from_first) / fresh, what,
                giq::realtime::sah_cost(kept) / fresh);
  }
  std::printf("\n%d rebuilds in %d frames\n", rebuilds, frames);
  return 0;
}
