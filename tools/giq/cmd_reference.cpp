// `giq reference`: renders the path-traced ground truth of a scene's view as a multi-layer
// reference EXR, with checkpoints and resume. See docs/reference.md.

#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <memory>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "command.h"
#include "progress.h"
#include "reference_frame.h"
#include "reference_output.h"
#include "scene_setup.h"
#include "integer_check.h"
#include "output_guard.h"
#include "giq/base/error.h"
#include "giq/base/frames.h"
#include "giq/image/io.h"
#include "giq/reference/distributed_render.h"
#include "giq/reference/part.h"
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
  std::string shard;  // "K/N": render only this share of the work units into a part file
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

// --shard K/N: this process's share of the work units (part.h), every pixel of it to --spp,
// into a part file for `giq reference merge`. No checkpoints: a shard is redone whole.
// Checked before the scene is loaded, so a mistyped share costs nothing.
ref::Shard shard_of(const Options& o) {
  const ref::Shard shard = ref::parse_shard(o.shard);
  if (o.spp == 0 || o.seconds > 0.0 || o.rel_error > 0.0)
    throw InputError("", "--shard",
                     "shards stop at a sample count: give --spp alone (a time or an error target would stop each shard "
                     "at a different point, and the parts would not add up to one render)");
  if (o.resume || o.record_time || o.half)
    throw InputError("", "--shard", "--resume, --record-time and --half do not apply to a shard (a shard is rendered again "
                                    "whole; give --half to giq reference merge)");
  check_output_file(o.out, {o.scene}, "--out");
  return shard;
}

// What the parts of one render, or a checkpoint across ranks, must share: everything in the
// header that changes the image.
std::string render_identity(const ref::Part& p) {
  return "scene " + p.scene_hash + " view " + p.view + " camera '" + p.camera_given + "' frames " +
         std::to_string(p.first_frame) + ":" + std::to_string(p.last_frame) + " spp " + std::to_string(p.spp) +
         " settings " + ref::settings_json(p.settings);
}

// What a render across ranks needs, checked on every rank before the scene is loaded (each
// rank reaches the same verdict, so all of them stop with the same message).
void ranks_check(const Options& o, bool shard) {
  if (shard) throw InputError("", "--shard", "a render across MPI ranks shares its work itself; give --shard without mpirun");
  if (o.spp == 0 || o.seconds > 0.0 || o.rel_error > 0.0)
    throw InputError("", "--spp",
                     "a render across MPI ranks stops at a sample count: give --spp alone (each rank renders whole units "
                     "to it)");
  if (o.record_time) throw InputError("", "--record-time", "does not apply to a render across MPI ranks");
}

int run_shard(const Options& o, ref::Shard shard, const sc::Scene& scene, const ref::RenderSettings& settings, int first,
              int last) {
  ref::Part part;
  part.scene = o.scene;
  part.scene_hash = scene.content_hash;
  part.settings = settings;
  part.spp = o.spp;
  part.first_frame = first, part.last_frame = last;
  part.shard = shard;
  const ref::WorkUnits units{first, last, settings.width, settings.height};
  uint64_t owned = 0;
  for (int f = first; f <= last; ++f) {
    const ReferenceFrame job = reference_frame(scene, o.scene, o.view, o.setup.camera, f, settings);
    part.view = job.metadata.view, part.camera_given = job.metadata.camera_given;
    bool any = false;
    for (int t = 0; t < units.tiles_per_frame(); ++t) any |= ref::WorkUnits::owned(units.unit(f, t), shard);
    if (!any) continue;
    const ref::Renderer renderer(job.posed, job.metadata.camera, settings);
    const auto mine = [&](int x, int y) {
      return ref::WorkUnits::owned(units.unit(f, (y / ref::kUnitSize) * units.tiles_x() + x / ref::kUnitSize), shard);
    };
    ref::Film film = renderer.make_film();
    renderer.render_aux(film, mine);  // the share's pixels only, like the samples
    if (!renderer.render(film, o.spp, &g_cancel, nullptr, mine)) {
      std::fprintf(stderr, "giq: interrupted; nothing written; run shard %s again\n", o.shard.c_str());
      return 130;
    }
    part.frames.push_back(ref::part_frame(film, f, job.metadata.camera, units, shard));
    owned += part.frames.back().tiles.size();
  }
  part.identity = render_identity(part);
  if (fs::path(o.out).has_parent_path()) fs::create_directories(fs::path(o.out).parent_path());
  ref::write_part(o.out, part);
  std::printf("reference shard %u/%u: %llu of %llu units of %dx%d pixels (frames %d to %d, %u spp) -> %s\n", shard.index,
              shard.count, (unsigned long long)owned, (unsigned long long)(uint64_t(units.tiles_per_frame()) * uint64_t(last - first + 1)),
              ref::kUnitSize, ref::kUnitSize, first, last, o.spp, o.out.c_str());
  return 0;
}

