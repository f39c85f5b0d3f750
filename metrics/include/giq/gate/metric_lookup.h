#pragma once
// Finding a gate metric in a metrics.json written by `giq score` (docs/metrics.md) and the
// technique's frame time in timings.json written by `giq realtime`.
//
// metrics.json keeps single-image metrics under "metrics", and for a sequence the temporal
// ones under "sequence" and the last frame's image metrics under "last_frame.metrics". Every
// value is an object {"value": v, ...} that may carry "unresolved": true when the reference's
// noise hides it. A gate metric name is either a short name (flip_mean, leak, leak_pixels,
// lag90_frames, or any key such as relmse, ssim, flicker, bias2) or a dotted path inside one
// of those sections ("flip.weighted_median", "leak.automatic.leak"), or a dotted path from
// the top of the file.

#include <nlohmann/json.hpp>
#include <filesystem>
#include <optional>
#include <string>

namespace giq::gate {

struct MetricValue {
  std::optional<double> value;  // empty: null in the file (undefined, e.g. no step for lag)
  bool unresolved = false;
  std::string path;  // where it was found, e.g. "last_frame.metrics.flip.mean"
  std::string note;  // the file's own note or reason, when it gives one
};

// Empty when the file does not hold the metric.
std::optional<MetricValue> find_metric(const nlohmann::json& metrics, const std::string& name);

// Why `name` cannot name a metric in a bound ("" when it can): a short name must be the
// catalogue's (a typo would otherwise fail every run as a missing metric, or be ignored); a
// dotted path into metrics.json is taken as written. The message lists the short names and
// suggests the nearest.
std::string unknown_metric(const std::string& name);

// timings.json (`giq realtime`'s, docs/realtime.md; or an engine's own with frame_ms):
// frame_gpu_ms.median (else frame_ms.median) and device.name. The one reader of that file.
struct FrameTime {
  std::optional<double> gpu_ms;
  std::string key;  // where gpu_ms was found, e.g. "frame_gpu_ms.median"
  std::string device;
};
FrameTime frame_time(const nlohmann::json& timings);
// Reads the file; throws InputError (file, field, what was expected) when it cannot be read,
// is not JSON, or holds no positive, finite frame time.
FrameTime read_timings(const std::filesystem::path& file);

}  // namespace giq::gate
