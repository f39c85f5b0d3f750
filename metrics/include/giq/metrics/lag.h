#pragma once
// Response to a change (docs/metrics.md, "Lag"). A sequence has a step at frame t0 (a light
// switched or moved, an object moved). The changed region is where the reference changed by
// more than 3 sigma between t0 - 1 and the last frame; r_t is the mean |e_t| = |Y_T,t - Y_R,t|
// over that region; r_inf the mean r_t over the last 25% of the frames (at least one) and s
// their sample standard deviation (0 for one frame);
//   lag90 = first t >= t0 with r_t <= r_inf + max(0.1 (r_t0 - r_inf), 2 s), minus t0
// in frames, and in milliseconds at the technique's measured frame time.

#include <cstdint>
#include <optional>
#include <vector>

#include "giq/metrics/layer.h"

namespace giq::metrics {

// 1 where |Y_after - Y_before| > 3 sqrt(sigma^2_Y,before + sigma^2_Y,after) (variances may be
// nullptr: sigma = 0, so any change counts). Non-finite pixels are never in the region.
std::vector<uint8_t> changed_region(const RgbLayer& before, const RgbLayer* variance_before, const RgbLayer& after,
                                    const RgbLayer* variance_after, double sigma_factor = 3.0);

// Mean over the region of |Y_T - Y_R| (valid pixels only); NaN when none.
double region_abs_error(const RgbLayer& reference, const RgbLayer& test, const std::vector<uint8_t>& region);

// Mean |Y_R,t - Y_R,t-1| over valid pixels: how much the reference changed at a frame. The
// step frame t0 is where this is largest when the sequence does not name it.
double mean_luminance_change(const RgbLayer& previous, const RgbLayer& current);

struct LagResult {
  int t0 = 0;                      // index into r (0 = first frame of the sequence)
  double r_t0 = 0.0, r_inf = 0.0, r_inf_stddev = 0.0, threshold = 0.0;
  std::optional<int> lag_frames;   // empty when r never reaches the threshold
  std::optional<double> lag_ms;    // with a frame time
};

// r: r_t for each frame of the sequence; t0 in [0, r.size()).
LagResult lag90(const std::vector<double>& r, int t0, std::optional<double> frame_ms = std::nullopt);

}  // namespace giq::metrics
