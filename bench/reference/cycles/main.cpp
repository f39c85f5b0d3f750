// giq-bench-cycles: giq's reference path tracer against Blender's Cycles (CPU) on the same
// glTF scene, at the same size and spp, both measured against giq's long render.
//
// For each repetition, Cycles (render_cycles.py inside `blender -b`, one process that renders
// on request) and giq (in this process) render one independent image per spp count, one
// right after the other, alternating which goes first, so that the slow phases of a shared
// machine hit both alike.
// Each image's relMSE against the long render (its own variance subtracted, long_render.h)
// and its render time give a curve error(time) per renderer and repetition; the time to reach
// a relMSE is interpolated on it in log-log. The ratio Cycles time / giq time at equal error
// is taken within each repetition, then the median over repetitions is reported; so is the
// median over image pairs of the ratio of time x relMSE (equal to the time ratio at equal
// error when relMSE ~ 1/time, which the reported slopes check).
//
// Whether the two renderers compute the same image is checked, not assumed: the mean of every
// channel over the image, and an estimate of the squared bias of Cycles' image against giq's
// long render (relMSE minus Cycles' own variance, which two independent Cycles images of the
// same spp measure: E[(c1 - c2)^2] = 2 Var(c)). The same estimate for giq's own images shows
// the noise of that estimate.
//
// Where the two models differ (glossy materials: render_cycles.py's rebuild_material says
// how), that bias would count as error against giq's long render and no number of samples
// would remove it. So the time to equal error is also taken on noise alone: each spp's
// variance from the pairs of repetitions, (1/2) E[(a - b)^2], normalised like relMSE. For
// the same model both measures agree (the Cornell box shows it); for different models the
// noise-only ratio is the speed comparison and the squared bias is the model difference.

#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cpu_model.h"
#include "giq/base/error.h"
#include "giq/image/io.h"
#include "giq/reference/reference_exr.h"
#include "giq/reference/renderer.h"
#include "giq/scenes/scene.h"
#include "long_render.h"

namespace {

namespace ref = giq::reference;
namespace sc = giq::scenes;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

struct Point {
  uint32_t spp = 0;
  double seconds = 0.0;
  double error = 0.0;  // relMSE against the long render, its variance subtracted
};

// Seconds to reach relMSE `target` on a curve of increasing spp: log-log linear between the
// two points bracketing it, else extrapolated from the nearest two (relMSE ~ 1/time for an
// unbiased Monte Carlo estimator, which the slope column checks). `extrapolated` says which.
double time_to(const std::vector<Point>& c, double target, bool& extrapolated) {
  size_t k = 1;
  while (k + 1 < c.size() && c[k].error > target) ++k;
  extrapolated = !(c[k - 1].error >= target && c[k].error <= target);
  const double a = std::log(c[k - 1].error / target) / std::log(c[k - 1].error / c[k].error);
  return std::exp(std::log(c[k - 1].seconds) +
                  a * (std::log(c[k].seconds) - std::log(c[k - 1].seconds)));
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n == 0 ? 0.0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char ch : s) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return q + "'";
}

std::string first_line_of(const std::string& command) {
  std::string line;
  if (FILE* p = popen(command.c_str(), "r")) {
    char buf[512];
    if (std::fgets(buf, sizeof buf, p)) line = buf;
    if (pclose(p) != 0) line.clear();
  }
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
  return line;
}

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  double a = 0, b = 0, c = 0;
  in >> a >> b >> c;
  char text[64];
  std::snprintf(text, sizeof text, "%.2f %.2f %.2f", a, b, c);
  return text;
}

// The beauty of an image as 3 doubles per pixel.
std::vector<double> beauty(const giq::image::Image& img) {
  std::vector<double> v(img.pixel_count() * 3);
  const float* ch[3] = {img.channel("R"), img.channel("G"), img.channel("B")};
  for (size_t i = 0; i < img.pixel_count(); ++i)
    for (int c = 0; c < 3; ++c) v[3 * i + size_t(c)] = ch[c][i];
  return v;
}
std::vector<double> beauty(const ref::Film& f) {
  std::vector<double> v(f.pixels.size() * 3);
  for (size_t i = 0; i < f.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) v[3 * i + size_t(c)] = f.pixels[i].mean[c];
  return v;
}

