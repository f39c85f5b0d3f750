// Times giq's FLIP on an image pair, read and evaluated as `giq score` does (image::read_image,
// hdr_flip / ldr_flip), and reports its pooled values as JSON:
//   flip_bench [--ldr] [--warmup] [--repeat N] [--map OUT.exr] [--against MAP.exr] REF.exr TEST.exr
// --repeat: timed evaluations (wall clock, evaluation only; file reading is timed separately),
// after one untimed one with --warmup; --map writes the error map; --against compares the map
// with another one (e.g. NVIDIA's) and reports the largest per-pixel and the mean difference.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "giq/image/io.h"
#include "giq/metrics/flip.h"

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

}  // namespace

int main(int argc, char** argv) {
  bool hdr = true, warmup = false;
  int repeat = 1;
  std::string map_path, against_path;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--ldr") hdr = false;
    else if (a == "--warmup") warmup = true;
    else if (a == "--repeat" && i + 1 < argc) repeat = std::max(1, std::atoi(argv[++i]));
    else if (a == "--map" && i + 1 < argc) map_path = argv[++i];
    else if (a == "--against" && i + 1 < argc) against_path = argv[++i];
    else files.push_back(a);
  }
  if (files.size() != 2) {
    std::fprintf(stderr,
                 "usage: flip_bench [--ldr] [--warmup] [--repeat N] [--map OUT.exr] [--against MAP.exr] REF.exr TEST.exr\n");
    return 2;
  }
  try {
    const auto t_read = Clock::now();
    const giq::image::Image ref = giq::image::read_image(files[0]);
    const giq::image::Image test = giq::image::read_image(files[1]);
    const double read_s = seconds_since(t_read);
    auto evaluate = [&] { return hdr ? giq::metrics::hdr_flip(ref, test, "") : giq::metrics::ldr_flip(ref, test, ""); };

    giq::metrics::FlipResult result;
    if (warmup) result = evaluate();
    std::vector<double> times;
    for (int i = 0; i < repeat; ++i) {
      const auto t0 = Clock::now();
      result = evaluate();
      times.push_back(seconds_since(t0));
    }
    std::sort(times.begin(), times.end());
    std::printf("{\"mean\": %.9g, \"weighted_median\": %.9g, \"weighted_q1\": %.9g, \"weighted_q3\": %.9g, \"max\": %.9g",
                result.mean, result.weighted_median, result.weighted_q1, result.weighted_q3, result.max);
    if (hdr)
      std::printf(", \"start_exposure\": %.9g, \"stop_exposure\": %.9g, \"exposures\": %d", double(result.start_exposure),
                  double(result.stop_exposure), result.exposures);
    std::printf(", \"read_seconds\": %.4f, \"median_seconds\": %.4f, \"min_seconds\": %.4f", read_s,
                times[times.size() / 2], times.front());
    if (!against_path.empty()) {
      const giq::image::Image other = giq::image::read_image(against_path);
      if (other.width() != result.width || other.height() != result.height)
        throw std::runtime_error("--against map has another size");
      const float* values = other.channel("Y");
      double max_diff = 0.0, sum_other = 0.0;
      for (size_t i = 0; i < result.map.size(); ++i) {
        max_diff = std::max(max_diff, std::fabs(double(result.map[i]) - double(values[i])));
        sum_other += values[i];
      }
      std::printf(", \"max_pixel_difference\": %.3g, \"mean_difference\": %.3g", max_diff,
                  std::fabs(result.mean - sum_other / double(result.map.size())));
    }
    std::printf("}\n");
    if (!map_path.empty()) {
      giq::image::Image map(result.width, result.height);
      std::copy(result.map.begin(), result.map.end(), map.add_channel("Y"));
      giq::image::write_exr(map, map_path);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "flip_bench: %s\n", e.what());
    return 2;
  }
  return 0;
}
