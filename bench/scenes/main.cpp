// giq-bench-scene: what a large textured scene costs, stage by stage, printed as Markdown:
//  1. loading (scenes::load: glTF, 1M+ triangles, every texture decoded): seconds and peak
//     memory of a process that only loads;
//  2. the reference: BVH build seconds, camera paths per second and peak memory;
//  3. real time: `giq realtime` GPU milliseconds a frame and GPU memory per technique;
//  4. start-up: `giq --version` and `giq --help` wall seconds.
// Every stage runs in a fresh child process (this binary with --stage, or giq itself), so peak
// memory is that stage's own (getrusage's ru_maxrss of the child), and is repeated; medians
// are reported. The scene is the atrium that `giq-scenegen --atrium` writes (bench/scenes/run).

#include <CLI/CLI.hpp>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "giq/base/error.h"
#include "giq/reference/renderer.h"
#include "giq/scenes/scene.h"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// A child's exit, wall time, peak resident memory and standard output.
struct Run {
  int status = -1;
  double seconds = 0.0, peak_mib = 0.0;
  std::string out;
};

Run run(const std::vector<std::string>& argv) {
  int pipefd[2];
  if (pipe(pipefd) != 0) throw std::runtime_error("pipe failed");
  const Clock::time_point t0 = Clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(pipefd[1], 1);
    close(pipefd[0]), close(pipefd[1]);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(args[0], args.data());
    _exit(127);
  }
  close(pipefd[1]);
  Run r;
  char buf[4096];
  for (ssize_t n; (n = read(pipefd[0], buf, sizeof buf)) > 0;) r.out.append(buf, size_t(n));
  close(pipefd[0]);
  rusage usage{};
  int status = 0;
  wait4(pid, &status, 0, &usage);
  r.seconds = seconds_since(t0);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.peak_mib = double(usage.ru_maxrss) / 1024.0;  // kilobytes on Linux
  return r;
}

std::string self_path() { return fs::read_symlink("/proc/self/exe").string(); }

// --stage load: prints {"seconds", "triangles", "textures", "texture_mib"}.
int stage_load(const fs::path& scene) {
  const Clock::time_point t0 = Clock::now();
  const giq::scenes::Scene s = giq::scenes::load(scene);
  const double seconds = seconds_since(t0);
  double texels = 0.0;
  for (const auto& t : s.textures)
    if (t.valid()) texels += double(t.width) * t.height * giq::scenes::Texture::words_per_texel(t.format) * 4.0;
  std::printf("%s\n", nlohmann::json{{"seconds", seconds},
                                     {"triangles", s.stats.triangles},
                                     {"textures", s.textures.size()},
                                     {"texture_mib", texels / (1 << 20)}}
                          .dump()
                          .c_str());
  return 0;
}

// --stage reference: prints {"load", "build", "samples_per_s", "rays_per_s"} for `seconds` of
// rendering at width x height of the scene's first view.
int stage_reference(const fs::path& scene, int width, int height, double seconds) {
  Clock::time_point t0 = Clock::now();
  const giq::scenes::Scene s = giq::scenes::load(scene);
  const double load = seconds_since(t0);
  giq::reference::RenderSettings rs;
  rs.width = width, rs.height = height;
  t0 = Clock::now();
  const giq::reference::Renderer r(s, s.views.at(0).camera, rs);
  const double build = seconds_since(t0);
  giq::reference::Film f = r.make_film();
  giq::reference::RenderStats stats;
  t0 = Clock::now();
  uint32_t spp = 0;
  while (seconds_since(t0) < seconds) r.render(f, ++spp, nullptr, &stats);
  const double t = seconds_since(t0);
  std::printf("%s\n", nlohmann::json{{"load", load},
                                     {"build", build},
                                     {"samples_per_s", double(stats.samples) / t},
                                     {"rays_per_s", double(stats.rays) / t}}
                          .dump()
                          .c_str());
  return 0;
}

