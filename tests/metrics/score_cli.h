#pragma once
// What the `giq score` end-to-end tests share: running the binary, a scratch folder per test,
// and a small reference-like image (tests/metrics/score_cli_test.cpp,
// tests/metrics/score_outside_test.cpp).
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "giq/image/image.h"
#include "synthetic.h"

namespace giq::test::score_cli {

namespace fs = std::filesystem;

struct CliRun {
  int code = -1;
  std::string out, err;
};

inline CliRun giq_run(const std::string& args, const fs::path& dir) {
  const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  const std::string cmd = std::string(GIQ_BINARY) + " " + args + " >" + out.string() + " 2>" + err.string();
  const int status = std::system(cmd.c_str());
  CliRun r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  auto slurp = [](const fs::path& p) {
    std::ifstream in(p);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

inline fs::path fresh_dir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("giq_score_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

inline constexpr int W = 24, H = 16;

// A reference-like image: beauty and indirect, variance, objectId (object 5 on the right third).
inline image::Image reference() {
  auto im = rgb_image(W, H, [](int x, int y, int k) { return 0.2f + 0.5f * hash01(x, y, k); });
  add_layer(im, "indirect", [](int x, int y, int k) { return 0.1f * hash01(x, y, k, 3); });
  add_layer(im, "variance", [](int, int, int) { return 1e-6f; });
  float* id = im.add_channel("objectId");
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) id[im.index(x, y)] = x >= 16 ? 5.0f : 1.0f;
  return im;
}

}  // namespace giq::test::score_cli
