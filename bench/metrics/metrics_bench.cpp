// Times SSIM, HDR-FLIP and the full score (`giq score`'s library call: every metric, the maps,
// strip.png and metrics.json) on deterministic synthetic HDR pairs, and prints one JSON object
// per size with the median and the extremes of the runs:
//   metrics_bench [--runs N] [--sizes WxH,WxH...] WORK_DIR
// The pair is tests/metrics/flip_pairs.h's procedural HDR scene (seed 7), the same one
// bench/flip times, so the FLIP figures of the two benchmarks are comparable. SSIM and FLIP are
// timed on images already in memory; the full score reads the pair from WORK_DIR (written once
// per size, untimed) and writes its outputs there, as `giq score` does.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "flip_pairs.h"
#include "giq/image/io.h"
#include "giq/metrics/flip.h"
#include "giq/metrics/layer.h"
#include "giq/metrics/score.h"
#include "giq/metrics/ssim.h"

namespace {

using Clock = std::chrono::steady_clock;

struct Timing {
  double median = 0.0, min = 0.0, max = 0.0;
};

// Runs `work` `runs` times and summarises the wall-clock seconds of each run.
Timing time_runs(int runs, const std::function<void()>& work) {
  std::vector<double> t;
  for (int i = 0; i < runs; ++i) {
    const auto t0 = Clock::now();
    work();
    t.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
  }
  std::sort(t.begin(), t.end());
  // For an even count the median is the mean of the two middle runs.
  const size_t n = t.size();
  const double median = n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
  return {median, t.front(), t.back()};
}

giq::image::Image to_image(const giq::flip_pairs::Rgb& rgb) {
  giq::image::Image img(rgb.width, rgb.height);
  std::copy(rgb.r.begin(), rgb.r.end(), img.add_channel("R"));
  std::copy(rgb.g.begin(), rgb.g.end(), img.add_channel("G"));
  std::copy(rgb.b.begin(), rgb.b.end(), img.add_channel("B"));
  return img;
}

void print_timing(const char* name, const Timing& t, bool last) {
  std::printf("\"%s\": {\"median_seconds\": %.4f, \"min_seconds\": %.4f, \"max_seconds\": %.4f}%s", name, t.median,
              t.min, t.max, last ? "" : ", ");
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 5;
  std::string sizes = "1920x1080,3840x2160";
  std::vector<std::string> rest;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--runs" && i + 1 < argc) runs = std::max(1, std::atoi(argv[++i]));
    else if (a == "--sizes" && i + 1 < argc) sizes = argv[++i];
    else rest.push_back(a);
  }
  if (rest.size() != 1) {
    std::fprintf(stderr, "usage: metrics_bench [--runs N] [--sizes WxH,WxH...] WORK_DIR\n");
    return 2;
  }
  try {
    const std::filesystem::path work = rest[0];
    std::filesystem::create_directories(work);
    size_t start = 0;
    while (start < sizes.size()) {
      const size_t end = std::min(sizes.find(',', start), sizes.size());
      const std::string size = sizes.substr(start, end - start);
      start = end + 1;
      int w = 0, h = 0;
      if (std::sscanf(size.c_str(), "%dx%d", &w, &h) != 2 || w <= 0 || h <= 0)
        throw std::runtime_error("bad size " + size + " (expected WxH)");

      const auto pair = giq::flip_pairs::procedural_hdr_pair(w, h, 7);
      const giq::image::Image ref = to_image(pair.reference), test = to_image(pair.test);
      const auto ref_path = work / (size + ".ref.exr"), test_path = work / (size + ".test.exr");
      giq::image::write_exr(ref, ref_path);
      giq::image::write_exr(test, test_path);

      const giq::metrics::RgbLayer a = giq::metrics::rgb_layer(ref, "", ref_path.string());
      const giq::metrics::RgbLayer b = giq::metrics::rgb_layer(test, "", test_path.string());
      double ssim_value = 0.0, flip_value = 0.0;
      const Timing ssim = time_runs(runs, [&] { ssim_value = giq::metrics::ssim(a, b).mean; });
      const Timing flip = time_runs(runs, [&] { flip_value = giq::metrics::hdr_flip(ref, test, "").mean; });
      giq::metrics::ScoreRequest request;
      request.reference = ref_path.string();
      request.test = test_path.string();
      request.out_dir = work / (size + ".score");
      const Timing score = time_runs(runs, [&] { giq::metrics::score(request); });

      std::printf("{\"size\": \"%s\", \"runs\": %d, \"ssim\": %.6f, \"flip\": %.6f, ", size.c_str(), runs, ssim_value,
                  flip_value);
      print_timing("ssim_time", ssim, false);
      print_timing("hdr_flip_time", flip, false);
      print_timing("score_time", score, true);
      std::printf("}\n");
      std::fflush(stdout);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "metrics_bench: %s\n", e.what());
    return 2;
  }
  return 0;
}
