#pragma once
// The metric catalogue: every metric giq reports, by the short name users, bounds and sweeps
// use, with where metrics.json holds it, its unit, which direction is better, whether it is a
// headline metric, and the section of docs/metrics.md that defines it. The one owner of those
// facts: `giq score`'s table, the report, `giq sweep`'s columns and the gate's bounds
// (default direction, where to find a value) all read them here. Header-only, so that the
// gate, which reads metrics.json as JSON and does not link the metrics, shares it.

#include <array>
#include <stdexcept>
#include <string>
#include <string_view>

namespace giq::metrics {

enum class Better { Lower, Higher };

// Where a metric lives in metrics.json: a per-image metric under "metrics" (one image) or
// "last_frame.metrics" (a sequence), a sequence metric under "sequence", a timing in
// timings.json.
enum class Scope { Image, Sequence, Timing };

struct MetricInfo {
  std::string_view name;   // short name: gate bounds, --error, sweep columns
  std::string_view label;  // the tables' row label
  // Dotted paths inside the scope's object, in order of preference (leak: the regions the
  // scene declares, else the automatic dark region); the tables show each one present.
  std::array<std::string_view, 2> paths;
  std::array<std::string_view, 2> path_labels;  // a row label per path when there are two
  std::string_view unit;
  Better better;
  bool headline;            // shown in summaries, sweeps and the results pages
  std::string_view anchor;  // docs/metrics.md section
  Scope scope;
};

// In the order the tables list them.
inline constexpr std::array<MetricInfo, 27> kMetricCatalogue = {{
    {"mse", "mse", {"mse"}, {}, "radiance^2", Better::Lower, false, "per-image-error", Scope::Image},
    {"rmse", "rmse", {"rmse"}, {}, "radiance", Better::Lower, false, "per-image-error", Scope::Image},
    {"mae", "mae", {"mae"}, {}, "radiance", Better::Lower, false, "per-image-error", Scope::Image},
    {"relmse", "relmse", {"relmse"}, {}, "1", Better::Lower, true, "per-image-error", Scope::Image},
    {"relmse_trimmed", "relmse (trimmed)", {"relmse_trimmed"}, {}, "1", Better::Lower, false, "per-image-error", Scope::Image},
    {"smape", "smape", {"smape"}, {}, "1", Better::Lower, true, "per-image-error", Scope::Image},
    {"psnr", "psnr", {"psnr"}, {}, "dB", Better::Higher, true, "per-image-error", Scope::Image},
    {"noise_floor", "noise_floor", {"noise_floor"}, {}, "radiance^2", Better::Lower, false,
     "noise-floor-and-unresolved-values", Scope::Image},
    {"mse_debiased", "mse_debiased", {"mse_debiased"}, {}, "radiance^2", Better::Lower, false,
     "noise-floor-and-unresolved-values", Scope::Image},
    {"ssim", "ssim", {"ssim"}, {}, "1", Better::Higher, true, "ssim", Scope::Image},
    {"flip_mean", "flip mean", {"flip.mean"}, {}, "1", Better::Lower, true, "flip", Scope::Image},
    {"flip_median", "flip weighted median", {"flip.weighted_median"}, {}, "1", Better::Lower, false, "flip",
     Scope::Image},
    {"flip_max", "flip max", {"flip.max"}, {}, "1", Better::Lower, false, "flip", Scope::Image},
    {"leak", "leak", {"leak.declared.leak", "leak.automatic.leak"}, {"leak (declared)", "leak (automatic)"},
     "share of sum_image Y_R", Better::Lower, true, "leaking", Scope::Image},
    {"leak_pixels", "leak_pixels", {"leak.declared.leak_pixels", "leak.automatic.leak_pixels"},
     {"leak_pixels (declared)", "leak_pixels (automatic)"}, "share of region pixels", Better::Lower, false, "leaking", Scope::Image},
    {"ztest_p", "z-test p (Sidak)", {"ztest.p_sidak"}, {}, "1", Better::Higher, false, "per-pixel-z-test", Scope::Image},
    {"nonfinite_pixels", "nonfinite_pixels", {"nonfinite_pixels"}, {}, "pixels", Better::Lower, false,
     "valid-pixels-and-non-finite-input", Scope::Image},
    {"mse_seq", "mse_seq", {"mse_seq"}, {}, "radiance^2", Better::Lower, false,
     "sequences-bias-variance-flicker", Scope::Sequence},
    {"bias2", "bias2", {"bias2"}, {}, "radiance^2", Better::Lower, false, "sequences-bias-variance-flicker",
     Scope::Sequence},
    {"variance", "variance", {"variance"}, {}, "radiance^2", Better::Lower, false,
     "sequences-bias-variance-flicker", Scope::Sequence},
    {"bias2_corrected", "bias2_corrected", {"bias2_corrected"}, {}, "radiance^2", Better::Lower, false,
     "sequences-bias-variance-flicker", Scope::Sequence},
    {"variance_corrected", "variance_corrected", {"variance_corrected"}, {}, "radiance^2", Better::Lower,
     false, "sequences-bias-variance-flicker", Scope::Sequence},
    {"flicker", "flicker", {"flicker"}, {}, "1", Better::Lower, true, "sequences-bias-variance-flicker",
     Scope::Sequence},
    {"temporal_flip", "temporal_flip", {"temporal_flip"}, {}, "1", Better::Lower, false,
     "sequences-bias-variance-flicker", Scope::Sequence},
    {"lag90_frames", "lag90_frames", {"lag90_frames"}, {}, "frames", Better::Lower, true, "lag", Scope::Sequence},
    {"lag90_ms", "lag90_ms", {"lag90_ms"}, {}, "ms", Better::Lower, false, "lag", Scope::Sequence},
    {"gpu_ms", "GPU ms", {"frame_gpu_ms.median"}, {}, "ms", Better::Lower, true, "speed", Scope::Timing},
}};

// The entry of a short name, or nullptr.
constexpr const MetricInfo* find_metric_info(std::string_view name) {
  for (const MetricInfo& m : kMetricCatalogue)
    if (m.name == name) return &m;
  return nullptr;
}

// The unit metrics.json writes for a catalogue metric (throws std::logic_error for a name the
// catalogue lacks: a programming error).
inline std::string_view unit_of(std::string_view name) {
  const MetricInfo* m = find_metric_info(name);
  if (!m) throw std::logic_error("metric '" + std::string(name) + "' is not in the catalogue");
  return m->unit;
}

// Better direction of a short name or a dotted metrics.json path (its last component names the
// metric: "leak.declared.leak" is a leak); lower for anything the catalogue does not know.
constexpr Better better_direction(std::string_view metric) {
  if (const MetricInfo* m = find_metric_info(metric)) return m->better;
  const size_t dot = metric.find_last_of('.');
  if (dot != std::string_view::npos)
    if (const MetricInfo* m = find_metric_info(metric.substr(dot + 1))) return m->better;
  return Better::Lower;
}

}  // namespace giq::metrics
