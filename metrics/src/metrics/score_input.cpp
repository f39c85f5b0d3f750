// prepare_input (score_image.h): the one place an input becomes what the metrics compare.

#include <cstring>

#include "giq/base/error.h"
#include "giq/image/io.h"
#include "giq/image/srgb.h"
#include "giq/metrics/layer.h"
#include "score_image.h"

namespace giq::metrics::detail {

image::Image read_input(const std::string& file, Side side, const ScoreRequest& req) {
  return prepare_input(image::read_image(file), file, image::is_exr_file(file), side, req);
}

image::Image prepare_input(const image::Image& in, const std::string& file, bool exr, Side side, const ScoreRequest& req) {
  const bool reference = side == Side::Reference;
  const std::string& layer = reference || !req.test_layer ? req.layer : *req.test_layer;
  rgb_layer(in, layer, file);  // throws, naming the layers present
  Crop c{0, 0, in.width(), in.height()};
  if (req.crop) {
    c = *req.crop;
    if (c.x < 0 || c.y < 0 || c.width <= 0 || c.height <= 0 || int64_t(c.x) + c.width > in.width() ||
        int64_t(c.y) + c.height > in.height())
      throw InputError(file, "--crop",
                       std::to_string(c.x) + "," + std::to_string(c.y) + "," + std::to_string(c.width) + "," +
                           std::to_string(c.height) + " does not lie inside the " + std::to_string(in.width()) + "x" +
                           std::to_string(in.height()) + " image; expected x,y,width,height with x + width <= " +
                           std::to_string(in.width()) + " and y + height <= " + std::to_string(in.height()));
  }
  image::Image out(c.width, c.height);
  out.metadata = in.metadata;
  auto copy = [&](const std::string& from, const std::string& to) {
    const float* src = in.channel(from);
    float* dst = out.add_channel(to);
    for (int y = 0; y < c.height; ++y)
      std::memcpy(dst + size_t(y) * size_t(c.width), src + in.index(c.x, c.y + y), size_t(c.width) * sizeof(float));
    return dst;
  };
  // The test's layer goes under the reference layer's names, so both images hold one layer.
  const auto from = in.layer_channels(layer), to = in.layer_channels(req.layer);
  float* rgb[3];
  for (int k = 0; k < 3; ++k) rgb[k] = copy(from[size_t(k)], to[size_t(k)]);
  float* var[3] = {nullptr, nullptr, nullptr};
  if (reference) {
    const std::string v = variance_layer_for(in, layer);
    if (!v.empty()) {
      const auto names = in.layer_channels(v);
      for (int k = 0; k < 3; ++k) var[k] = copy(names[size_t(k)], names[size_t(k)]);
    }
    if (in.has_channel("objectId")) copy("objectId", "objectId");
  }
  const size_t n = out.pixel_count();
  if (!reference && req.test_encoding == TestEncoding::Linear) {
    if (exr) throw InputError(file, "--test-encoding", "linear applies to 8-bit images; an EXR holds linear values already");
    // The reader decoded the stored values as sRGB; encoding them again gives them back.
    for (float* p : rgb)
      for (size_t i = 0; i < n; ++i) p[i] = image::srgb_encode(p[i]);
  }
  // The exposure brings the reference to the test's (which carries its own); the tone curve
  // makes both display-referred, so it goes on an HDR test too.
  DisplayTransform display = req.display;
  if (!reference) display.exposure_ev = 0.0;
  if (display.active() && (reference || exr))
    for (int k = 0; k < 3; ++k)
      for (size_t i = 0; i < n; ++i) {
        const float x = rgb[k][i];
        if (var[k]) {
          const float s = display.slope(x);
          var[k][i] *= s * s;
        }
        rgb[k][i] = display.apply(x);
      }
  return out;
}

bool compares_hdr(const std::string& reference_file, const std::string& test_file, const ScoreRequest& req) {
  return image::is_exr_file(reference_file) && image::is_exr_file(test_file) && req.display.curve == ToneCurve::None;
}

}  // namespace giq::metrics::detail
