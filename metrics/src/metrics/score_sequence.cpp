// score() for sequences: frames are read (or prepared, when in memory) one at a time (two
// passes when lag needs the changed region first), so memory stays at two reference and two
// technique frames plus the per-pixel accumulators of SequenceAccumulator.

#include <limits>
#include <optional>

#include "giq/base/error.h"
#include "giq/image/io.h"
#include "giq/metrics/catalogue.h"
#include "giq/metrics/error.h"
#include "giq/metrics/flip.h"
#include "giq/metrics/lag.h"
#include "giq/metrics/maps.h"
#include "giq/metrics/sequence.h"
#include "score_image.h"
#include "score_json.h"

namespace giq::metrics::detail {
namespace {

using nlohmann::json;

std::optional<RgbLayer> variance_of(const image::Image& ref, const std::string& layer, const std::string& file) {
  const std::string vl = variance_layer_for(ref, layer);
  if (vl.empty()) return std::nullopt;
  return rgb_layer(ref, vl, file);
}

}  // namespace

json score_sequence(const Frames& in, const ScoreRequest& req, std::vector<Map>* kept) {
  const int first = in.first, last = in.last, frames = last - first + 1;
  const bool per_frame_ref = in.per_frame_reference;
  const std::string layer_name = req.layer.empty() ? "beauty" : req.layer;
  const json io = {"reference:" + layer_name, "test:" + layer_name};
  const auto& ref_file = in.reference_name;
  const auto& test_file = in.test_name;
  const bool hdr = in.hdr;

  std::optional<image::Image> static_ref;
  if (!per_frame_ref) static_ref = in.reference(first);

  // --- pass 1 (references only): the step frame and the changed region, for lag90
  json lag = {{"value_frames", nullptr}, {"definition", "lag90"}};
  std::vector<uint8_t> region;
  int t0 = -1;
  if (!per_frame_ref) {
    lag["reason"] = "one reference for every frame: the reference has no step change";
  } else if (frames < 2) {
    lag["reason"] = "a single frame has no step change";
  } else {
    if (req.step_frame) {
      if (*req.step_frame <= first || *req.step_frame > last)
        throw InputError("", "--step-frame",
                         std::to_string(*req.step_frame) + " must lie in " + std::to_string(first + 1) + ".." +
                             std::to_string(last) + " (a frame with a previous frame)");
      t0 = *req.step_frame - first;
      lag["step_frame_source"] = req.step_frame_source;
    } else {
      // The step is where the reference changes most between consecutive frames.
      double best = -1.0;
      std::optional<image::Image> prev;
      for (int f = first; f <= last; ++f) {
        image::Image cur = in.reference(f);
        const RgbLayer c = rgb_layer(cur, req.layer, ref_file(f));
        if (prev) {
          if (cur.width() != prev->width() || cur.height() != prev->height())
            throw InputError(ref_file(f), "size", "differs from the first reference frame's");
          const double d = mean_luminance_change(rgb_layer(*prev, req.layer, ref_file(f - 1)), c);
          if (d > best) best = d, t0 = f - first;
        }
        prev = std::move(cur);
      }
      lag["step_frame_source"] = "detected: largest mean |Y_R,t - Y_R,t-1|";
    }
    const image::Image before = in.reference(first + t0 - 1);
    const image::Image after = in.reference(last);
    const auto vb = variance_of(before, req.layer, ref_file(first + t0 - 1));
    const auto va = variance_of(after, req.layer, ref_file(last));
    region = changed_region(rgb_layer(before, req.layer, ref_file(first + t0 - 1)), vb ? &*vb : nullptr,
                            rgb_layer(after, req.layer, ref_file(last)), va ? &*va : nullptr);
  }
  size_t region_pixels = 0;
  for (uint8_t b : region) region_pixels += b;
  if (!region.empty() && region_pixels == 0) {
    lag["reason"] = "the reference does not change by more than 3 sigma anywhere between the step and the end";
    region.clear();
  }

  // --- pass 2: every frame
  std::optional<SequenceAccumulator> acc;
  std::optional<image::Image> prev_ref, prev_test;
  double flip_test = 0.0, flip_ref = 0.0;
  int flip_pairs = 0;
  std::vector<double> r_t;
  json per_frame = json::array(), last_frame;
  int width = 0, height = 0;
  for (int f = first; f <= last; ++f) {
    image::Image test = in.test(f);
    std::optional<image::Image> ref_frame;
    if (per_frame_ref) ref_frame = in.reference(f);
    const image::Image& ref = per_frame_ref ? *ref_frame : *static_ref;
    const std::string rf = per_frame_ref ? ref_file(f) : in.reference_label;
    check_pair(ref, rf, test, test_file(f), req.layer);
    if (!acc) {
      width = ref.width(), height = ref.height();
      acc.emplace(width, height, per_frame_ref);
    } else if (ref.width() != width || ref.height() != height) {
      throw InputError(rf, "size",
                       std::to_string(ref.width()) + "x" + std::to_string(ref.height()) + ", expected " +
                           std::to_string(width) + "x" + std::to_string(height) + " as in frame " +
                           std::to_string(first));
    }
    const RgbLayer r = rgb_layer(ref, req.layer, rf), t = rgb_layer(test, req.layer, test_file(f));
    const auto var = variance_of(ref, req.layer, rf);
    acc->add(r, t, var ? &*var : nullptr);
    const ErrorStats e = error_stats(r, t, var ? &*var : nullptr);
    per_frame.push_back({{"frame", f},
                         {"mse", number(e.mse)},
                         {"mae", number(e.mae)},
                         {"relmse", number(e.relmse)},
                         {"relmse_trimmed", number(e.relmse_trimmed)},
                         {"nonfinite_pixels", e.nonfinite_pixels}});
    if (!region.empty()) r_t.push_back(region_abs_error(r, t, region));
    if (prev_test && !req.sequence_only) {
      flip_test += flip_valid(*prev_test, test, req.layer, hdr).mean;
      if (per_frame_ref) flip_ref += flip_valid(*prev_ref, ref, req.layer, hdr).mean;
      ++flip_pairs;
    }
    if (f == last && !req.sequence_only) last_frame = score_image(ref, rf, test, test_file(f), hdr, req, kept);
    prev_test = std::move(test);
    if (per_frame_ref) prev_ref = std::move(ref_frame);
  }

  // --- sequence metrics
  const SequenceStats s = acc->stats();
  json q;
  q["frames"] = frames;
  q["per_frame_reference"] = per_frame_ref;
  q["pixels"] = s.pixels;
  q["nonfinite_pixel_frames"] = s.nonfinite_pixel_frames;
  q["mse_seq"] = metric(s.mse_seq, "mse_seq", io, unit_of("mse_seq"));
  q["bias2"] = metric(s.bias2, "bias2", io, unit_of("bias2"));
  q["variance"] = metric(s.variance, "variance", io, unit_of("variance"));
  q["reference_noise"] = metric(s.reference_noise, "reference_noise", json{"reference:variance"}, "radiance^2");
  q["bias2_corrected"] = metric(s.bias2_corrected, "bias2_corrected", io, unit_of("bias2_corrected"));
  q["variance_corrected"] = metric(s.variance_corrected, "variance_corrected", io, unit_of("variance_corrected"));
  q["mean_reference_luminance"] = number(s.mean_reference_luminance);
  q["flicker"] = metric(s.flicker, "flicker", io, unit_of("flicker"));
  q["flicker_uncorrected"] = metric(s.flicker_uncorrected, "flicker", io, unit_of("flicker"));
  if (!req.sequence_only) {
    const double tf_test = flip_pairs ? flip_test / flip_pairs : std::numeric_limits<double>::quiet_NaN();
    const double tf_ref = flip_pairs ? flip_ref / flip_pairs : std::numeric_limits<double>::quiet_NaN();
    q["temporal_flip"] = metric(tf_test - tf_ref, "temporal_flip", io, unit_of("temporal_flip"));
    q["temporal_flip"]["technique_consecutive_flip"] = number(tf_test);
    q["temporal_flip"]["reference_consecutive_flip"] = number(tf_ref);
  }
  if (!region.empty()) {
    const LagResult lr = lag90(r_t, t0, req.frame_ms);
    lag["step_frame"] = first + t0;
    lag["value_frames"] = lr.lag_frames ? json(*lr.lag_frames) : json(nullptr);
    if (!lr.lag_frames) lag["reason"] = "r_t never fell below the 90% threshold";
    lag["r_t0"] = number(lr.r_t0);
    lag["r_inf"] = number(lr.r_inf);
    lag["r_inf_stddev"] = number(lr.r_inf_stddev);
    lag["threshold"] = number(lr.threshold);
    lag["region_pixels"] = region_pixels;
    json rs = json::array();
    for (double v : r_t) rs.push_back(number(v));
    lag["r"] = rs;
    q["lag90_frames"] = metric(lr.lag_frames ? double(*lr.lag_frames) : std::numeric_limits<double>::quiet_NaN(),
                               "lag90", io, unit_of("lag90_frames"));
    if (req.frame_ms) {
      json ms_in = io;
      ms_in.push_back("timings:" + req.timings);
      q["lag90_ms"] = metric(lr.lag_ms ? *lr.lag_ms : std::numeric_limits<double>::quiet_NaN(), "lag90", ms_in, unit_of("lag90_ms"));
    }
  }
  q["lag"] = lag;

  json out;
  out["inputs"] = {{"reference", in.reference_label},
                   {"test", in.test_label},
                   {"frames", {first, last}},
                   {"layer", layer_name},
                   {"width", width},
                   {"height", height},
                   {"dynamic_range", hdr ? "hdr" : "ldr"}};
  out["sequence"] = q;
  out["per_frame"] = per_frame;
  if (!req.sequence_only) out["last_frame"] = last_frame;
  if (req.write_maps || kept) {
    Map sd = acc->temporal_stddev_map();
    if (req.write_maps) {
      const WrittenMap wm = write_map(sd, req.out_dir, auto_range(sd));
      out["maps"] = {{"temporal_stddev",
                      {{"exr", wm.exr.filename().string()},
                       {"png", wm.png.filename().string()},
                       {"definition", sd.definition},
                       {"unit", sd.unit},
                       {"colormap", wm.colormap},
                       {"range", {wm.range.lo, wm.range.hi}},
                       {"range_rule", wm.range.rule}}}};
    }
    if (kept) kept->push_back(std::move(sd));
  }
  return out;
}

}  // namespace giq::metrics::detail
