// giq-bench-ranks: strong and weak scaling of `giq reference` across MPI ranks
// (distributed_render.h), printed as Markdown.
//  - strong: one frame, the same work on 1, 2, 4, ... ranks; speed-up T1 / TR and parallel
//    efficiency T1 / (R TR), medians over the repetitions, the runs of one repetition taken
//    one after another so that all rank counts see the same machine state;
//  - weak: a sequence of `frames-per-rank` x R frames on R ranks; efficiency T1 / TR.
// Every rank renders with one thread (--threads 1), so R ranks use R cores. Each render's files
// are compared with the one-rank render's: they must be byte-identical.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Options {
  std::string giq, launcher = "mpirun --oversubscribe", out = "ranks-bench";
  std::string scene, weak_scene;
  int width = 1920, height = 1080, weak_width = 480, weak_height = 270;
  uint32_t spp = 32, weak_spp = 16;
  int frames_per_rank = 4, repeat = 3;
  std::vector<int> ranks{1, 2, 4, 8, 16}, weak_ranks{1, 3, 7, 15};
};

// Runs `giq reference` on `ranks` ranks; its wall time in seconds.
double render(const Options& o, int ranks, const std::string& args, const fs::path& out) {
  fs::remove_all(out.parent_path());
  fs::create_directories(out.parent_path());
  const std::string cmd = o.launcher + " -n " + std::to_string(ranks) + " " + quote(o.giq) + " reference " + args +
                          " --threads 1 --out " + quote(out.string()) + " >" + quote((out.parent_path() / "log").string()) +
                          " 2>&1";
  const auto t0 = std::chrono::steady_clock::now();
  const int rc = std::system(cmd.c_str());
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (rc != 0) {
    std::fprintf(stderr, "giq-bench-ranks: failed (%d): %s\n%s", rc, cmd.c_str(), slurp(out.parent_path() / "log").c_str());
    std::exit(1);
  }
  return s;
}

// Whether every .exr under a matches its twin under b byte for byte.
bool identical(const fs::path& a, const fs::path& b) {
  int n = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(a)) {
    if (e.path().extension() != ".exr") continue;
    ++n;
    if (slurp(e.path()) != slurp(b / e.path().filename())) return false;
  }
  return n > 0;
}

void table(const char* title, const std::vector<int>& ranks, const std::map<int, std::vector<double>>& times,
           const std::map<int, bool>& same, bool strong) {
  std::printf("\n%s\n\n| ranks | wall s (median) | runs | %s | efficiency | bytes = 1 rank |\n|---:|---:|---|---:|---:|---|\n",
              title, strong ? "speed-up" : "T1 / TR");
  const double t1 = median(times.at(ranks.front()));
  for (int r : ranks) {
    const double t = median(times.at(r));
    std::string runs;
    for (double x : times.at(r)) runs += (runs.empty() ? "" : ", ") + std::to_string(x).substr(0, 6);
    const double eff = strong ? t1 / (double(r) * t) : t1 / t;
    std::printf("| %d | %.2f | %s | %.2f | %.0f %% | %s |\n", r, t, runs.c_str(), strong ? t1 / t : t1 / t, 100.0 * eff,
                same.at(r) ? "yes" : "NO");
  }
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{"Strong and weak scaling of giq reference across MPI ranks", "giq-bench-ranks"};
  app.add_option("--giq", o.giq, "giq binary built with GIQ_WITH_MPI")->required();
  app.add_option("--launcher", o.launcher, "MPI launcher words; ' -n R' is appended")->capture_default_str();
  app.add_option("--out", o.out, "Scratch folder")->capture_default_str();
  app.add_option("--scene", o.scene, "Strong scaling: the scene of the one frame")->required();
  app.add_option("--width", o.width)->capture_default_str();
  app.add_option("--height", o.height)->capture_default_str();
  app.add_option("--spp", o.spp)->capture_default_str();
  app.add_option("--ranks", o.ranks, "Strong scaling: rank counts, the first the baseline")->delimiter(',')->capture_default_str();
  app.add_option("--repeat", o.repeat, "Repetitions (medians)")->capture_default_str();
  app.add_option("--weak-scene", o.weak_scene, "Weak scaling: a scene with a sequence (none: skipped)");
  app.add_option("--weak-width", o.weak_width)->capture_default_str();
  app.add_option("--weak-height", o.weak_height)->capture_default_str();
  app.add_option("--weak-spp", o.weak_spp)->capture_default_str();
  app.add_option("--frames-per-rank", o.frames_per_rank)->capture_default_str();
  app.add_option("--weak-ranks", o.weak_ranks)->delimiter(',')->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  const fs::path out = fs::absolute(o.out);
  std::map<int, std::vector<double>> strong, weak;
  std::map<int, bool> strong_same, weak_same;
  const std::string strong_args = "--scene " + quote(o.scene) + " --width " + std::to_string(o.width) + " --height " +
                                  std::to_string(o.height) + " --spp " + std::to_string(o.spp);
  for (int rep = 0; rep < o.repeat; ++rep) {
    for (int r : o.ranks) {
      const fs::path dir = out / ("strong" + std::to_string(r));
      strong[r].push_back(render(o, r, strong_args, dir / "frame.exr"));
      std::fprintf(stderr, "strong %d ranks: %.2f s\n", r, strong[r].back());
    }
    for (int r : o.ranks) strong_same[r] = identical(out / ("strong" + std::to_string(o.ranks.front())), out / ("strong" + std::to_string(r)));
    if (o.weak_scene.empty()) continue;
    for (int r : o.weak_ranks) {
      const int frames = o.frames_per_rank * r;
      const std::string args = "--scene " + quote(o.weak_scene) + " --frames 0:" + std::to_string(frames - 1) + " --width " +
                               std::to_string(o.weak_width) + " --height " + std::to_string(o.weak_height) + " --spp " +
                               std::to_string(o.weak_spp);
      const fs::path dir = out / ("weak" + std::to_string(r));
      weak[r].push_back(render(o, r, args, dir / "f####.exr"));
      std::fprintf(stderr, "weak %d ranks, %d frames: %.2f s\n", r, frames, weak[r].back());
      // The first frames of every run are the same frames: compare them with the smallest run's.
      weak_same[r] = identical(out / ("weak" + std::to_string(o.weak_ranks.front())), dir);
    }
  }
  std::printf("Strong scaling: %s, one frame %dx%d, %u spp, one thread a rank.\n", o.scene.c_str(), o.width, o.height, o.spp);
  table("Strong", o.ranks, strong, strong_same, true);
  if (!o.weak_scene.empty()) {
    std::printf("\nWeak scaling: %s, %d frames a rank at %dx%d, %u spp, one thread a rank.\n", o.weak_scene.c_str(),
                o.frames_per_rank, o.weak_width, o.weak_height, o.weak_spp);
    table("Weak", o.weak_ranks, weak, weak_same, false);
  }
  return 0;
}
