#include "giq/reference/progressive_render.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "giq/base/error.h"
#include "giq/reference/checkpoint.h"

namespace giq::reference {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Target duration of one pass: short enough for a live progress bar and for checkpoints at
// the requested interval, long enough that the per-pass overhead stays negligible.
constexpr double kPassSeconds = 1.0;
// Below this many samples (or two blocks of the Sobol sampler) the variance estimate is too
// noisy to stop on.
constexpr uint32_t kMinSppForErrorStop = 8;
constexpr uint32_t kMaxSpp = 1u << 24;  // float-exact sample counts in the spp layer

}  // namespace

RenderOutcome render_progressive(const Renderer& renderer, const ProgressiveOptions& o) {
  const StopCriteria& stop = o.stop;
  if (stop.spp == 0 && !(stop.seconds > 0.0) && !(stop.rel_error > 0.0))
    throw InputError("", "--spp/--time/--rel-error", "no stopping criterion: give a sample count, a time or a relative error");
  if (stop.spp > kMaxSpp) throw InputError("", "--spp", "spp " + std::to_string(stop.spp) + " exceeds the maximum 16777216");

  RenderOutcome out;
  double before = 0.0;  // seconds spent before a resume
  if (o.resume && !o.checkpoint.empty()) {
    if (auto c = read_checkpoint(o.checkpoint, o.identity)) {
      const RenderSettings& s = renderer.settings();
      if (c->film.width != s.width || c->film.height != s.height)
        throw InputError(o.checkpoint.string(), "checkpoint", "size differs from the render's");
      out.film = std::move(c->film);
      before = c->elapsed_seconds;
      out.resumed = true;
    }
  }
  const Clock::time_point start = Clock::now();
  const auto elapsed = [&] { return before + since(start); };
  if (!out.resumed) {
    out.film = renderer.make_film();
    renderer.render_aux(out.film);
  }

  // A checkpoint cancelled mid-pass leaves pixels with different counts: complete them first.
  uint32_t spp = out.film.min_samples();
  uint32_t max_spp = 0;
  for (const PixelAccumulator& p : out.film.pixels) max_spp = std::max(max_spp, p.samples);
  const uint32_t cap = stop.spp > 0 ? stop.spp : kMaxSpp;
  const uint32_t block = renderer.settings().block();
  const uint32_t min_spp_for_error_stop = std::max(kMinSppForErrorStop, 2 * block);
  double seconds_per_spp = 0.0;  // measured on the last pass
  Clock::time_point last_checkpoint = Clock::now();
  const double pass_seconds = std::min(kPassSeconds, std::max(0.05, o.checkpoint_interval_seconds));

  const auto done = [&](uint32_t n) {
    if (n >= cap) return true;
    if (stop.seconds > 0.0 && elapsed() >= stop.seconds) return true;
    if (stop.rel_error > 0.0 && n >= min_spp_for_error_stop && out.film.relative_standard_error() <= stop.rel_error) return true;
    return false;
  };

  bool cancelled = false;
  while (max_spp > spp || !done(spp)) {
    uint32_t step = 1;
    if (max_spp > spp) {
      step = max_spp - spp;
    } else if (seconds_per_spp > 0.0) {
      double budget = pass_seconds;
      if (stop.seconds > 0.0) budget = std::min(budget, stop.seconds - elapsed());
      step = uint32_t(std::clamp(std::floor(budget / seconds_per_spp), 1.0, double(cap - spp)));
    }
    // Passes that stop on time or error end on whole blocks, so that every block counted in
    // the variance is complete and the mean has no partial block.
    if (block > 0 && max_spp <= spp && spp + step >= block) step = std::min(cap, (spp + step + block - 1) / block * block) - spp;
    const Clock::time_point t0 = Clock::now();
    const bool finished = renderer.render(out.film, spp + step, o.cancel);
    if (!finished) {
      cancelled = true;
      break;
    }
    seconds_per_spp = since(t0) / double(step);
    spp += step;
    max_spp = std::max(max_spp, spp);
    if (o.on_progress) {
      Progress p;
      p.spp = spp;
      p.target_spp = stop.spp;
      p.elapsed_seconds = elapsed();
      p.rel_error = out.film.relative_standard_error();
      if (stop.spp > 0) p.eta_seconds = seconds_per_spp * double(stop.spp - spp);
      if (stop.seconds > 0.0) {
        const double left = std::max(0.0, stop.seconds - p.elapsed_seconds);
        p.eta_seconds = p.eta_seconds < 0.0 ? left : std::min(p.eta_seconds, left);
      }
      o.on_progress(p);
    }
    if (!o.checkpoint.empty() && since(last_checkpoint) >= o.checkpoint_interval_seconds && !done(spp)) {
      write_checkpoint(o.checkpoint, out.film, o.identity, elapsed());
      last_checkpoint = Clock::now();
    }
  }
  out.elapsed_seconds = elapsed();
  out.spp = out.film.min_samples();
  out.completed = !cancelled;
  if (cancelled && !o.checkpoint.empty()) write_checkpoint(o.checkpoint, out.film, o.identity, out.elapsed_seconds);
  return out;
}

}  // namespace giq::reference
