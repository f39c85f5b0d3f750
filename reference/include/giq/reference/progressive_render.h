#pragma once
// A render driven to a stopping criterion in passes, with periodic checkpoints and resume.
//
// A pass adds whole samples to every pixel (pixel p gets samples n..m-1 in order), so how the
// render is cut into passes, interrupted or resumed never changes the result: with the same
// total spp, a resumed render's film has the bits of an uninterrupted one.

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include "giq/reference/film.h"
#include "giq/reference/renderer.h"

namespace giq::reference {

// The render stops when any criterion that is set (non-zero) is met.
struct StopCriteria {
  uint32_t spp = 0;         // samples per pixel
  double seconds = 0.0;     // render time, counting the time before a resume
  double rel_error = 0.0;   // Film::relative_standard_error() at or below this
};

struct Progress {
  uint32_t spp = 0;
  uint32_t target_spp = 0;  // 0 when the stop is not a sample count
  double elapsed_seconds = 0.0;
  double eta_seconds = -1.0;  // -1 when unknown
  double rel_error = 0.0;
};

struct ProgressiveOptions {
  StopCriteria stop;
  std::filesystem::path checkpoint;     // empty: no checkpoints
  double checkpoint_interval_seconds = 60.0;
  bool resume = false;                  // continue from `checkpoint` when it exists
  std::string identity;                 // what a checkpoint must match to be resumed
  std::function<void(const Progress&)> on_progress;  // after every pass
  const std::atomic<bool>* cancel = nullptr;         // set from a signal handler, for example
};

struct RenderOutcome {
  Film film;
  bool completed = false;  // false: cancelled (a checkpoint holds the work, when enabled)
  bool resumed = false;
  double elapsed_seconds = 0.0;
  uint32_t spp = 0;
};

// Throws InputError when no criterion is set or a checkpoint cannot be resumed.
RenderOutcome render_progressive(const Renderer& renderer, const ProgressiveOptions& options);

}  // namespace giq::reference