// Each rank's renderer of the frame its units are in (distributed_render.h).
class PosedFrames final : public ref::FrameRenderers {
 public:
  PosedFrames(const Options& o, const sc::Scene& scene, const ref::RenderSettings& settings)
      : o_(o), scene_(scene), settings_(settings) {}
  const ref::Renderer& renderer(int frame) override {
    if (frame != frame_) {
      renderer_.reset();
      job_ = std::make_unique<ReferenceFrame>(reference_frame(scene_, o_.scene, o_.view, o_.setup.camera, frame, settings_));
      renderer_ = std::make_unique<ref::Renderer>(job_->posed, job_->metadata.camera, settings_);
      frame_ = frame;
    }
    return *renderer_;
  }

 private:
  const Options& o_;
  const sc::Scene& scene_;
  const ref::RenderSettings& settings_;
  int frame_ = -1;
  std::unique_ptr<ReferenceFrame> job_;
  std::unique_ptr<ref::Renderer> renderer_;
};

// `mpirun -n R giq reference ... --spp N`: the render across R ranks, written by rank 0 as
// the files one process would have written (distributed_render.h). An error any rank meets
// ends every rank, with exit code 2 for bad input.
int run_across_ranks(const Options& o, const ref::Ranks& ranks, const sc::Scene& scene, ref::RenderSettings settings,
                     int first, int last) try {
  // One rank per core by default: the machine's threads shared among its ranks.
  if (settings.threads == 0)
    settings.threads = std::max(1, int(std::thread::hardware_concurrency()) / std::max(1, ranks.local_size()));
  const bool many = first != last;
  ref::DistributedJob job;
  ref::Part& h = job.header;
  h.scene = o.scene, h.scene_hash = scene.content_hash, h.settings = settings, h.spp = o.spp;
  h.first_frame = first, h.last_frame = last;
  const ReferenceFrame first_job = reference_frame(scene, o.scene, o.view, o.setup.camera, first, settings);
  h.view = first_job.metadata.view, h.camera_given = first_job.metadata.camera_given;
  h.identity = render_identity(h);
  job.checkpoint = o.out + ".ranks.checkpoint";
  job.checkpoint_interval_seconds = o.checkpoint_interval;
  job.resume = o.resume;
  job.cancel = &g_cancel;
  if (ranks.rank() == 0) {
    for (int f = first; f <= last; ++f) check_output_file(frame_path(o.out, f, many), {o.scene}, "--out");
    if (fs::exists(job.checkpoint) && !o.resume && !o.overwrite)
      throw InputError(job.checkpoint.string(), "--out",
                       "a checkpoint for this render exists: add --resume to continue it, or --overwrite to start again");
    if (fs::exists(job.checkpoint) && o.overwrite) fs::remove(job.checkpoint);
    if (fs::path(o.out).has_parent_path()) fs::create_directories(fs::path(o.out).parent_path());
  }
  PosedFrames renderers(o, scene, settings);
  const auto done = [&](int f, const ref::Film& film) {
    ReferenceFrame frame = reference_frame(scene, o.scene, o.view, o.setup.camera, f, settings);
    frame.metadata.render_seconds = -1.0;
    const fs::path out = frame_path(o.out, f, many);
    if (out.has_parent_path()) fs::create_directories(out.parent_path());
    const image::Image img = ref::reference_image(film, settings, frame.metadata);
    image::write_exr(img, out, exr_options(img, o.half));
    warn_if_black(img, out.string());
    std::printf("reference %s: %dx%d, view %s, frame %d, %u spp, %d ranks, rel.err %.3g%%, %llu non-finite samples\n",
                out.string().c_str(), settings.width, settings.height, frame.metadata.view.c_str(), f, o.spp, ranks.size(),
                100.0 * film.relative_standard_error(), (unsigned long long)film.nonfinite_samples());
    std::fflush(stdout);
  };
  const ref::DistributedOutcome r = ref::render_across_ranks(ranks, job, renderers, done);
  if (!r.completed) {
    if (ranks.rank() == 0)
      std::fprintf(stderr, "giq: interrupted; progress saved in %s; continue with --resume\n", job.checkpoint.string().c_str());
    return 130;
  }
  return 0;
} catch (const InputError& e) {
  const std::string who = ranks.rank() == 0 ? "" : " (rank " + std::to_string(ranks.rank()) + ")";
  std::fprintf(stderr, "giq: error%s: %s\n", who.c_str(), e.what());
  ranks.abort(2);
} catch (const std::exception& e) {
  std::fprintf(stderr, "giq: internal error (rank %d): %s\n", ranks.rank(), e.what());
  ranks.abort(3);
}

