// `giq reference`: renders the path-traced ground truth of a scene's view as a multi-layer
// reference EXR, with checkpoints and resume. See docs/reference.md.

#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "command.h"
#include "progress.h"
#include "reference_frame.h"
#include "scene_setup.h"
#include "integer_check.h"
#include "output_guard.h"
#include "giq/base/error.h"
#include "giq/base/frames.h"
#include "giq/image/io.h"
#include "giq/reference/progressive_render.h"
#include "giq/reference/reference_exr.h"
#include "giq/reference/renderer.h"
#include "giq/scenes/scene.h"

namespace giq::cli {
namespace {

namespace fs = std::filesystem;
namespace ref = giq::reference;
namespace sc = giq::scenes;

std::atomic<bool> g_cancel{false};
extern "C" void on_signal(int) { g_cancel.store(true); }

// SIGINT/SIGTERM ask the render to stop at the next pass boundary and save a checkpoint. The
// handlers cover the whole command, not only the render loop: a signal that arrives while the
// scene loads is kept and honoured by the first render, so an interruption always leaves a
// checkpoint to --resume from instead of killing the process with nothing saved.
class InterruptGuard {
 public:
  InterruptGuard() : old_int_(std::signal(SIGINT, on_signal)), old_term_(std::signal(SIGTERM, on_signal)) {}
  ~InterruptGuard() {
    std::signal(SIGINT, old_int_);
    std::signal(SIGTERM, old_term_);
  }
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