// Squared bias of a renderer's images against the long render: their mean relMSE minus their
// own variance term, estimated from pairs of independent images (E[(a - b)^2] = 2 Var).
struct BiasEstimate {
  double error = 0.0, own_variance = 0.0, bias2 = 0.0;
};
// A set of independent images' own variance, normalised like relMSE: the mean over pairs
// of (1/2) (a - b)^2 / (mean^2 + 0.01).
double pair_variance(const std::vector<std::vector<double>>& images,
                     const giq::bench::LongRender& lr) {
  double v = 0.0;
  int pairs = 0;
  for (size_t a = 0; a < images.size(); ++a)
    for (size_t k = a + 1; k < images.size(); ++k, ++pairs) {
      double s = 0.0;
      for (size_t j = 0; j < lr.mean.size(); ++j) {
        const double d = images[a][j] - images[k][j];
        s += d * d / (lr.mean[j] * lr.mean[j] + 0.01);
      }
      v += 0.5 * s / double(lr.mean.size());
    }
  return pairs > 0 ? v / double(pairs) : 0.0;
}

BiasEstimate bias_estimate(const std::vector<std::vector<double>>& images,
                           const giq::bench::LongRender& lr) {
  BiasEstimate b;
  for (const auto& im : images)
    b.error += lr.rel_mse_of([&](size_t i, int c) { return im[3 * i + size_t(c)]; });
  b.error /= double(images.size());
  b.own_variance = pair_variance(images, lr);
  b.bias2 = b.error - b.own_variance;
  return b;
}

std::array<double, 3> channel_means(const std::vector<double>& im) {
  std::array<double, 3> m{0.0, 0.0, 0.0};
  for (size_t j = 0; j < im.size(); ++j) m[j % 3] += im[j];
  for (double& x : m) x /= double(im.size() / 3);
  return m;
}

// Blender running render_cycles.py with --spp stdin: each render() asks for one image and
// waits for its line; Blender's own output goes to the log.
class CyclesProcess {
 public:
  CyclesProcess(const std::string& command, std::ofstream& log, const fs::path& log_path)
      : log_(log), log_path_(log_path) {
    int in[2], out[2];
    if (pipe(in) != 0 || pipe(out) != 0)
      throw giq::InputError("", "", "cannot create pipes for Blender");
    pid_ = fork();
    if (pid_ == 0) {
      dup2(in[0], 0);
      dup2(out[1], 1);
      dup2(out[1], 2);
      close(in[0]), close(in[1]), close(out[0]), close(out[1]);
      execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    close(in[0]), close(out[1]);
    to_ = fdopen(in[1], "w");
    from_ = fdopen(out[0], "r");
    wait_for("giq-cycles ready");
  }
  ~CyclesProcess() { close_and_wait(); }
  CyclesProcess(const CyclesProcess&) = delete;
  CyclesProcess& operator=(const CyclesProcess&) = delete;

  std::string render(uint32_t spp) {
    std::fprintf(to_, "%u\n", spp);
    std::fflush(to_);
    return wait_for("giq-cycles spp=");
  }
  // Ends Blender (end of its input) and throws if it failed.
  void finish() {
    if (!close_and_wait())
      throw giq::InputError(log_path_.string(), "", "Blender failed; its output is in this file");
  }

 private:
  bool close_and_wait() {
    if (pid_ <= 0) return true;
    std::fclose(to_);
    char buf[4096];
    while (std::fgets(buf, sizeof buf, from_)) log_ << buf;
    std::fclose(from_);
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = -1;
    log_.flush();
    return WIFEXITED(status) && WEXITSTATUS(status) == 0;
  }

  std::string wait_for(const std::string& prefix) {
    char buf[4096];
    std::string reason;  // render_cycles.py's own message, if it gave one
    while (std::fgets(buf, sizeof buf, from_)) {
      log_ << buf;
      if (std::string(buf).rfind(prefix, 0) == 0) return buf;
      if (std::string(buf).rfind("render_cycles.py: ", 0) == 0) reason = buf;
    }
    log_.flush();
    while (!reason.empty() && reason.back() == '\n') reason.pop_back();
    throw giq::InputError(log_path_.string(), "",
                          "Blender ended early" +
                              (reason.empty() ? std::string() : " (" + reason + ")") +
                              "; its output is in this file");
  }

  std::ofstream& log_;
  fs::path log_path_;
  pid_t pid_ = -1;
  FILE* to_ = nullptr;
  FILE* from_ = nullptr;
};

}  // namespace

