#include "score_image.h"

#include <cmath>

#include "giq/base/error.h"
#include "giq/image/io.h"
#include "giq/metrics/catalogue.h"
#include "giq/metrics/error.h"
#include "giq/metrics/flip.h"
#include "giq/metrics/leak.h"
#include "giq/metrics/maps.h"
#include "giq/metrics/ssim.h"
#include "giq/metrics/ztest.h"
#include "giq/metrics/strip.h"
#include "score_json.h"

namespace giq::metrics::detail {
namespace {

using nlohmann::json;

json map_entry(const WrittenMap& m, const Map& map) {
  return {{"exr", m.exr.filename().string()}, {"png", m.png.filename().string()},
          {"definition", map.definition},     {"unit", map.unit},
          {"colormap", m.colormap},           {"range", {m.range.lo, m.range.hi}},
          {"range_rule", m.range.rule}};
}

json leak_region_json(const LeakRegion& g, const std::string& region, const json& inputs) {
  return {{"region", region},
          {"pixels", g.pixels},
          {"leak", metric(g.leak, "leak", inputs, unit_of("leak"))},
          {"leak_pixels", metric(g.leak_pixels, "leak_pixels", inputs, unit_of("leak_pixels"))},
          {"leak_absolute", metric(g.leak_absolute, "leak_absolute", inputs, "radiance per image pixel")}};
}

}  // namespace

json score_image(const image::Image& ref, const std::string& ref_file, const image::Image& test,
                 const std::string& test_file, bool hdr, const ScoreRequest& req, std::vector<Map>* kept) {
  check_pair(ref, ref_file, test, test_file, req.layer);
  const RgbLayer r = rgb_layer(ref, req.layer, ref_file);
  const RgbLayer t = rgb_layer(test, req.layer, test_file);
  const std::string layer_name = req.layer.empty() ? "beauty" : req.layer;
  const std::string var_layer = variance_layer_for(ref, req.layer);
  std::optional<RgbLayer> var;
  if (!var_layer.empty()) var = rgb_layer(ref, var_layer, ref_file);
  const RgbLayer* v = var ? &*var : nullptr;

  const json io = {"reference:" + layer_name, "test:" + layer_name};
  json io_noise = io;
  if (v) io_noise.push_back("reference:" + var_layer);

  json out;
  out["inputs"] = {{"reference", ref_file},
                   {"test", test_file},
                   {"layer", layer_name},
                   {"width", ref.width()},
                   {"height", ref.height()},
                   {"dynamic_range", hdr ? "hdr" : "ldr"},
                   {"variance_layer", var_layer.empty() ? json(nullptr) : json(var_layer)}};
  if (!var_layer.empty() && var_layer == "variance" && layer_name != "beauty")
    out["inputs"]["variance_note"] = "the beauty's variance stands in for layer " + layer_name;

  // --- per-image error and noise floor
  const ErrorStats e = error_stats(r, t, v);
  json m;
  m["pixels"] = e.pixels;
  m["valid_pixels"] = e.valid_pixels;
  m["nonfinite_pixels"] = e.nonfinite_pixels;
  m["reference_nonfinite_pixels"] = e.reference_nonfinite_pixels;
  auto with_floor = [&](json j, bool unresolved, double floor) {
    if (e.noise) {
      j["noise_floor"] = number(floor);
      j["unresolved"] = unresolved;
      if (unresolved) j["note"] = "unresolved: reference too noisy (value < 3x noise floor)";
    }
    return j;
  };
  const double nf_mse = e.noise ? e.noise->mean_variance : 0.0;
  m["mse"] = with_floor(metric(e.mse, "mse", io, unit_of("mse")), e.unresolved_mse, nf_mse);
  m["rmse"] = with_floor(metric(e.rmse, "rmse", io, unit_of("rmse")), e.unresolved_mse, std::sqrt(nf_mse));
  m["mae"] = with_floor(metric(e.mae, "mae", io, unit_of("mae")), e.unresolved_mae, e.noise ? e.noise->mae : 0.0);
  m["relmse"] = with_floor(metric(e.relmse, "relmse", io, unit_of("relmse")), e.unresolved_relmse, e.noise ? e.noise->relmse : 0.0);
  m["relmse_trimmed"] = with_floor(metric(e.relmse_trimmed, "relmse_trimmed", io, unit_of("relmse_trimmed")),
                                   e.unresolved_relmse_trimmed, e.noise ? e.noise->relmse_trimmed : 0.0);
  m["relmse_trimmed"]["trimmed_pixels"] = e.trimmed_pixels;
  m["smape"] = with_floor(metric(e.smape, "smape", io, unit_of("smape")), e.unresolved_smape, e.noise ? e.noise->smape : 0.0);
  m["psnr"] = with_floor(metric(e.psnr, "psnr", io, unit_of("psnr")), e.unresolved_mse, nf_mse);
  if (e.noise) {
    m["noise_floor"] = metric(e.noise->mean_variance, "noise_floor", json{"reference:" + var_layer}, unit_of("noise_floor"));
    // Below the noise floor (a negative estimate included) the debiased error is noise: flagged
    // like the plain error.
    m["mse_debiased"] = with_floor(metric(e.mse_debiased, "mse_debiased", io_noise, unit_of("mse_debiased")),
                                   e.unresolved_mse, nf_mse);
  }

  // --- the per-pixel z-test, where the reference has its noise (and the test its own, if any)
  if (v) {
    const std::string test_var_layer = variance_layer_for(test, req.layer);
    std::optional<RgbLayer> tv;
    if (!test_var_layer.empty()) tv = rgb_layer(test, test_var_layer, test_file);
    const ZTest zt = ztest(r, t, *v, tv ? &*tv : nullptr);
    json zio = io_noise;
    if (tv) zio.push_back("test:" + test_var_layer);
    m["ztest"] = {{"p_sidak", metric(zt.p_sidak, "ztest_sidak", zio, unit_of("ztest_p"))},
                  {"max_abs_z", number(zt.max_abs_z)},
                  {"p_min", number(zt.p_min)},
                  {"tested", zt.tested}};
  }

  // --- SSIM
  const SsimResult s = ssim(r, t);
  m["ssim"] = metric(s.mean, "ssim", io, unit_of("ssim"));

  // --- FLIP
  FlipResult f = flip_valid(ref, test, req.layer, hdr);
  const std::string flip_def = hdr ? "hdr_flip" : "ldr_flip";
  json fj = {{"mean", metric(f.mean, flip_def, io, unit_of("flip_mean"))},
             {"weighted_median", metric(f.weighted_median, flip_def, io, unit_of("flip_median"))},
             {"weighted_q1", metric(f.weighted_q1, flip_def, io, "1")},
             {"weighted_q3", metric(f.weighted_q3, flip_def, io, "1")},
             {"max", metric(f.max, flip_def, io, unit_of("flip_max"))},
             {"pixels_per_degree", FlipOptions{}.pixels_per_degree}};
  if (hdr) fj["exposure"] = {{"start", f.start_exposure}, {"stop", f.stop_exposure}, {"count", f.exposures}};
  m["flip"] = fj;

  // --- leaking
  const float* object_id = nullptr;
  if (!req.leak_object_ids.empty()) {
    if (!ref.has_channel("objectId"))
      throw InputError(ref_file, "objectId",
                       "the scene declares leak regions, which are found through the reference's objectId "
                       "channel; the reference has none");
    object_id = ref.channel("objectId");
  }
  LeakOptions lo;
  lo.declared_object_ids = req.leak_object_ids;
  const LeakResult lk = leak(r, t, v, object_id, lo);
  json leak_io = io_noise;
  json lj = {{"reference_luminance_sum", number(lk.reference_luminance_sum)},
             {"automatic", leak_region_json(lk.automatic, "Y_R <= 0.05 mean Y_R", leak_io)},
             {"dark_threshold", number(lk.dark_threshold)}};
  if (lk.declared) {
    json dio = leak_io;
    dio.push_back("reference:objectId");
    if (!req.scene.empty()) dio.push_back("scene:" + req.scene);
    lj["declared"] = leak_region_json(*lk.declared, "objectId in scene leak regions", dio);
    lj["declared"]["object_ids"] = req.leak_object_ids;
  }
  m["leak"] = lj;
  out["metrics"] = m;

  // --- what makes the scores doubtful (score() adds the ones about the files)
  double sum_r = 0.0, sum_t = 0.0;
  for (size_t i = 0; i < r.pixel_count(); ++i)
    if (r.finite(i) && t.finite(i)) sum_r += r.luminance(i), sum_t += t.luminance(i);
  json warnings = json::array();
  if (!(sum_r > 0.0)) {
    warnings.push_back("the reference is black (mean luminance " + std::to_string(sum_r / double(r.pixel_count())) +
                       "): relative metrics are undefined and only absolute ones (mse, mae, leak_absolute) mean "
                       "something; if light was expected, check the camera (position, handedness, units) and the lights");
  } else {
    const double ratio = sum_t / sum_r;
    out["metrics"]["mean_luminance_ratio"] = number(ratio);
    if (!(ratio >= 0.8 && ratio <= 1.25)) {
      std::string w = "the test's mean luminance is " + std::to_string(ratio) +
                      " times the reference's: an exposure or unit mismatch, or light missing or added over much of the image";
      if (std::abs(std::log(ratio / 683.0)) < 0.1 || std::abs(std::log(ratio * 683.0)) < 0.1)
        w += " (683 lm/W is the factor between photometric and radiometric light units, KHR_lights_punctual)";
      warnings.push_back(w + "; for a mismatch, --exposure scales the reference (docs/own-engine.md)");
    }
  }
  if (m["relmse"].value("unresolved", false))
    warnings.push_back("the reference is too noisy to resolve the error (relmse below 3 times its noise floor): render it "
                       "with more samples");
  out["warnings"] = warnings;

  // --- maps, one at a time so at most one extra plane is resident (unless they are kept)
  if (req.write_maps || kept) {
    json maps;
    std::optional<Map> abs_map;
    MapRange abs_range;
    auto emit = [&](Map map, std::optional<MapRange> range) {
      const MapRange rg = range ? *range : auto_range(map);
      if (req.write_maps) maps[map.name] = map_entry(write_map(map, req.out_dir, rg), map);
      if (req.write_maps && map.name == "abs_error") abs_map = map, abs_range = rg;  // for the strip
      if (kept) kept->push_back(std::move(map));
    };
    emit(abs_error_map(r, t), std::nullopt);
    emit(relative_error_map(r, t), std::nullopt);
    emit(signed_luminance_map(r, t), std::nullopt);
    emit(leak_map(r, t, v), std::nullopt);
    emit(Map{"flip", flip_def + " per pixel", "1", false, f.width, f.height, std::move(f.map)},
         MapRange{0.0f, 1.0f, "FLIP's own range [0, 1]"});
    if (req.write_maps) {
      out["maps"] = maps;
      const StripInfo si = write_strip(req.out_dir / "strip.png", r, t, *abs_map, abs_range, hdr);
      out["strip"] = {{"png", "strip.png"},
                      {"panels", {"reference", "technique", "abs_error"}},
                      {"exposure", si.exposure},
                      {"panel_size", {si.panel_width, si.panel_height}}};
    }
  }
  return out;
}

}  // namespace giq::metrics::detail
