// giq-bench-pose: what posing a scene at a frame's time costs on the CPU (scenes::Scene::at:
// animation, skins, particles as octahedra, then derive's emissive triangles and area lights),
// which the reference does once a frame; `giq realtime` does it with the particles counted
// only (--counted: scenes::ParticleDetail::Counted). With --rate, every emitter of
// the scene emits that many particles a second for --lifetime seconds, so that the particles'
// share can be taken at any count. Medians over --frames consecutive frames from --start, each
// posed --reps times; Markdown on stdout.

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "giq/base/error.h"
#include "giq/scenes/scene.h"

using namespace giq;

int main(int argc, char** argv) {
  CLI::App app{"CPU time to pose a scene at a frame (Markdown on stdout)", "giq-bench-pose"};
  std::string path = "scenes/dynamic.gltf";
  double rate = 0.0, lifetime = 2.0, start = 2.5;
  int frames = 5, reps = 3;
  bool counted = false;
  app.add_option("--scene", path, "glTF scene")->capture_default_str();
  app.add_option("--rate", rate, "particles a second of every emitter (0: the scene's)")->capture_default_str();
  app.add_option("--lifetime", lifetime, "seconds, with --rate")->capture_default_str();
  app.add_option("--start", start, "time of the first frame (s)")->capture_default_str();
  app.add_option("--frames", frames)->capture_default_str();
  app.add_option("--reps", reps)->capture_default_str();
  app.add_flag("--counted", counted, "count the particles, do not place them");
  CLI11_PARSE(app, argc, argv);
  try {
    scenes::Scene scene = scenes::load(path);
    if (rate > 0.0)
      for (scenes::Emitter& e : scene.emitters) {
        e.rate = rate, e.lifetime = lifetime;
        e.max_particles = uint32_t(std::floor(rate * lifetime) + 1.0);
      }
    std::vector<double> ms;
    size_t triangles = 0, particles = 0;
    for (int f = 0; f < frames; ++f)
      for (int r = 0; r < reps; ++r) {
        const double t = start + f / scene.sequence.fps;
        const auto t0 = std::chrono::steady_clock::now();
        const scenes::Scene posed = scene.at(t, counted ? scenes::ParticleDetail::Counted : scenes::ParticleDetail::Placed);
        ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        triangles = posed.stats.triangles;
        particles = 0;
        for (const scenes::Emitter& e : posed.emitters) particles += scenes::alive_range(e, t).count();
      }
    std::sort(ms.begin(), ms.end());
    std::printf("| scene | particles | alive | triangles | pose ms (median) | min | max |\n|---|---|---:|---:|---:|---:|---:|\n");
    std::printf("| %s | %s | %zu | %zu | %.3f | %.3f | %.3f |\n", path.c_str(), counted ? "counted" : "placed", particles, triangles,
                ms[ms.size() / 2], ms.front(), ms.back());
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