int main(int argc, char** argv) try {
  CLI::App app{
      "giq's reference path tracer against Blender's Cycles at equal error (Markdown on stdout)",
      "giq-bench-cycles"};
  std::string scene_path = "scenes/cornell.gltf", blender = "blender", script = GIQ_CYCLES_SCRIPT,
              work = "/tmp/giq-bench-cycles", reference_path, sampler = "sobol";
  uint32_t sobol_block = ref::RenderSettings().sobol_block;
  int size = 512, threads = 0, reps = 3, max_bounces = 64;
  uint32_t ref_spp = 1024;
  double target = 1e-3;
  std::vector<uint32_t> spps = {32, 64, 128, 256};
  app.add_option("--scene", scene_path,
                 "A glTF scene render_cycles.py can rebuild (its first view is rendered)")
      ->capture_default_str();
  app.add_option("--size", size, "Image width and height")->capture_default_str();
  app.add_option("--spp", spps, "Sample counts, increasing; each is an independent render")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--reps", reps, "Repetitions (medians are reported)")->capture_default_str();
  app.add_option("--ref-spp", ref_spp, "Samples per pixel of giq's long render")
      ->capture_default_str();
  app.add_option("--reference", reference_path,
                 "giq's long render: read when it matches (scene, view, size), else rendered and "
                 "written there "
                 "(default WORK/<scene>-<size>.exr)");
  app.add_option("--target", target, "relMSE of the time-to-error comparison")
      ->capture_default_str();
  app.add_option("--max-bounces", max_bounces,
                 "Scattering events per path of both renderers (1 = direct light)")
      ->capture_default_str();
  app.add_option("--sampler", sampler, "giq's sampler: sobol or independent")->capture_default_str();
  app.add_option("--sobol-block", sobol_block, "Samples per Sobol block")->capture_default_str();
  app.add_option("--threads", threads, "Threads of both renderers (0 = all cores)")
      ->capture_default_str();
  app.add_option("--blender", blender, "Blender executable")->capture_default_str();
  app.add_option("--script", script, "render_cycles.py")->capture_default_str();
  app.add_option("--work", work, "Folder for Cycles' images and the long render")
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  if (spps.size() < 2 || !std::is_sorted(spps.begin(), spps.end()) || spps.front() < 1 ||
      reps < 1 || size < 1)
    throw giq::InputError("", "--spp/--reps/--size",
                          "at least two increasing spp counts >= 1, reps >= 1, size >= 1");

  const std::string version =
      first_line_of(quote(blender) + " -b --factory-startup --version 2>/dev/null");
  if (version.empty()) {
    std::fprintf(
        stderr,
        "giq-bench-cycles: '%s' does not run. Install Blender and the numpy its glTF importer "
        "needs:\n"
        "  apt-get install -y blender python3-numpy   (or tools/bootstrap --with-blender)\n",
        blender.c_str());
    return 2;
  }
  if (threads == 0) threads = int(std::thread::hardware_concurrency());
  std::signal(SIGPIPE, SIG_IGN);  // a Blender that died is reported from its log instead
  fs::create_directories(work);

  const sc::Scene scene = sc::load(scene_path);
  const sc::View& view = scene.views.at(0);
  const sc::Camera& cam = view.camera;
  ref::RenderSettings rs;
  rs.width = rs.height = size;
  rs.threads = threads;
  rs.max_bounces = max_bounces;
  rs.sampler = ref::parse_sampler(sampler);
  rs.sobol_block = sobol_block;

  std::printf("# giq reference vs Blender Cycles: %s, %dx%d, max bounces %d, giq's sampler %s\n\n",
              scene_path.c_str(), size, size, max_bounces,
              ref::describe_sampler(rs).c_str());
  std::printf(
      "Machine: %s, %u hardware threads; both renderers on %d threads; %s; load average at start "
      "%s\n\n",
      giq::bench::cpu_model().c_str(), std::thread::hardware_concurrency(), threads, version.c_str(),
      load_average().c_str());
  std::fflush(stdout);

  // giq's long render, the ground truth of both.
  if (reference_path.empty())
    reference_path = (fs::path(work) /
                      (fs::path(scene_path).stem().string() + "-" + std::to_string(size) + ".exr"))
                         .string();
  ref::RenderSettings long_rs = rs;
  long_rs.seed = 777;
  giq::bench::LongRender lr;
  if (fs::exists(reference_path)) lr = giq::bench::LongRender::from_exr(reference_path);
  // A file counts only for the same scene content, view and image-determining settings.
  if (lr.scene_hash != scene.content_hash || lr.view != view.name ||
      lr.settings != ref::settings_json(long_rs)) {
    const ref::Renderer r(scene, cam, long_rs);
    ref::Film film = r.make_film();
    const Clock::time_point t0 = Clock::now();
    r.render(film, ref_spp);
    std::printf("Long render: %u spp in %.1f s, written to %s\n", ref_spp, seconds_since(t0),
                reference_path.c_str());
    ref::ReferenceMetadata meta;
    meta.scene = scene_path;
    meta.scene_hash = scene.content_hash;
    meta.view = view.name;
    meta.camera = cam;
    giq::image::write_exr(ref::reference_image(film, long_rs, meta), reference_path);
    lr = giq::bench::LongRender::from_film(film);
    lr.scene_hash = scene.content_hash;
    lr.view = view.name;
    lr.settings = ref::settings_json(long_rs);
  }
  std::printf(
      "Long render (giq, %s): %.0f spp; its own relMSE contribution %.3g (subtracted from every "
      "error)\n\n",
      reference_path.c_str(), lr.spp, lr.variance_term);
  std::fflush(stdout);

  // giq's camera in the glTF's frame for render_cycles.py.
  const glm::dvec3 eye = glm::dvec3(cam.position) + scene.origin;
  std::ostringstream camera_arg;
  camera_arg.precision(9);
  camera_arg << eye.x << ',' << eye.y << ',' << eye.z << ',' << cam.forward.x << ','
             << cam.forward.y << ',' << cam.forward.z << ',' << cam.up.x << ',' << cam.up.y << ','
             << cam.up.z << ',' << cam.yfov;

  std::vector<std::vector<Point>> giq_curves(static_cast<size_t>(reps)),
      cycles_curves(static_cast<size_t>(reps));
  // Every image, per spp and repetition, for the variances from pairs.
  std::vector<std::vector<std::vector<double>>> giq_images(spps.size()), cycles_images(spps.size());
  const fs::path log_path = fs::path(work) / "blender.log";
  std::ofstream blender_log(log_path);

  const auto render_giq = [&](int rep, uint32_t spp) {
    ref::RenderSettings s = rs;
    s.seed = 1000 + uint64_t(rep);
    // Timed like Cycles' render call: the renderer (BVH, lights) is built for each image.
    const Clock::time_point t0 = Clock::now();
    const ref::Renderer r(scene, cam, s);
    ref::Film film = r.make_film();
    r.render(film, spp);
    const double t = seconds_since(t0);
    giq_curves[size_t(rep)].push_back({spp, t, lr.rel_mse(film)});
    giq_images[giq_curves[size_t(rep)].size() - 1].push_back(beauty(film));
  };
  const auto render_cycles = [&](int rep, CyclesProcess& blender_process, uint32_t spp) {
    const std::string line = blender_process.render(spp);
    Point pt;
    char file[2048] = {0};
    if (std::sscanf(line.c_str(), "giq-cycles spp=%u seconds=%lf file=%2047s", &pt.spp, &pt.seconds,
                    file) != 3 ||
        pt.spp != spp)
      throw giq::InputError(log_path.string(), "",
                            "unexpected line from render_cycles.py: " + line);
    const giq::image::Image img = giq::image::read_image(file);
    pt.error = lr.rel_mse(img, file);
    cycles_curves[size_t(rep)].push_back(pt);
    cycles_images[cycles_curves[size_t(rep)].size() - 1].push_back(beauty(img));
  };

  // One Blender process per repetition renders on request, so each Cycles image is taken
  // right next to giq's image of the same spp; which of the two goes first alternates.
  std::printf(
      "| rep | spp | first | load avg | giq s | giq relMSE | Cycles s | Cycles relMSE | Cycles / "
      "giq time x "
      "relMSE |\n|---|---|---|---|---|---|---|---|---|\n");
  std::vector<double> pair_ratios;
  for (int rep = 0; rep < reps; ++rep) {
    CyclesProcess blender_process(
        quote(blender) + " -b --factory-startup --python-exit-code 2 --python " + quote(script) +
            " -- --gltf " + quote(scene_path) + " --out " + quote(work) + " --size " +
            std::to_string(size) + " --threads " + std::to_string(threads) + " --seed " +
            std::to_string(rep + 1) + " --max-bounces " + std::to_string(max_bounces) +
            " --spp stdin --camera=" + camera_arg.str(),
        blender_log, log_path);
    for (size_t k = 0; k < spps.size(); ++k) {
      const std::string load = load_average();
      const bool cycles_first = (size_t(rep) + k) % 2 == 0;
      if (cycles_first) render_cycles(rep, blender_process, spps[k]);
      render_giq(rep, spps[k]);
      if (!cycles_first) render_cycles(rep, blender_process, spps[k]);
      const Point &g = giq_curves[size_t(rep)][k], &c = cycles_curves[size_t(rep)][k];
      // For unbiased estimators relMSE x time is constant: its ratio is the ratio of the
      // times to any equal error, measured on two images taken one after the other.
      pair_ratios.push_back(c.seconds * c.error / (g.seconds * g.error));
      std::printf("| %d | %u | %s | %s | %.3f | %.4g | %.3f | %.4g | %.2f |\n", rep, g.spp,
                  cycles_first ? "Cycles" : "giq", load.c_str(), g.seconds, g.error, c.seconds,
                  c.error, pair_ratios.back());
      std::fflush(stdout);
    }
    blender_process.finish();
  }

  // Medians over repetitions, per spp.
  const double pixels = double(size) * double(size);
  std::printf("\nMedians over %d repetitions (Msamples/s = camera paths per second):\n\n", reps);
  std::printf(
      "| spp | giq s | giq Msamples/s | giq relMSE | Cycles s | Cycles Msamples/s | Cycles relMSE "
      "| Cycles s at giq's "
      "relMSE | Cycles / giq time at equal error |\n|---|---|---|---|---|---|---|---|---|\n");
  std::vector<Point> giq_median, cycles_median;
  for (size_t k = 0; k < spps.size(); ++k) {
    std::vector<double> gt, ge, ct, ce;
    for (int rep = 0; rep < reps; ++rep) {
      gt.push_back(giq_curves[size_t(rep)][k].seconds),
          ge.push_back(giq_curves[size_t(rep)][k].error);
      ct.push_back(cycles_curves[size_t(rep)][k].seconds),
          ce.push_back(cycles_curves[size_t(rep)][k].error);
    }
    giq_median.push_back({spps[k], median(gt), median(ge)});
    cycles_median.push_back({spps[k], median(ct), median(ce)});
  }
  for (size_t k = 0; k < spps.size(); ++k) {
    const Point &g = giq_median[k], &c = cycles_median[k];
    bool extra = false;
    const double tc = time_to(cycles_median, g.error, extra);
    std::printf("| %u | %.3f | %.3f | %.4g | %.3f | %.3f | %.4g | %.3f%s | %.2f |\n", g.spp,
                g.seconds, pixels * g.spp / g.seconds / 1e6, g.error, c.seconds,
                pixels * c.spp / c.seconds / 1e6, c.error, tc, extra ? " (extrapolated)" : "",
                tc / g.seconds);
  }
  const auto slope = [](const std::vector<Point>& m) {
    return std::log(m.back().error / m.front().error) /
           std::log(m.back().seconds / m.front().seconds);
  };
  std::printf(
      "\nSlope of log relMSE over log time (-1 for unbiased Monte Carlo): giq %.3f, Cycles %.3f\n",
      slope(giq_median), slope(cycles_median));

  // Time to the target, per repetition (interleaved pairs), then medians.
  std::vector<double> tg, tc, ratio;
  bool any_extra = false;
  for (int rep = 0; rep < reps; ++rep) {
    bool eg = false, ec = false;
    tg.push_back(time_to(giq_curves[size_t(rep)], target, eg));
    tc.push_back(time_to(cycles_curves[size_t(rep)], target, ec));
    ratio.push_back(tc.back() / tg.back());
    any_extra = any_extra || eg || ec;
  }
  std::printf(
      "\nTime to relMSE %.0e (median of %d repetitions%s): giq %.2f s, Cycles %.2f s; Cycles / giq "
      "= %.2f "
      "(per repetition:",
      target, reps, any_extra ? ", extrapolated beyond the measured spp" : "", median(tg),
      median(tc), median(ratio));
  for (double r : ratio) std::printf(" %.2f", r);
  std::printf(")\n");
  std::printf(
      "Median over all %zu image pairs of Cycles / giq time x relMSE (the time ratio at equal "
      "error when relMSE "
      "~ 1/time): %.2f\n",
      pair_ratios.size(), median(pair_ratios));

  // Noise alone: each spp's variance from the pairs of repetitions, on the median times.
  if (reps >= 2) {
    std::vector<Point> giq_noise, cycles_noise;
    std::printf(
        "\nNoise alone (variance from the %d pairs of repetitions at each spp, normalised like "
        "relMSE; the model difference is not in it):\n\n| spp | giq s | giq variance | Cycles s | "
        "Cycles variance | Cycles / giq time x variance |\n|---|---|---|---|---|---|\n",
        reps * (reps - 1) / 2);
    for (size_t k = 0; k < spps.size(); ++k) {
      giq_noise.push_back({spps[k], giq_median[k].seconds, pair_variance(giq_images[k], lr)});
      cycles_noise.push_back(
          {spps[k], cycles_median[k].seconds, pair_variance(cycles_images[k], lr)});
      const Point &g = giq_noise.back(), &c = cycles_noise.back();
      std::printf("| %u | %.3f | %.4g | %.3f | %.4g | %.2f |\n", g.spp, g.seconds, g.error,
                  c.seconds, c.error, c.seconds * c.error / (g.seconds * g.error));
    }
    bool eg = false, ec = false;
    const double ng = time_to(giq_noise, target, eg), nc = time_to(cycles_noise, target, ec);
    std::printf(
        "\nSlope of log variance over log time: giq %.3f, Cycles %.3f\nTime to a variance of "
        "%.0e%s: giq %.2f s, Cycles %.2f s; Cycles / giq = %.2f\n",
        slope(giq_noise), slope(cycles_noise), target,
        eg || ec ? " (extrapolated beyond the measured spp)" : "", ng, nc, nc / ng);
  }

  // Do the renderers agree? Channel means and the squared-bias estimate at the largest spp.
  std::array<double, 3> ref_mean{0, 0, 0}, ref_se{0, 0, 0};
  for (size_t j = 0; j < lr.mean.size(); ++j)
    ref_mean[j % 3] += lr.mean[j], ref_se[j % 3] += lr.variance[j];
  const double n_px = double(lr.mean.size() / 3);
  std::printf(
      "\nAgreement at %u spp (%d images each):\n\n| | mean R | mean G | mean B "
      "|\n|---|---|---|---|\n",
      spps.back(), reps);
  std::printf("| giq long render | %.5f +- %.5f | %.5f +- %.5f | %.5f +- %.5f |\n",
              ref_mean[0] / n_px, std::sqrt(ref_se[0]) / n_px, ref_mean[1] / n_px,
              std::sqrt(ref_se[1]) / n_px, ref_mean[2] / n_px, std::sqrt(ref_se[2]) / n_px);
  const auto& giq_last = giq_images.back();
  const auto& cycles_last = cycles_images.back();
  for (const auto* set : {&giq_last, &cycles_last}) {
    std::array<double, 3> m{0, 0, 0}, m2{0, 0, 0};
    for (const auto& im : *set) {
      const auto cm = channel_means(im);
      for (int c = 0; c < 3; ++c) m[c] += cm[c], m2[c] += cm[c] * cm[c];
    }
    const double n = double(set->size());
    std::printf("| %s | ", set == &giq_last ? "giq" : "Cycles");
    for (int c = 0; c < 3; ++c) {
      const double mean = m[c] / n,
                   sd = n > 1 ? std::sqrt(std::max(0.0, (m2[c] - n * mean * mean) / (n - 1))) : 0.0;
      std::printf("%.5f +- %.5f | ", mean, sd / std::sqrt(n));
    }
    std::printf("\n");
  }
  std::printf(
      "\n(+- one standard error: the long render's from its pixel variances, the others' from the "
      "spread of "
      "their repetitions)\n\n| renderer | relMSE vs long render | own variance (from pairs) | "
      "squared bias "
      "estimate |\n|---|---|---|---|\n");
  for (const auto* set : {&giq_last, &cycles_last}) {
    const BiasEstimate b = bias_estimate(*set, lr);
    std::printf("| %s | %.4g | %.4g | %.3g |\n", set == &giq_last ? "giq" : "Cycles", b.error,
                b.own_variance, b.bias2);
  }
  std::printf("\nLoad average at the end: %s\n", load_average().c_str());
  return 0;
} catch (const giq::InputError& e) {
  std::fprintf(stderr, "giq-bench-cycles: %s\n", e.what());
  return 2;
}