int run(const Options& o) {
  const InterruptGuard interrupts;
  if (o.scene.empty()) throw InputError("", "--scene", "a scene is required (a .gltf/.glb path)");
  if (o.out.empty()) throw InputError("", "--out", "an output file is required");
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
  const std::optional<ref::Shard> shard = o.shard.empty() ? std::nullopt : std::optional(shard_of(o));
  const ref::Ranks& ranks = ref::Ranks::world();
  if (ranks.size() > 1) ranks_check(o, shard.has_value());
  if (!shard) {
    std::string ext = fs::path(o.out).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (ext != ".exr")
      throw InputError(o.out, "--out", "the reference is written as OpenEXR; expected a file name ending in .exr");
  }
  const sc::Scene scene = o.setup.load(o.scene, double(o.settings.width) / double(o.settings.height));
  const auto [first, last] = frame_range(o, scene);
  if (shard) return run_shard(o, *shard, scene, settings, first, last);
  if (ranks.size() > 1) return run_across_ranks(o, ranks, scene, settings, first, last);
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
  cmd->add_option("--scene", o.scene, "glTF 2.0 scene (.gltf or .glb)");
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
  cmd->add_option("--out", o.out, "Output EXR path (with --shard: the part file)");
  cmd->add_option("--shard", o.shard,
                  "K/N: render only share K of N of the work units (frames x 64x64 tiles) into the part file --out; "
                  "giq reference merge joins the N parts (docs/reference.md, 'Shards')");
  cmd->add_option("--checkpoint-interval", o.checkpoint_interval, "Seconds between checkpoints (OUT.checkpoint)")->capture_default_str();
  cmd->add_flag("--resume", o.resume, "Continue from OUT.checkpoint when it exists");
  cmd->add_flag("--overwrite", o.overwrite, "Discard an existing OUT.checkpoint and start again");
  cmd->add_flag("--half", o.half, "Store the colour layers as float16 (variance, depth, ids stay float32)");
  cmd->add_flag("--record-time", o.record_time, "Write the render time into the header (the file then differs run to run)");
  cmd->footer("Example: the Cornell box to a mean relative error of 1%, resumable:\n  giq reference --scene scenes/cornell.gltf --rel-error 0.01 --out out/cornell.exr --resume");
  CLI::App* merge = add_reference_merge_command(*cmd, exit_code);
  cmd->callback([merge, &exit_code] {
    if (merge->parsed()) return;
    const ref::Ranks& ranks = ref::Ranks::world();
    if (ranks.size() == 1) {
      exit_code = run(o);
      return;
    }
    try {
      exit_code = run(o);
    } catch (const InputError& e) {
      // Every rank read the same options and scene and met the same error: one message.
      if (ranks.rank() == 0) std::fprintf(stderr, "giq: error: %s\n", e.what());
      exit_code = 2;
    }
  });
}

}  // namespace giq::cli
