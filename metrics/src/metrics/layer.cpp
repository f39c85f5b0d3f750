#include "giq/metrics/layer.h"

#include <cmath>

#include "giq/base/error.h"

namespace giq::metrics {
namespace {

std::string layer_label(std::string_view layer) {
  return (layer.empty() || layer == "beauty") ? std::string("beauty (R,G,B)") : std::string(layer);
}

std::string list_layers(const image::Image& image) {
  std::string s;
  for (const auto& l : image.layers()) s += (s.empty() ? "" : ", ") + (l.empty() ? std::string("beauty") : l);
  return s.empty() ? "none" : s;
}

}  // namespace

bool RgbLayer::finite(size_t i) const {
  return std::isfinite(c[0][i]) && std::isfinite(c[1][i]) && std::isfinite(c[2][i]);
}

RgbLayer rgb_layer(const image::Image& image, std::string_view layer, const std::string& file) {
  if (!image.has_layer(layer))
    throw InputError(file, layer.empty() ? "beauty" : std::string(layer),
                     "no RGB layer " + layer_label(layer) + " (RGB layers present: " + list_layers(image) + ")");
  const auto names = image.layer_channels(layer);
  RgbLayer v;
  for (int k = 0; k < 3; ++k) v.c[k] = image.channel(names[size_t(k)]);
  v.width = image.width();
  v.height = image.height();
  return v;
}

std::vector<std::string> layer_channel_set(const image::Image& image, std::string_view layer) {
  std::vector<std::string> out;
  const bool beauty = layer.empty() || layer == "beauty";
  const std::string prefix = beauty ? "" : std::string(layer) + ".";
  for (const auto& n : image.channel_names()) {
    if (beauty) {
      if (n == "R" || n == "G" || n == "B" || n == "A") out.push_back(n);
    } else if (n.size() > prefix.size() && n.compare(0, prefix.size(), prefix) == 0 &&
               n.find('.', prefix.size()) == std::string::npos) {
      out.push_back(n);
    }
  }
  return out;
}

void check_pair(const image::Image& reference, const std::string& reference_file, const image::Image& test,
                const std::string& test_file, std::string_view layer) {
  rgb_layer(reference, layer, reference_file);
  rgb_layer(test, layer, test_file);
  if (reference.width() != test.width() || reference.height() != test.height())
    throw InputError(test_file, "size",
                     std::to_string(test.width()) + "x" + std::to_string(test.height()) + ", expected the reference's " +
                         std::to_string(reference.width()) + "x" + std::to_string(reference.height()) + " (" +
                         reference_file + "); render the reference at the test's size (giq reference --width " +
                         std::to_string(test.width()) + " --height " + std::to_string(test.height()) +
                         "), or save the test at the reference's");
  const auto rc = layer_channel_set(reference, layer), tc = layer_channel_set(test, layer);
  if (rc.size() != tc.size()) {
    auto join = [](const std::vector<std::string>& v) {
      std::string s;
      for (const auto& n : v) s += (s.empty() ? "" : ",") + n;
      return s;
    };
    throw InputError(test_file, "layer " + layer_label(layer),
                     std::to_string(tc.size()) + " channels (" + join(tc) + "), expected the reference's " +
                         std::to_string(rc.size()) + " (" + join(rc) + ")");
  }
}

std::string variance_layer_for(const image::Image& reference, std::string_view layer) {
  const bool beauty = layer.empty() || layer == "beauty";
  if (!beauty && reference.has_layer(std::string(layer) + ".variance")) return std::string(layer) + ".variance";
  if (reference.has_layer("variance")) return "variance";
  return "";
}

}  // namespace giq::metrics