 private:
  void (*old_int_)(int);
  void (*old_term_)(int);
};

struct Options {
  std::string scene;
  std::string view;
  SceneSetup setup;  // --camera, --sun, --env
  int frame = 0;
  std::string frames;
  uint32_t spp = 0;
  double seconds = 0.0;
  double rel_error = 0.0;
  ref::RenderSettings settings;
  std::string estimator = "mis";
  std::string sampler = "sobol";
  std::string out;
  double checkpoint_interval = 60.0;
  bool resume = false;
  bool overwrite = false;
  bool record_time = false;
  bool half = false;
};

std::pair<int, int> frame_range(const Options& o, const sc::Scene& scene) {
  int a = o.frame, b = o.frame;
  if (!o.frames.empty()) {
    const auto range = parse_frame_range(o.frames);
    if (!range) throw InputError("", "--frames", "'" + o.frames + "' is not a range A:B with 0 <= A <= B");
    std::tie(a, b) = *range;
  }
  if (a < 0 || b >= scene.sequence.frames)
    throw InputError(scene.path.string(), "--frame", "frames " + std::to_string(a) + " to " + std::to_string(b) +
                                                         " are outside the scene's sequence 0 to " +
                                                         std::to_string(scene.sequence.frames - 1));
  return {a, b};
}

// The output path of one frame: "#" runs are replaced by the zero-padded frame number;
// otherwise, when several frames are rendered, ".<frame>" goes before the extension.
fs::path frame_path(const std::string& pattern, int frame, bool several) {
  const size_t hash = pattern.find('#');
  if (hash != std::string::npos) {
    size_t n = 0;
    while (hash + n < pattern.size() && pattern[hash + n] == '#') ++n;
    std::string num = std::to_string(frame);
    if (num.size() < n) num.insert(0, n - num.size(), '0');
    return pattern.substr(0, hash) + num + pattern.substr(hash + n);
  }
  if (!several) return pattern;
  fs::path p(pattern);
  char num[16];
  std::snprintf(num, sizeof num, ".%04d", frame);
  return p.parent_path() / (p.stem().string() + num + p.extension().string());
}

// --half: the colour layers (beauty, direct, indirect, albedo) as float16, a third of the
// size of float32 with zip compression on noisy data. Half keeps 11 significant bits, a
// relative rounding error of at most 2^-11 (4.9e-4), far below the per-pixel noise of any
// finite-spp render (golden/README.md has the measured ratio). The variance layer stays
// float32: it spans many decades and is squared into z-scores and noise floors; so do depth,
// normals, object ids and the sample count. A channel with a finite value beyond half's range
// (65504) stays float32 rather than turn into infinity.
image::ExrOptions exr_options(const image::Image& img, bool half) {
  image::ExrOptions opts;
  if (!half) return opts;
  for (const char* layer : {"", "direct", "indirect", "albedo"}) {
    if (!img.has_layer(layer)) continue;
    for (const std::string& name : img.layer_channels(layer)) {
      const float* c = img.channel(name);
      bool fits = true;
      for (size_t i = 0; i < img.pixel_count() && fits; ++i) fits = !(std::fabs(c[i]) > 65504.0f);
      if (fits) opts.half_channels.insert(name);
    }
  }
  return opts;
}

void draw_bar(ProgressLine& line, const ref::Progress& p, const std::string& label) {
  double fraction = 0.0;
  if (p.target_spp > 0) fraction = double(p.spp) / double(p.target_spp);
  else if (p.eta_seconds >= 0.0) fraction = p.elapsed_seconds / std::max(1e-9, p.elapsed_seconds + p.eta_seconds);
  constexpr int kWidth = 28;
  const int filled = int(std::clamp(fraction, 0.0, 1.0) * kWidth);
  std::string bar(size_t(filled), '=');
  bar.resize(kWidth, ' ');
  line.show("%s [%s] %u spp  %s elapsed  ETA %s  rel.err %.3g%%", label.c_str(), bar.c_str(), p.spp,
            format_seconds(p.elapsed_seconds).c_str(), format_seconds(p.eta_seconds).c_str(), 100.0 * p.rel_error);
}

int run(const Options& o) {
  const InterruptGuard interrupts;
  if (!o.view.empty() && o.setup.has_camera()) throw InputError("", "--view/--camera", "give a view or a camera, not both");
  ref::RenderSettings settings = o.settings;
  if (o.estimator == "mis") settings.estimator = ref::Estimator::Mis;
  else if (o.estimator == "light") settings.estimator = ref::Estimator::LightOnly;
  else if (o.estimator == "bsdf") settings.estimator = ref::Estimator::BsdfOnly;
  else throw InputError("", "--estimator", "'" + o.estimator + "' is not one of mis, light, bsdf");
  settings.sampler = ref::parse_sampler(o.sampler);
  if (o.seconds < 0.0 || !std::isfinite(o.seconds)) throw InputError("", "--time", "must be a positive number of seconds");
  if (o.rel_error < 0.0 || !std::isfinite(o.rel_error)) throw InputError("", "--rel-error", "must be a positive fraction, e.g. 0.01");
  if (!(o.checkpoint_interval > 0.0)) throw InputError("", "--checkpoint-interval", "must be a positive number of seconds");

  if (o.resume && o.overwrite) throw InputError("", "--resume/--overwrite", "give one of them, not both");
  {
    std::string ext = fs::path(o.out).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (ext != ".exr")
      throw InputError(o.out, "--out", "the reference is written as OpenEXR; expected a file name ending in .exr");
  }
  const sc::Scene scene = o.setup.load(o.scene, double(o.settings.width) / double(o.settings.height));
  const auto [first, last] = frame_range(o, scene);
  // Every output and checkpoint is checked before the first sample: a render of hours must not
  // fail at its end, overwrite its scene, or discard another render's saved progress.
  for (int f = first; f <= last; ++f) {
    const fs::path out = frame_path(o.out, f, first != last);
    check_output_file(out, {o.scene}, "--out");
    const fs::path checkpoint = out.string() + ".checkpoint";
    if (fs::exists(checkpoint) && !fs::is_regular_file(checkpoint))
      throw InputError(checkpoint.string(), "--out", "is where this render's checkpoint goes, but is not a file");
    if (fs::exists(checkpoint) && !o.resume && !o.overwrite)
      throw InputError(checkpoint.string(), "--out",
                       "a checkpoint for this render exists: add --resume to continue it, or --overwrite to start again");
    if (fs::exists(checkpoint) && o.overwrite) fs::remove(checkpoint);
  }
  for (int f = first; f <= last; ++f) {
    ReferenceFrame job = reference_frame(scene, o.scene, o.view, o.setup.camera, f, settings);
    ref::ReferenceMetadata& meta = job.metadata;
    const fs::path out = frame_path(o.out, f, first != last);
    if (out.has_parent_path()) fs::create_directories(out.parent_path());
    const ref::Renderer renderer(job.posed, meta.camera, settings);

    ref::ProgressiveOptions po;
    po.stop = {o.spp, o.seconds, o.rel_error};
    po.checkpoint = out.string() + ".checkpoint";
    po.checkpoint_interval_seconds = o.checkpoint_interval;
    po.resume = o.resume;
    po.identity = job.identity;
    po.cancel = &g_cancel;
    const std::string label = out.filename().string();
    ProgressLine line;
    if (line.active()) po.on_progress = [&](const ref::Progress& p) { draw_bar(line, p, label); };

    const ref::RenderOutcome r = ref::render_progressive(renderer, po);
    line.finish();
    if (!r.completed) {
      std::fprintf(stderr, "giq: interrupted after %.1f s; progress saved in %s; continue with --resume\n", r.elapsed_seconds,
                   po.checkpoint.string().c_str());
      return 130;
    }
    meta.render_seconds = o.record_time ? r.elapsed_seconds : -1.0;
    const image::Image img = ref::reference_image(r.film, settings, meta);
    image::write_exr(img, out, exr_options(img, o.half));
    fs::remove(po.checkpoint);
    const uint64_t nonfinite = r.film.nonfinite_samples();
    // A black image has no relative error to speak of: say so rather than 0%.
    const bool black = warn_if_black(img, out.string());
    // Unknown, not 0%, where there is no error estimate: a black image, or one sample a pixel.
    char rel[48] = "n/a (black image)";
    if (!black && r.spp < 2) std::snprintf(rel, sizeof rel, "n/a (one sample a pixel)");
    else if (!black) std::snprintf(rel, sizeof rel, "%.3g%%", 100.0 * r.film.relative_standard_error());
    std::printf("reference %s: %dx%d, view %s, frame %d, %u spp, %.2f s%s, rel.err %s, %llu non-finite samples\n",
                out.string().c_str(), settings.width, settings.height, meta.view.c_str(), f, r.spp, r.elapsed_seconds,
                r.resumed ? " (resumed)" : "", rel, (unsigned long long)nonfinite);
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace

void add_reference_command(CLI::App& app, int& exit_code) {
  static Options o;
  auto* cmd = app.add_subcommand("reference", "Render the path-traced reference EXR of a view");
  cmd->add_option("--scene", o.scene, "glTF 2.0 scene (.gltf or .glb)")->required();
  cmd->add_option("--view", o.view, "View name or index (default: the first view)");
  o.setup.add_options(*cmd);
  auto* frame = cmd->add_option("--frame", o.frame, "Frame of the sequence to render (default 0)");
  cmd->add_option("--frames", o.frames, "Frames A:B (inclusive); '#' in --out becomes the frame number")->excludes(frame);
  cmd->add_option("--spp", o.spp, "Stop at this many samples per pixel");
  cmd->add_option("--time", o.seconds, "Stop after this many seconds of rendering");
  cmd->add_option("--rel-error", o.rel_error, "Stop when the mean relative standard error of the beauty is below this");
  cmd->add_option("--width", o.settings.width, "Image width in pixels")->capture_default_str();
  cmd->add_option("--height", o.settings.height, "Image height in pixels")->capture_default_str();
  cmd->add_option("--seed", o.settings.seed, "Random seed")
      ->check(integer_in(0.0L, 18446744073709551615.0L))
      ->capture_default_str();
  cmd->add_option("--threads", o.settings.threads, "Worker threads (0 = all cores; never changes the image)")->capture_default_str();
  cmd->add_option("--max-bounces", o.settings.max_bounces, "Scattering events per path")->capture_default_str();
  cmd->add_option("--estimator", o.estimator, "mis, light (light sampling only) or bsdf (BSDF sampling only)")->capture_default_str();
  cmd->add_option("--sampler", o.sampler,
                  "sobol (scrambled Sobol nets in independent blocks; variance from the blocks) or independent")
      ->capture_default_str();
  cmd->add_option("--sobol-block", o.settings.sobol_block, "Samples per Sobol block, a power of two from 2 to 256")
      ->capture_default_str();
  cmd->add_option("--out", o.out, "Output EXR path")->required();
  cmd->add_option("--checkpoint-interval", o.checkpoint_interval, "Seconds between checkpoints (OUT.checkpoint)")->capture_default_str();
  cmd->add_flag("--resume", o.resume, "Continue from OUT.checkpoint when it exists");
  cmd->add_flag("--overwrite", o.overwrite, "Discard an existing OUT.checkpoint and start again");
  cmd->add_flag("--half", o.half, "Store the colour layers as float16 (variance, depth, ids stay float32)");
  cmd->add_flag("--record-time", o.record_time, "Write the render time into the header (the file then differs run to run)");
  cmd->footer("Example: the Cornell box to a mean relative error of 1%, resumable:\n  giq reference --scene scenes/cornell.gltf --rel-error 0.01 --out out/cornell.exr --resume");
  cmd->callback([&exit_code] { exit_code = run(o); });
}

}  // namespace giq::cli
