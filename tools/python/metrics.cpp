// giq.score, giq.flip, giq.ssim, giq.relmse, giq.leak, giq.flicker, giq.lag: the metrics of
// docs/metrics.md on arrays or files, through metrics::score and the functions it calls.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <filesystem>
#include <optional>

#include "arrays.h"
#include "giq/base/error.h"
#include "giq/gate/metric_lookup.h"
#include "giq/image/io.h"
#include "giq/metrics/error.h"
#include "giq/metrics/flip.h"
#include "giq/metrics/leak.h"
#include "giq/metrics/score.h"
#include "giq/metrics/ssim.h"
#include "giq/scenes/scene.h"
#include "interruptible.h"
#include "module.h"

namespace giq::python {
namespace {

using nlohmann::json;

// One side of a comparison in memory: one image, or one per frame.
struct Side {
  std::vector<image::Image> images;
  std::string name;
  bool hdr = true;
  bool sequence = false;
};

Side side_of(const py::handle& input, const std::string& name, NanPolicy nans) {
  Side s;
  s.name = name;
  auto one = [&](const py::handle& h, const std::string& what) {
    if (is_path(h)) {
      const std::string path = path_of(h);
      s.hdr = image::is_exr_file(path);
      py::gil_scoped_release release;
      return image::read_image(path);
    }
    return image_from(h, what, nans);
  };
  if (is_path(input)) s.name = path_of(input);
  const bool stack = py::isinstance<py::array>(input) && py::reinterpret_borrow<py::array>(input).ndim() == 4;
  if (py::isinstance<py::list>(input) || py::isinstance<py::tuple>(input) || stack) {
    s.sequence = true;
    size_t i = 0;
    for (const py::handle& frame : input) s.images.push_back(one(frame, name + "[" + std::to_string(i++) + "]"));
    if (s.images.empty()) throw InputError(name, "frames", "an empty sequence; expected at least one frame");
  } else {
    s.images.push_back(one(input, s.name));
  }
  return s;
}

// variance= and object_id= go into the reference image(s): one array for all, or one per frame.
void add_to_reference(Side& ref, const py::handle& extra, const std::string& field, const std::string& layer) {
  if (extra.is_none()) return;
  const bool per_frame = py::isinstance<py::list>(extra) || py::isinstance<py::tuple>(extra) ||
                         (py::isinstance<py::array>(extra) && py::reinterpret_borrow<py::array>(extra).ndim() == 4);
  const size_t n = per_frame ? py::len(extra) : 1;
  if (per_frame && n != ref.images.size())
    throw InputError(ref.name, field, std::to_string(n) + " arrays for " + std::to_string(ref.images.size()) +
                                          " reference frames; expected one per frame, or one array");
  for (size_t i = 0; i < ref.images.size(); ++i) {
    const py::handle a = per_frame ? py::handle(extra[py::int_(i)]) : extra;
    if (field == "object_id") add_plane(ref.images[i], "objectId", a, ref.name, field);
    else add_rgb(ref.images[i], layer.empty() || layer == "beauty" ? "variance" : layer + ".variance", a, ref.name, field);
  }
}

struct ScoreOptions {
  std::string layer = "beauty";
  std::optional<std::string> ref_layer, test_layer;
  py::object variance = py::none(), object_id = py::none(), scene = py::none(), timings = py::none();
  std::string tonemap = "none", test_encoding = "srgb", nan_policy = "omit";
  double exposure = 0.0;
  std::optional<std::array<int, 4>> crop;
  std::optional<std::pair<int, int>> frames;
  std::optional<int> step_frame;
};

std::string beauty_as_empty(const std::string& layer) { return layer == "beauty" ? "" : layer; }

metrics::ScoreRequest request_of(const ScoreOptions& o) {
  metrics::ScoreRequest req;
  req.layer = beauty_as_empty(o.ref_layer.value_or(o.layer));
  req.test_layer = beauty_as_empty(o.test_layer.value_or(o.layer));
  if (o.crop) req.crop = metrics::Crop{(*o.crop)[0], (*o.crop)[1], (*o.crop)[2], (*o.crop)[3]};
  if (o.test_encoding != "srgb" && o.test_encoding != "linear")
    throw InputError("", "test_encoding", "'" + o.test_encoding + "'; expected srgb or linear");
  req.test_encoding = o.test_encoding == "linear" ? metrics::TestEncoding::Linear : metrics::TestEncoding::Srgb;
  const auto curve = metrics::tone_curve_from_name(o.tonemap);
  if (!curve) throw InputError("", "tonemap", "'" + o.tonemap + "'; expected one of " + std::string(metrics::kToneCurveNames));
  req.display.curve = *curve;
  if (!std::isfinite(o.exposure) || std::abs(o.exposure) > 64.0)
    throw InputError("", "exposure", std::to_string(o.exposure) + "; expected stops in [-64, 64]");
  req.display.exposure_ev = o.exposure;
  req.frames = o.frames;
  req.step_frame = o.step_frame;
  if (!o.scene.is_none()) {
    // A path, or a giq.Scene (which knows its path and leak regions).
    const std::string path = is_path(o.scene) ? path_of(o.scene) : py::str(o.scene.attr("path")).cast<std::string>();
    const scenes::Scene s = scenes::load(path);
    req.scene = path;
    req.leak_object_ids = s.leak_object_ids;
  }
  if (!o.timings.is_none()) {
    // timings.json by path, or the timings dict giq.realtime returns.
    const gate::FrameTime t = is_path(o.timings) ? gate::read_timings(path_of(o.timings))
                                                 : gate::frame_time(json::parse(py::str(py::module_::import("json").attr("dumps")(o.timings)).cast<std::string>()));
    if (!t.gpu_ms) throw InputError("", "timings", "holds no frame time (frame_gpu_ms.median)");
    req.frame_ms = *t.gpu_ms;
    req.timings = is_path(o.timings) ? path_of(o.timings) + ":" + t.key : "<timings>:" + t.key;
  }
  return req;
}

// metrics::score on files (out given, both paths: exactly giq score --out) or on images in memory.
metrics::ScoreResult run_score(const py::handle& ref, const py::handle& test, const ScoreOptions& o,
                               const std::optional<std::filesystem::path>& out, bool keep_maps, bool sequence_only) {
  metrics::ScoreRequest req = request_of(o);
  req.sequence_only = sequence_only;
  const NanPolicy nans = parse_nan_policy(o.nan_policy);
  if (out && is_path(ref) && is_path(test) && o.variance.is_none() && o.object_id.is_none() && !keep_maps &&
      nans == NanPolicy::Omit) {
    req.reference = path_of(ref), req.test = path_of(test), req.out_dir = *out;
    metrics::ScoreResult r;
    run_interruptible([&](const std::atomic<bool>&) { r.metrics = metrics::score(req); });
    return r;
  }
  if (o.frames) throw InputError("", "frames", "applies to file patterns with out=; give arrays of frames as a list instead");
  Side r = side_of(ref, "<reference>", NanPolicy::Omit), t = side_of(test, "<test>", nans);
  add_to_reference(r, o.variance, "variance", o.ref_layer.value_or(o.layer));
  add_to_reference(r, o.object_id, "object_id", "");
  if (r.sequence && !t.sequence) throw InputError(r.name, "frames", "a sequence of reference frames needs a sequence of test frames");
  metrics::ImageInputs in;
  in.reference = std::move(r.images), in.test = std::move(t.images);
  in.sequence = t.sequence;
  in.reference_name = r.name, in.test_name = t.name;
  in.reference_hdr = r.hdr, in.test_hdr = t.hdr;
  if (out) req.out_dir = *out;
  metrics::ScoreResult result;
  run_interruptible([&](const std::atomic<bool>&) { result = metrics::score(in, req, keep_maps); });
  return result;
}

ScoreOptions options_of(const py::kwargs& kw, std::initializer_list<const char*> allowed, const char* function) {
  ScoreOptions o;
  for (const auto& [key, value] : kw) {
    const std::string k = py::str(key);
    if (std::find_if(allowed.begin(), allowed.end(), [&](const char* a) { return k == a; }) == allowed.end()) {
      std::string names;
      for (const char* a : allowed) {
        if (!names.empty()) names += ", ";
        names += a;
      }
      throw py::type_error(std::string(function) + "() got an unexpected keyword argument '" + k + "' (expected " + names + ")");
    }
    if (k == "layer") o.layer = value.cast<std::string>();
    else if (k == "ref_layer") o.ref_layer = value.cast<std::optional<std::string>>();
    else if (k == "test_layer") o.test_layer = value.cast<std::optional<std::string>>();
    else if (k == "variance") o.variance = py::reinterpret_borrow<py::object>(value);
    else if (k == "object_id") o.object_id = py::reinterpret_borrow<py::object>(value);
    else if (k == "scene") o.scene = py::reinterpret_borrow<py::object>(value);
    else if (k == "timings") o.timings = py::reinterpret_borrow<py::object>(value);
    else if (k == "tonemap") o.tonemap = value.cast<std::string>();
    else if (k == "exposure") o.exposure = value.cast<double>();
    else if (k == "test_encoding") o.test_encoding = value.cast<std::string>();
    else if (k == "nan_policy") o.nan_policy = value.cast<std::string>();
    else if (k == "crop") o.crop = value.cast<std::optional<std::array<int, 4>>>();
    else if (k == "frames") o.frames = value.cast<std::optional<std::pair<int, int>>>();
    else if (k == "step_frame") o.step_frame = value.cast<std::optional<int>>();
  }
  return o;
}

py::dict maps_of(const std::vector<metrics::Map>& maps) {
  py::dict d;
  for (const metrics::Map& m : maps) d[py::str(m.name)] = plane_array(m.values.data(), m.width, m.height);
  return d;
}

py::object score(const py::object& ref, const py::object& test, const std::optional<std::filesystem::path>& out, bool maps,
                 const py::kwargs& kw) {
  const ScoreOptions o = options_of(kw,
                                    {"layer", "ref_layer", "test_layer", "variance", "object_id", "scene", "timings", "tonemap",
                                     "exposure", "test_encoding", "nan_policy", "crop", "frames", "step_frame"},
                                    "score");
  const metrics::ScoreResult r = run_score(ref, test, o, out, maps, false);
  if (maps) return py::make_tuple(to_python(r.metrics), maps_of(r.maps));
  return to_python(r.metrics);
}

// A pair of single images for the per-image metrics below, prepared as score prepares them.
std::pair<image::Image, image::Image> pair_of(const py::object& ref, const py::object& test, const py::object& variance,
                                              NanPolicy nans, bool& hdr) {
  Side r = side_of(ref, "<reference>", NanPolicy::Omit), t = side_of(test, "<test>", nans);
  if (r.sequence || t.sequence) throw InputError(r.sequence ? r.name : t.name, "frames", "a sequence; expected one image");
  add_to_reference(r, variance, "variance", "");
  metrics::check_pair(r.images[0], r.name, t.images[0], t.name, "");
  hdr = r.hdr && t.hdr;
  return {std::move(r.images[0]), std::move(t.images[0])};
}

py::tuple flip(const py::object& ref, const py::object& test, bool hdr, double ppd, const std::string& nan_policy) {
  bool files_hdr = true;
  auto [r, t] = pair_of(ref, test, py::none(), parse_nan_policy(nan_policy), files_hdr);
  if (!(ppd > 0.0 && std::isfinite(ppd))) throw InputError("", "ppd", std::to_string(ppd) + "; expected pixels per degree > 0");
  metrics::FlipOptions options;
  options.pixels_per_degree = ppd;
  metrics::FlipResult f;
  {
    py::gil_scoped_release release;
    f = metrics::flip_valid(r, t, "", hdr, options);
  }
  return py::make_tuple(f.mean, plane_array(f.map.data(), f.width, f.height));
}

double ssim(const py::object& ref, const py::object& test, const std::string& nan_policy) {
  bool hdr = true;
  const auto [r, t] = pair_of(ref, test, py::none(), parse_nan_policy(nan_policy), hdr);
  py::gil_scoped_release release;
  return metrics::ssim(metrics::rgb_layer(r, "", ""), metrics::rgb_layer(t, "", "")).mean;
}

double relmse(const py::object& ref, const py::object& test, const std::string& nan_policy) {
  bool hdr = true;
  const auto [r, t] = pair_of(ref, test, py::none(), parse_nan_policy(nan_policy), hdr);
  py::gil_scoped_release release;
  return metrics::error_stats(metrics::rgb_layer(r, "", ""), metrics::rgb_layer(t, "", "")).relmse;
}

py::dict leak(const py::object& ref, const py::object& test, const py::object& variance, const py::object& object_id,
              const std::vector<uint32_t>& object_ids) {
  bool hdr = true;
  auto [r, t] = pair_of(ref, test, variance, NanPolicy::Omit, hdr);
  const float* ids = nullptr;
  if (!object_id.is_none()) add_plane(r, "objectId", object_id, "<reference>", "object_id"), ids = r.channel("objectId");
  if (!object_ids.empty() && !ids) throw InputError("<reference>", "object_id", "object_ids given without the reference's object_id plane");
  const metrics::RgbLayer rl = metrics::rgb_layer(r, "", ""), tl = metrics::rgb_layer(t, "", "");
  std::optional<metrics::RgbLayer> vl;
  if (!variance.is_none()) vl = metrics::rgb_layer(r, "variance", "");
  metrics::LeakOptions lo;
  lo.declared_object_ids = object_ids;
  metrics::LeakResult lk;
  {
    py::gil_scoped_release release;
    lk = metrics::leak(rl, tl, vl ? &*vl : nullptr, ids, lo);
  }
  auto region = [](const metrics::LeakRegion& g) {
    py::dict d;
    d["leak"] = g.leak, d["leak_pixels"] = g.leak_pixels, d["leak_absolute"] = g.leak_absolute, d["pixels"] = g.pixels;
    return d;
  };
  py::dict out;
  out["automatic"] = region(lk.automatic);
  out["declared"] = lk.declared ? py::object(region(*lk.declared)) : py::object(py::none());
  out["reference_luminance_sum"] = lk.reference_luminance_sum;
  out["dark_threshold"] = lk.dark_threshold;
  return out;
}

// The value of each metric entry ({"value": v, ...} -> v) of a metrics.json section.
py::dict values_of(const json& section) {
  py::dict d;
  for (const auto& [k, v] : section.items())
    d[py::str(k)] = v.is_object() && v.contains("value") ? to_python(v["value"]) : to_python(v);
  return d;
}

py::dict flicker(const py::object& ref, const py::object& test, const py::kwargs& kw) {
  const ScoreOptions o = options_of(kw, {"layer", "variance", "nan_policy"}, "flicker");
  const json seq = run_score(ref, test, o, std::nullopt, false, true).metrics.at("sequence");
  json picked;
  for (const char* k : {"frames", "flicker", "flicker_uncorrected", "mse_seq", "bias2", "variance", "bias2_corrected",
                        "variance_corrected", "reference_noise", "mean_reference_luminance", "nonfinite_pixel_frames"})
    picked[k] = seq.at(k);
  return values_of(picked);
}

py::dict lag(const py::object& ref, const py::object& test, const py::kwargs& kw) {
  const ScoreOptions o = options_of(kw, {"layer", "variance", "step_frame", "timings", "nan_policy"}, "lag");
  const json seq = run_score(ref, test, o, std::nullopt, false, true).metrics.at("sequence");
  json picked = seq.at("lag");
  if (seq.contains("lag90_ms")) picked["lag90_ms"] = seq["lag90_ms"].at("value");
  return values_of(picked);
}

}  // namespace

void register_metrics(py::module_& m) {
  m.def("score", &score, py::arg("ref"), py::arg("test"), py::kw_only(), py::arg("out") = py::none(), py::arg("maps") = false,
        R"(Scores a technique's image (or frames) against the reference: metrics.json's content as a dict.

ref, test: arrays (H, W, 3) or (H, W), float16/32/64, any order; dicts of layers as read_exr returns
them; paths (EXR, or PNG/JPEG screenshots); or lists of these (or (T, H, W, 3) arrays) for a sequence.
Keywords as giq score's options: layer, ref_layer, test_layer, variance (the reference's per-pixel
variance of the mean, one array or one per frame), object_id (the reference's objectId plane), scene
(its leak regions), timings (timings.json or giq.realtime's dict), tonemap, exposure, test_encoding,
crop=(x, y, w, h), frames=(a, b) with file patterns, step_frame, nan_policy ('omit' or 'raise').
out: a folder; written as giq score --out writes it (metrics.json, maps, strip), and with two paths
exactly giq score's run. Without it nothing is written and there are no 'maps' and 'strip' entries.
maps=True: returns (metrics, {name: (H, W) array}) with the error maps (abs_error, relative_error,
signed_luminance, leak, flip; temporal_stddev for a sequence).)");
  m.def("flip", &flip, py::arg("ref"), py::arg("test"), py::arg("hdr") = true,
        py::arg("ppd") = metrics::FlipOptions{}.pixels_per_degree, py::arg("nan_policy") = "omit",
        "FLIP of two images as giq score computes it (HDR-FLIP, or LDR-FLIP with hdr=False): (mean, (H, W) map).");
  m.def("ssim", &ssim, py::arg("ref"), py::arg("test"), py::arg("nan_policy") = "omit", "Mean SSIM (docs/metrics.md).");
  m.def("relmse", &relmse, py::arg("ref"), py::arg("test"), py::arg("nan_policy") = "omit",
        "Relative MSE, mean over pixels and RGB of (T - R)^2 / (R^2 + 0.01) (docs/metrics.md).");
  m.def("leak", &leak, py::arg("ref"), py::arg("test"), py::kw_only(), py::arg("variance") = py::none(),
        py::arg("object_id") = py::none(), py::arg("object_ids") = std::vector<uint32_t>{},
        "Light leaking (docs/metrics.md): the automatic dark region's and, with object_id and object_ids, the declared region's.");
  m.def("flicker", &flicker, py::arg("ref"), py::arg("test"),
        "Sequence error split into bias and variance, and flicker, over frames (lists or (T, H, W, 3) arrays; one reference\n"
        "array for a static scene). Keywords: layer, variance, nan_policy. The values of metrics.json's sequence entries.");
  m.def("lag", &lag, py::arg("ref"), py::arg("test"),
        "lag90 after a step change over frames (one reference per frame). Keywords: layer, variance, step_frame, timings,\n"
        "nan_policy. metrics.json's sequence.lag, with lag90_ms when timings are given.");
}

}  // namespace giq::python
