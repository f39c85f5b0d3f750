// giq-bench-realtime: GPU milliseconds per pass of every technique (`pt`: 1 path per pixel per
// frame) on the Cornell box at 720p, 1080p and 4K, and at 1080p as the triangle count grows
// (the box plus a tessellated sphere of about 10k, 100k and 1M triangles). Scenes are built
// in code, so the benchmark runs without the glTF loader; --scene adds glTF scenes.
//
// Prints a Markdown table and writes every run's timings.json content to --out.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "giq/base/error.h"
#include "giq/realtime/context.h"
#include "giq/realtime/renderer.h"
#include "giq/realtime/shader.h"
#include "giq/realtime/technique.h"
#include "scene_builders.h"

namespace {

using namespace giq;

struct Case {
  std::string scene_name;
  const scenes::Scene* scene;
  std::string technique;
  uint32_t width, height;
  std::vector<std::string> params;
};

std::string pass_summary(const nlohmann::json& t) {
  std::string s;
  for (const auto& p : t["passes"]) {
    char b[96];
    std::snprintf(b, sizeof b, "%s%s %.3f", s.empty() ? "" : ", ", p["name"].get<std::string>().c_str(),
                  p["gpu_ms"]["median"].get<double>());
    s += b;
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"giq-bench-realtime: per-pass GPU ms of every technique", "giq-bench-realtime"};
  std::string device, out = "bench-realtime.json";
  std::vector<std::string> gltf;
  int frames = 50, warmup = 10;
  bool quick = false;
  app.add_option("--device", device, "Vulkan device index or name");
  app.add_option("--frames", frames, "Measured frames per case")->capture_default_str();
  app.add_option("--warmup", warmup, "Warm-up frames per case")->capture_default_str();
  app.add_option("--scene", gltf, "Also run these glTF scenes (view 0) at 1080p");
  app.add_option("--out", out, "JSON output")->capture_default_str();
  app.add_flag("--quick", quick, "Small sizes only (a smoke test on a CPU device)");
  std::vector<std::string> only;
  app.add_option("--technique", only, "Only these techniques (default: every registered one)");
  CLI11_PARSE(app, argc, argv);

  try {
    realtime::ContextOptions co;
    co.device = device;
    realtime::Context ctx(co);
    realtime::ShaderCompiler compiler;

    std::vector<std::pair<std::string, scenes::Scene>> scenes_owned;
    scenes_owned.emplace_back("cornell", test::cornell_box());
    const int sphere_sizes[][2] = {{50, 100}, {160, 320}, {500, 1000}};  // ~10k, ~100k, ~1M triangles
    for (const auto& rs : sphere_sizes) {
      if (quick && rs[0] > 50) break;
      scenes::Scene s = test::cornell_box();
      const int m = test::add_material(s, glm::vec3(0.6f));
      test::add_sphere(s, {0.35f, -0.5f, 0.45f}, 0.3f, rs[0], rs[1], m);
      s.derive();
      scenes_owned.emplace_back("cornell+sphere", std::move(s));
    }
    for (const auto& path : gltf) scenes_owned.emplace_back(path, scenes::load(path));

    std::vector<Case> cases;
    const uint32_t sizes[][2] = {{1280, 720}, {1920, 1080}, {3840, 2160}};
    // Every registered technique with its defaults; `direct` with each G-buffer builder named
    // (the default picks one by device), the rasterised and the ray-traced one (same image).
    std::vector<std::pair<std::string, std::vector<std::string>>> variants = {
        {"direct", {"gbuffer_ray_traced=0"}}, {"direct", {"gbuffer_ray_traced=1"}}};
    for (const auto& info : realtime::techniques())
      if (info.name != "direct") variants.push_back({info.name, {}});
    // vct also with its second bounce (twice the voxel passes).
    variants.push_back({"vct", {"bounces=2"}});
    // A CPU device voxelises 256^3 in seconds: the smoke test uses a small grid.
    if (quick)
      for (auto& [t, params] : variants)
        if (t == "vct") params.push_back("voxel_resolution=64");
    if (!only.empty())
      std::erase_if(variants, [&](const auto& v) { return std::find(only.begin(), only.end(), v.first) == only.end(); });
    for (const auto& [t, params] : variants) {
      for (const auto& sz : sizes) {
        if (quick && sz[0] > 1280) break;
        cases.push_back({"cornell", &scenes_owned[0].second, t, quick ? sz[0] / 8 : sz[0], quick ? sz[1] / 8 : sz[1], params});
      }
      for (size_t i = 1; i < scenes_owned.size(); ++i)
        cases.push_back({scenes_owned[i].first, &scenes_owned[i].second, t, quick ? 240u : 1920u, quick ? 135u : 1080u, params});
    }

    nlohmann::json all = nlohmann::json::array();
    std::printf("device: %s (%s)\n\n", ctx.info().name.c_str(), ctx.info().driver.c_str());
    std::printf("| technique | parameters | scene | triangles | resolution | frame GPU ms (median) | p95 | GPU memory MB | passes (median GPU ms) |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|\n");
    for (const auto& c : cases) {
      realtime::RenderOptions o;
      o.technique = c.technique;
      o.parameters = c.params;
      o.width = c.width;
      o.height = c.height;
      o.frames = frames;
      o.warmup = warmup;
      o.read_back = false;
      nlohmann::json t = realtime::render_sequence(ctx, compiler, *c.scene, o, [](realtime::RenderedFrame&) {});
      t["scene"] = c.scene_name;
      t["triangles"] = c.scene->stats.triangles;
      t.erase("per_frame");
      std::string params;
      for (const auto& p : c.params) params += (params.empty() ? "" : " ") + p;
      std::printf("| %s | %s | %s | %zu | %ux%u | %.3f | %.3f | %.1f | %s |\n", c.technique.c_str(),
                  params.empty() ? "defaults" : params.c_str(), c.scene_name.c_str(),
                  c.scene->stats.triangles, c.width, c.height, t["frame_gpu_ms"]["median"].get<double>(),
                  t["frame_gpu_ms"]["p95"].get<double>(), t["gpu_memory_mb"]["technique"].get<double>(),
                  pass_summary(t).c_str());
      std::fflush(stdout);
      all.push_back(t);
    }
    std::ofstream(out) << all.dump(2) << '\n';
  } catch (const InputError& e) {
    std::fprintf(stderr, "giq-bench-realtime: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "giq-bench-realtime: internal error: %s\n", e.what());
    return 3;
  }
  return 0;
}
