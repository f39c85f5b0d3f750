// Benchmarks of the reference path tracer, printed as Markdown tables:
//  1. throughput on each built-in scene: camera paths (samples) per second and rays per
//     second as rendered (specialised on the scene's features, eight paths at a time where the
//     scene allows), one path at a time, and with the generic variant (every feature compiled
//     in, one path at a time), measured alternately several times; the lanes' speed-up and
//     the specialisation's saving as medians of the repetitions' ratios;
//  2. time to error: seconds until the relative mse against a long render falls below a
//     target (relMSE = mean over pixels and channels of (x - ref)^2 / (ref^2 + 0.01), with
//     the long render's own variance subtracted);
//  3. scaling with triangle count: a Cornell-like box holding a sphere of 10k to 1M triangles.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "giq/base/error.h"
#include "giq/image/io.h"
#include "giq/reference/reference_exr.h"
#include "embree_scene.h"
#include "giq/reference/renderer.h"
#include "giq/scenes/scene.h"
#include "long_render.h"

namespace {

namespace ref = giq::reference;
namespace sc = giq::scenes;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

struct Throughput {
  double samples_per_s = 0.0, rays_per_s = 0.0;
};

// Renders passes until `seconds` have passed; rate over the whole run.
Throughput measure(const sc::Scene& s, const sc::Camera& cam, ref::RenderSettings rs,
                   double seconds) {
  ref::Renderer r(s, cam, rs);
  ref::Film f = r.make_film();
  ref::RenderStats stats;
  const Clock::time_point t0 = Clock::now();
  uint32_t spp = 0;
  while (seconds_since(t0) < seconds) r.render(f, ++spp, nullptr, &stats);
  const double t = seconds_since(t0);
  return {double(stats.samples) / t, double(stats.rays) / t};
}

// The raw Embree rate: the rays of a render on one thread, traced again alone with Embree's
// one-ray queries (rtcIntersect1, rtcOccluded1), against the render's own rays per second.
struct RawRate {
  double render = 0.0, raw = 0.0;  // rays per second
  uint64_t rays = 0;
};
RawRate raw_rate(const sc::Scene& s, const sc::Camera& cam, ref::RenderSettings rs, uint32_t spp) {
  rs.threads = 1;
  RawRate out;
  {
    const ref::Renderer r(s, cam, rs);
    ref::Film f = r.make_film();
    ref::RenderStats stats;
    const Clock::time_point t0 = Clock::now();
    r.render(f, spp, nullptr, &stats);
    out.render = double(stats.rays) / seconds_since(t0);
  }
  std::vector<ref::TracedRay> log;
  ref::EmbreeScene::record(&log);
  {
    const ref::Renderer r(s, cam, rs);
    ref::Film f = r.make_film();
    r.render(f, spp);
  }
  ref::EmbreeScene::record(nullptr);
  const ref::EmbreeScene bvh(s, s.bounds.centre(), s.features.alpha_mask);
  uint64_t hits = 0;  // used, so that no query is optimised away
  const Clock::time_point t0 = Clock::now();
  for (const ref::TracedRay& ray : log) {
    switch (ray.kind) {
      case ref::TracedRay::Camera: hits += bvh.intersect_camera(ray.origin, ray.dir).valid(); break;
      case ref::TracedRay::Bounce: hits += bvh.intersect(ray.origin, ray.dir, ray.tfar).valid(); break;
      case ref::TracedRay::Shadow: hits += bvh.occluded(ray.origin, ray.dir, ray.tfar); break;
    }
  }
  out.raw = double(log.size()) / seconds_since(t0);
  out.rays = log.size() + (hits == ~uint64_t(0));
  return out;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Seconds for an independent render to reach `target` relMSE against `reference`,
// interpolated in log-log between the spp counts bracketing it; -1 if not reached by max_spp.
double time_to_error(const sc::Scene& s, const sc::Camera& cam, ref::RenderSettings rs,
                     const giq::bench::LongRender& reference, double target, uint32_t max_spp,
                     uint32_t& spp_reached) {
  rs.seed = 12345;
  ref::Renderer r(s, cam, rs);
  ref::Film f = r.make_film();
  const Clock::time_point t0 = Clock::now();
  double prev_t = 0.0, prev_e = 0.0;
  for (uint32_t spp = 1; spp <= max_spp; spp *= 2) {
    r.render(f, spp);
    const double t = seconds_since(t0), e = reference.rel_mse(f);
    if (e <= target) {
      spp_reached = spp;
      if (prev_t <= 0.0 || prev_e <= e) return t;
      const double a = std::log(prev_e / target) / std::log(prev_e / e);
      return std::exp(std::log(prev_t) + a * (std::log(t) - std::log(prev_t)));
    }
    prev_t = t, prev_e = e;
  }
  spp_reached = 0;
  return -1.0;
}

// A Cornell-like box (Lambert walls, one ceiling light) with a sphere of about n triangles.
sc::Scene tessellated(size_t n) {
  sc::Scene s;
  const auto diffuse = [](glm::vec3 c, glm::vec3 e = glm::vec3(0.0f)) {
    sc::Material m;
    m.base_color = glm::vec4(c, 1.0f);
    m.metallic = 0.0f;
    m.specular = 0.0f;
    m.emissive = e;
    return m;
  };
  s.materials = {diffuse(glm::vec3(0.73f)), diffuse({0.63f, 0.065f, 0.05f}),
                 diffuse({0.14f, 0.45f, 0.09f}), diffuse(glm::vec3(0.0f), {17.0f, 12.0f, 4.0f})};
  const auto quad = [&](int m, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
    sc::Mesh mesh;
    mesh.material = m;
    mesh.object_id = uint32_t(s.meshes.size() + 1);
    mesh.positions = {a, b, c, d};
    const glm::vec3 nn = glm::normalize(glm::cross(b - a, c - a));
    mesh.normals = {nn, nn, nn, nn};
    mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    s.meshes.push_back(mesh);
  };
  quad(0, {-1, -1, 1}, {1, -1, 1}, {1, -1, -1}, {-1, -1, -1});
  quad(0, {-1, 1, -1}, {1, 1, -1}, {1, 1, 1}, {-1, 1, 1});
  quad(0, {-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1});
  quad(1, {-1, -1, 1}, {-1, -1, -1}, {-1, 1, -1}, {-1, 1, 1});
  quad(2, {1, -1, -1}, {1, -1, 1}, {1, 1, 1}, {1, 1, -1});
  quad(3, {-0.25f, 0.99f, -0.25f}, {0.25f, 0.99f, -0.25f}, {0.25f, 0.99f, 0.25f},
       {-0.25f, 0.99f, 0.25f});
  // UV sphere: rings x segments x 2 triangles ~ n.
  const int seg = std::max(8, int(std::sqrt(double(n))));
  const int rings = std::max(4, int(n / (2 * size_t(seg))));
  sc::Mesh sphere;
  sphere.material = 0;
  sphere.object_id = 99;
  const glm::vec3 c(0.1f, -0.5f, 0.0f);
  for (int i = 0; i <= rings; ++i)
    for (int j = 0; j <= seg; ++j) {
      const float th = 3.14159265f * float(i) / float(rings),
                  ph = 6.2831853f * float(j) / float(seg);
      const glm::vec3 nrm(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
      sphere.positions.push_back(c + 0.45f * nrm);
      sphere.normals.push_back(nrm);
    }
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < seg; ++j) {
      const uint32_t a = uint32_t(i * (seg + 1) + j), b = a + uint32_t(seg + 1);
      if (i != 0) sphere.triangles.push_back({a, a + 1, b});
      if (i != rings - 1) sphere.triangles.push_back({a + 1, b + 1, b});
    }
  s.meshes.push_back(sphere);
  sc::View v;
  v.name = "front";
  v.camera = sc::Camera::look_at({0, 0, 3.4f}, {0, 0, 0}, {0, 1, 0}, 0.7f);
  s.views.push_back(v);
  s.derive();
  return s;
}

}  // namespace

int main(int argc, char** argv) try {
  CLI::App app{"Benchmarks of the reference path tracer (Markdown on stdout)",
               "giq-bench-reference"};
  std::string scenes_dir = "scenes";
  int size = 512, threads = 0, throughput_reps = 3;
  double seconds = 5.0, target = 1e-3;
  uint32_t ref_spp = 4096, max_spp = 4096;
  std::vector<size_t> triangles = {10000, 100000, 1000000};
  std::vector<std::string> names = {"cornell", "leak", "sunroom", "movinglight"};
  std::string references, sampler = "sobol";
  uint32_t sobol_block = ref::RenderSettings().sobol_block;
  bool scaling = true, time_to_error_too = true, raw = false;
  app.add_option("--scenes", scenes_dir, "Folder of the built-in scenes")->capture_default_str();
  app.add_option("--size", size, "Image width and height")->capture_default_str();
  app.add_option("--threads", threads, "Threads (0 = all cores)")->capture_default_str();
  app.add_option("--seconds", seconds, "Seconds per throughput measurement")->capture_default_str();
  app.add_option("--throughput-reps", throughput_reps,
                 "Alternating specialised / generic throughput measurements per scene (medians are reported)")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  app.add_option("--ref-spp", ref_spp, "Samples per pixel of the long renders")
      ->capture_default_str();
  app.add_option("--target", target, "relMSE target of the time-to-error measurement")
      ->capture_default_str();
  app.add_option("--max-spp", max_spp, "Give up time-to-error beyond this spp")
      ->capture_default_str();
  app.add_option("--triangles", triangles, "Triangle counts of the scaling test")
      ->capture_default_str();
  app.add_option("--only", names, "Built-in scenes to measure")->capture_default_str();
  app.add_option("--references", references,
                 "Folder of long renders <scene>.exr: used when present (same size), else rendered "
                 "and written there");
  app.add_flag("!--no-scaling", scaling, "Skip the triangle-count scaling test");
  app.add_flag("!--no-time-to-error", time_to_error_too, "Throughput only: skip the long renders and the time to error");
  app.add_flag("--raw-rays", raw, "Also: one thread's rays per second against Embree's alone on the same rays (16 spp)");
  app.add_option("--sampler", sampler, "giq reference's sampler: sobol or independent")->capture_default_str();
  app.add_option("--sobol-block", sobol_block, "Samples per Sobol block")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  ref::RenderSettings rs;
  rs.width = rs.height = size;
  rs.threads = threads;
  rs.sampler = ref::parse_sampler(sampler);
  rs.sobol_block = sobol_block;
  std::printf("Machine: %u hardware threads; image %dx%d; threads %s; sampler %s; throughput: median of %d "
              "alternating runs of %g s each\n\n",
              std::thread::hardware_concurrency(), size, size, threads == 0 ? "all" : std::to_string(threads).c_str(),
              ref::describe_sampler(rs).c_str(), throughput_reps, seconds);
  std::printf(
      "| scene | features (mask) | Msamples/s | Mrays/s | one path at a time Msamples/s | lanes speed-up | "
      "generic Msamples/s | specialisation saving | time to relMSE %.0e | spp | long render spp |\n",
      target);
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const std::string& name : names) {
    const std::filesystem::path path = std::filesystem::path(scenes_dir) / (name + ".gltf");
    const sc::Scene s = sc::load(path);
    const sc::Camera cam = s.views.at(0).camera;
    // The lanes' speed-up is measured on every scene (Lanes::Always against Never); what the
    // renderer runs by default (Auto) is one of the two.
    ref::RenderSettings single = rs, generic = rs, lanes = rs;
    single.lanes = ref::RenderSettings::Lanes::Never;
    lanes.lanes = ref::RenderSettings::Lanes::Always;
    generic.all_features = true, generic.lanes = ref::RenderSettings::Lanes::Never;
    const ref::Renderer probe(s, cam, rs), laned(s, cam, lanes);
    // Alternated, so that a change in the machine's load between them does not pass for a
    // difference between the integrators.
    std::vector<double> paths, rays, single_paths, gen_paths, speedup, saving;
    for (int rep = 0; rep < throughput_reps; ++rep) {
      const Throughput eight = laned.lanes() ? measure(s, cam, lanes, seconds) : Throughput{};
      const Throughput b = measure(s, cam, single, seconds);
      const Throughput c = measure(s, cam, generic, seconds);
      const Throughput a = probe.lanes() ? eight : b;  // as rendered
      paths.push_back(a.samples_per_s), rays.push_back(a.rays_per_s);
      single_paths.push_back(b.samples_per_s), gen_paths.push_back(c.samples_per_s);
      speedup.push_back(eight.samples_per_s / b.samples_per_s);
      saving.push_back(1.0 - c.samples_per_s / b.samples_per_s);
    }
    std::string feats;
    for (const auto& f : s.features.names()) feats += (feats.empty() ? "" : ", ") + f;
    char speedup_text[48] = "(one at a time)";
    if (laned.lanes())
      std::snprintf(speedup_text, sizeof speedup_text, "%.2fx%s", median(speedup), probe.lanes() ? "" : " (not used)");
    if (raw) {
      // As rendered (Auto) and one path at a time, each against its own rays traced alone.
      for (const ref::RenderSettings& variant : {rs, single}) {
        std::vector<double> ratio, render_rate, raw_rate_v;
        uint64_t rays = 0;
        for (int rep = 0; rep < throughput_reps; ++rep) {
          const RawRate r = raw_rate(s, cam, variant, 16);
          ratio.push_back(r.render / r.raw), render_rate.push_back(r.render), raw_rate_v.push_back(r.raw), rays = r.rays;
        }
        std::fprintf(stderr, "raw rays: %s %s: render %.3f Mrays/s, Embree alone %.3f Mrays/s on the same %llu rays: %.0f %%\n",
                     name.c_str(), ref::Renderer(s, cam, variant).lanes() ? "lanes" : "one path", median(render_rate) / 1e6,
                     median(raw_rate_v) / 1e6, (unsigned long long)rays, 100.0 * median(ratio));
      }
    }
    if (!time_to_error_too) {
      std::printf("| %s | %s (%u) | %.3f | %.3f | %.3f | %s | %.3f | %.1f %% | | | |\n", name.c_str(), feats.c_str(),
                  probe.feature_mask(), median(paths) / 1e6, median(rays) / 1e6, median(single_paths) / 1e6, speedup_text,
                  median(gen_paths) / 1e6, 100.0 * median(saving));
      std::fflush(stdout);
      continue;
    }
    ref::RenderSettings long_rs = rs;
    long_rs.seed = 777;
    const std::filesystem::path cached = references.empty()
                                             ? std::filesystem::path()
                                             : std::filesystem::path(references) / (name + ".exr");
    giq::bench::LongRender reference;
    if (!cached.empty() && std::filesystem::exists(cached))
      reference = giq::bench::LongRender::from_exr(cached);
    // A cached file counts only for the same scene content, view and image-determining settings.
    if (reference.scene_hash != s.content_hash || reference.view != s.views.at(0).name ||
        reference.settings != ref::settings_json(long_rs)) {
      const ref::Renderer long_r(s, cam, long_rs);
      ref::Film film = long_r.make_film();
      long_r.render(film, ref_spp);
      if (!cached.empty()) {
        std::filesystem::create_directories(cached.parent_path());
        ref::ReferenceMetadata meta;
        meta.scene = path.string();
        meta.scene_hash = s.content_hash;
        meta.view = s.views.at(0).name;
        meta.camera = cam;
        giq::image::write_exr(ref::reference_image(film, long_rs, meta), cached);
      }
      reference = giq::bench::LongRender::from_film(film);
    }
    uint32_t spp_reached = 0;
    const double tte = time_to_error(s, cam, rs, reference, target, max_spp, spp_reached);
    char tte_text[32];
    if (tte >= 0.0)
      std::snprintf(tte_text, sizeof tte_text, "%.2f s", tte);
    else
      std::snprintf(tte_text, sizeof tte_text, "not within %u spp", max_spp);
    std::printf("| %s | %s (%u) | %.3f | %.3f | %.3f | %s | %.3f | %.1f %% | %s | %u | %.0f |\n", name.c_str(),
                feats.c_str(), probe.feature_mask(), median(paths) / 1e6, median(rays) / 1e6,
                median(single_paths) / 1e6, speedup_text, median(gen_paths) / 1e6, 100.0 * median(saving), tte_text,
                spp_reached, reference.spp);
    std::fflush(stdout);
  }
  if (!scaling) return 0;
  std::printf("\n| triangles | BVH build s | Msamples/s | Mrays/s |\n|---|---|---|---|\n");
  for (size_t n : triangles) {
    const sc::Scene s = tessellated(n);
    const Clock::time_point t0 = Clock::now();
    const ref::Renderer r(s, s.views[0].camera, rs);
    const double build = seconds_since(t0);
    const Throughput t = measure(s, s.views[0].camera, rs, seconds);
    std::printf("| %zu | %.3f | %.3f | %.3f |\n", s.stats.triangles, build, t.samples_per_s / 1e6,
                t.rays_per_s / 1e6);
    std::fflush(stdout);
  }
  return 0;
} catch (const giq::InputError& e) {
  std::fprintf(stderr, "giq-bench-reference: %s\n", e.what());
  return 2;
}
