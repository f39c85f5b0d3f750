#include "giq/image/image.h"

#include <algorithm>
#include <stdexcept>

#include "giq/base/error.h"

namespace giq::image {

Image::Image(int width, int height) : width_(width), height_(height) {
  if (width < 0 || height < 0)
    throw std::invalid_argument("Image: negative size " + std::to_string(width) + "x" + std::to_string(height));
}

bool Image::has_channel(std::string_view name) const {
  return std::find(names_.begin(), names_.end(), name) != names_.end();
}

float* Image::add_channel(std::string_view name, float value) {
  auto it = std::find(names_.begin(), names_.end(), name);
  if (it != names_.end()) return planes_[size_t(it - names_.begin())].data();
  names_.emplace_back(name);
  // Planes are separate vectors: adding a channel never moves the data of the others, so
  // pointers handed out earlier stay valid.
  planes_.emplace_back(pixel_count(), value);
  return planes_.back().data();
}

const float* Image::channel(std::string_view name) const {
  auto it = std::find(names_.begin(), names_.end(), name);
  if (it == names_.end()) {
    std::string present;
    for (const auto& n : names_) present += (present.empty() ? "" : ",") + n;
    throw InputError("", std::string(name),
                     "no such channel (channels present: " + (present.empty() ? "none" : present) + ")");
  }
  return planes_[size_t(it - names_.begin())].data();
}

float* Image::channel(std::string_view name) {
  return const_cast<float*>(static_cast<const Image&>(*this).channel(name));
}

void Image::remove_channel(std::string_view name) {
  auto it = std::find(names_.begin(), names_.end(), name);
  if (it == names_.end()) return;
  planes_.erase(planes_.begin() + (it - names_.begin()));
  names_.erase(it);
}

std::array<std::string, 3> Image::layer_channels(std::string_view layer) const {
  const std::string prefix = (layer.empty() || layer == "beauty") ? "" : std::string(layer) + ".";
  std::array<std::string, 3> rgb{prefix + "R", prefix + "G", prefix + "B"};
  std::array<std::string, 3> xyz{prefix + "X", prefix + "Y", prefix + "Z"};
  auto all = [&](const std::array<std::string, 3>& c) {
    return has_channel(c[0]) && has_channel(c[1]) && has_channel(c[2]);
  };
  if (!all(rgb) && all(xyz)) return xyz;
  return rgb;
}

bool Image::has_layer(std::string_view layer) const {
  for (const auto& c : layer_channels(layer))
    if (!has_channel(c)) return false;
  return true;
}

std::vector<std::string> Image::layers() const {
  std::vector<std::string> out;
  if (has_layer("")) out.emplace_back("");
  for (const auto& n : names_) {
    size_t dot = n.rfind('.');
    if (dot == std::string::npos || dot == 0) continue;
    std::string layer = n.substr(0, dot);
    if (std::find(out.begin(), out.end(), layer) == out.end() && has_layer(layer)) out.push_back(layer);
  }
  return out;
}

}  // namespace giq::image
