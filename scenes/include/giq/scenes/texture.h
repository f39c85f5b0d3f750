#pragma once
// A glTF texture, decoded once at load time. 8-bit images (nearly all of them) stay 8-bit:
// four bytes a texel instead of sixteen, on the CPU and on the GPU, and every renderer turns a
// byte into a float through the same table (decode_table), so the reference and the real-time
// module read the same floats to the bit. 16-bit images are kept as float RGBA.

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

namespace giq::scenes {

enum class Wrap { Repeat, ClampToEdge, MirroredRepeat };
enum class Filter { Nearest, Linear };

enum class TexelFormat {
  Rgba8Srgb,  // one word a texel, R in the low byte; RGB sRGB-encoded (colour textures), A linear
  Rgba8Unorm, // one word a texel; every channel linear (data textures, and alpha everywhere)
  Rgba32F,    // four words a texel: the bits of linear float R, G, B, A
};

// IEC 61966-2-1 sRGB electro-optical transfer function, of an encoded value in [0, 1].
float srgb_to_linear(float c);

// Byte value c as a float: entries 0..255 are c / 255 (linear), entries 256..511 the IEC
// 61966-2-1 sRGB decoding of c / 255. The only place a byte becomes a colour.
const std::array<float, 512>& decode_table();

struct Texture {
  std::string name;  // image name or URI, for messages
  int width = 0;
  int height = 0;
  TexelFormat format = TexelFormat::Rgba32F;
  // Row-major, first row = v 0 (glTF puts UV (0,0) at the image's top-left corner). Shared, so
  // posing a scene at another time does not copy texels, and one image used as colour and as
  // data is stored once.
  std::shared_ptr<const std::vector<uint32_t>> words;
  Wrap wrap_s = Wrap::Repeat;
  Wrap wrap_t = Wrap::Repeat;
  Filter filter = Filter::Linear;  // magnification filter (docs/scene-format.md)
  // The sampler's minification filter asks for mip maps (or, unset, leaves it to giq): the
  // real-time G-buffer's primary hits then read mip levels; every ray reads level 0 only.
  bool mip_maps = true;

  static uint32_t words_per_texel(TexelFormat f) { return f == TexelFormat::Rgba32F ? 4u : 1u; }
  // True when `words` holds width x height texels.
  bool valid() const;
  // Texel (x, y), decoded; x, y in range.
  glm::vec4 texel(int x, int y) const;
  // Filtered lookup following the sampler's wrap modes; texel centres at (i + 0.5) / size.
  glm::vec4 sample(glm::vec2 uv) const { return fetch(locate(uv)); }

  // sample() in two steps, for a caller with several lookups to make: locate() finds the
  // texels and their weights and asks the memory system for them; fetch() blends them. A path
  // tracer's hits land anywhere in large images, so nearly every lookup waits on memory;
  // locating all of a surface's lookups before fetching any lets those waits overlap.
  struct Footprint {
    size_t texel[4] = {0, 0, 0, 0};  // (x0, y0), (x1, y0), (x0, y1), (x1, y1); Nearest: the first
    float fx = 0.0f, fy = 0.0f;      // weights of x1 and y1
    bool nearest = false;
    bool valid = false;
  };
  Footprint locate(glm::vec2 uv) const;
  glm::vec4 fetch(const Footprint& f) const;

  // Sets width x height float RGBA texels (Rgba32F): textures built in code.
  void assign(int w, int h, const std::vector<glm::vec4>& rgba);

 private:
  glm::vec4 decode(size_t texel) const;  // texel number y * width + x
};

}  // namespace giq::scenes