nlohmann::json last_line(const Run& r) {
  const size_t end = r.out.find_last_not_of('\n');
  const size_t start = r.out.rfind('\n', end);
  return nlohmann::json::parse(r.out.substr(start == std::string::npos ? 0 : start + 1, end + 1));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"giq-bench-scene: load, reference, real-time and start-up cost of a large scene"};
  std::string scene, stage, giq, techniques = "direct,pt", device;
  int repeats = 3, width = 256, height = 144, rt_width = 1920, rt_height = 1080;
  double seconds = 5.0;
  app.add_option("--scene", scene, "The scene (e.g. the atrium giq-scenegen --atrium writes)")->required();
  app.add_option("--giq", giq, "The giq binary, for the real-time and start-up stages (none: skipped)");
  app.add_option("--repeats", repeats, "Runs of each stage (medians reported)");
  app.add_option("--width", width, "Reference image width");
  app.add_option("--height", height, "Reference image height");
  app.add_option("--seconds", seconds, "Seconds of reference rendering per run");
  app.add_option("--realtime-width", rt_width, "Real-time image width");
  app.add_option("--realtime-height", rt_height, "Real-time image height");
  app.add_option("--techniques", techniques, "Real-time techniques, comma-separated (empty: none)");
  app.add_option("--device", device, "Vulkan device for giq realtime");
  app.add_option("--stage", stage, "Internal: run one stage in this process")->group("");
  CLI11_PARSE(app, argc, argv);
  try {
    if (stage == "load") return stage_load(scene);
    if (stage == "reference") return stage_reference(scene, width, height, seconds);

    const std::string self = self_path();
    std::vector<double> load_s, load_mib, build_s, sps, rps, ref_mib;
    nlohmann::json facts;
    for (int i = 0; i < repeats; ++i) {
      const Run l = run({self, "--scene", scene, "--stage", "load"});
      if (l.status != 0) throw std::runtime_error("the load stage failed");
      facts = last_line(l);
      load_s.push_back(facts["seconds"].get<double>()), load_mib.push_back(l.peak_mib);
      const Run r = run({self, "--scene", scene, "--stage", "reference", "--width", std::to_string(width), "--height",
                         std::to_string(height), "--seconds", std::to_string(seconds)});
      if (r.status != 0) throw std::runtime_error("the reference stage failed");
      const nlohmann::json j = last_line(r);
      build_s.push_back(j["build"].get<double>()), sps.push_back(j["samples_per_s"].get<double>());
      rps.push_back(j["rays_per_s"].get<double>()), ref_mib.push_back(r.peak_mib);
    }
    std::printf("Scene: %s: %zu triangles, %zu textures (%.0f MiB of texels). %d runs of each stage, medians.\n\n", scene.c_str(),
                facts["triangles"].get<size_t>(), facts["textures"].get<size_t>(), facts["texture_mib"].get<double>(), repeats);
    std::printf("| stage | seconds | peak memory MiB | rate |\n|---|---|---|---|\n");
    std::printf("| load (scenes::load) | %.2f | %.0f | |\n", median(load_s), median(load_mib));
    std::printf("| reference BVH build | %.2f | %.0f (load, build, render) | |\n", median(build_s), median(ref_mib));
    std::printf("| reference render %dx%d | | | %.3f Msamples/s, %.3f Mrays/s |\n", width, height, median(sps) / 1e6,
                median(rps) / 1e6);
    if (giq.empty()) return 0;

    std::stringstream list(techniques);
    for (std::string t; std::getline(list, t, ',');) {
      if (t.empty()) continue;
      const fs::path out = fs::temp_directory_path() / ("giq-bench-scene-" + t);
      std::vector<std::string> cmd = {giq, "realtime", "--scene", scene, "--technique", t, "--width", std::to_string(rt_width),
                                      "--height", std::to_string(rt_height), "--warmup", "2", "--frames", "8", "--out", out.string()};
      if (!device.empty()) cmd.insert(cmd.end(), {"--device", device});
      const Run r = run(cmd);
      if (r.status != 0) {
        std::printf("| realtime %s | failed (exit %d) | | |\n", t.c_str(), r.status);
        continue;
      }
      std::ifstream in(out / "timings.json");
      const nlohmann::json timings = nlohmann::json::parse(in);
      std::printf("| realtime %s %dx%d on %s | %.2f wall (load, upload, 10 frames) | %.0f host; GPU %.0f scene (%.0f of it textures) + %.0f technique | %.3f ms GPU a frame (median of 8) |\n",
                  t.c_str(), rt_width, rt_height, timings["device"]["name"].get<std::string>().c_str(), r.seconds, r.peak_mib,
                  timings["gpu_memory_mb"]["scene"].get<double>(), timings["gpu_memory_mb"]["textures"].get<double>(),
                  timings["gpu_memory_mb"]["technique"].get<double>(), timings["frame_gpu_ms"]["median"].get<double>());
      fs::remove_all(out);
    }
    for (const char* flag : {"--version", "--help"}) {
      std::vector<double> t;
      for (int i = 0; i < 9; ++i) t.push_back(run({giq, flag}).seconds);
      std::printf("| giq %s | %.3f | | |\n", flag, median(t));
    }
  } catch (const giq::InputError& e) {
    std::fprintf(stderr, "giq-bench-scene: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "giq-bench-scene: %s\n", e.what());
    return 3;
  }
  return 0;
}
