#pragma once
// A float32 image with named channels, as in a multi-layer OpenEXR file: "R","G","B" for the
// beauty, "<layer>.R" etc. for a layer ("indirect.R", "variance.G"), single channels such as
// "Z" or "objectId", and string metadata. Storage is planar (one contiguous plane per
// channel), which is how EXR frame buffers, per-channel metrics and GPU read-back want it.

#include <array>
#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace giq::image {

class Image {
 public:
  Image() = default;
  Image(int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }
  size_t pixel_count() const { return size_t(width_) * size_t(height_); }

  // Channels keep their insertion order (EXR files store them sorted by name; readers and
  // writers keep this order where the format allows).
  const std::vector<std::string>& channel_names() const { return names_; }
  bool has_channel(std::string_view name) const;
  // Adds a channel filled with `value`, or returns the existing one unchanged.
  float* add_channel(std::string_view name, float value = 0.0f);
  // Throws InputError naming the missing channel and the ones present.
  float* channel(std::string_view name);
  const float* channel(std::string_view name) const;
  void remove_channel(std::string_view name);

  float at(std::string_view name, int x, int y) const { return channel(name)[index(x, y)]; }
  size_t index(int x, int y) const { return size_t(y) * size_t(width_) + size_t(x); }

  // The three channel names of an RGB layer: "" or "beauty" -> R,G,B; "indirect" ->
  // indirect.R, indirect.G, indirect.B. Accepts ".X/.Y/.Z" layers such as "N" too.
  std::array<std::string, 3> layer_channels(std::string_view layer) const;
  bool has_layer(std::string_view layer) const;
  // Layer names present, "" (beauty) first when the image has R,G,B.
  std::vector<std::string> layers() const;

  std::map<std::string, std::string> metadata;

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<std::string> names_;
  std::vector<std::vector<float>> planes_;
};

// Luminance Y = 0.2126 R + 0.7152 G + 0.0722 B (ITU-R BT.709 primaries, linear RGB).
inline float luminance(float r, float g, float b) { return 0.2126f * r + 0.7152f * g + 0.0722f * b; }

}  // namespace giq::image
