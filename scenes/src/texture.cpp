#include "giq/scenes/texture.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <utility>

namespace giq::scenes {
namespace {

// Maps an integer texel coordinate onto [0, n) following the glTF sampler wrap mode (glTF 2.0
// spec, 5.26 "Sampler": wrapS/wrapT take the OpenGL REPEAT, CLAMP_TO_EDGE and MIRRORED_REPEAT
// meanings). The coordinate is floor(uv x size) with |uv| <= 1e6, so it fits int64 and the
// modulo is exact (and cheaper than floating-point division, which texture lookups did four
// times each).
int wrap_index(int64_t i, int n, Wrap mode) {
  switch (mode) {
    case Wrap::Repeat: {
      const int64_t m = i % n;
      return int(m < 0 ? m + n : m);
    }
    case Wrap::ClampToEdge:
      return int(std::clamp<int64_t>(i, 0, n - 1));
    case Wrap::MirroredRepeat: {
      int64_t m = i % (2 * int64_t(n));
      if (m < 0) m += 2 * int64_t(n);
      return int(m < n ? m : 2 * int64_t(n) - 1 - m);
    }
  }
  return 0;
}

// The wrapped indices of i and i + 1, the two texels a bilinear lookup blends along one axis.
std::pair<int, int> wrap_pair(int64_t i, int n, Wrap mode) {
  const int a = wrap_index(i, n, mode);
  if (mode == Wrap::Repeat) return {a, a + 1 == n ? 0 : a + 1};
  return {a, wrap_index(i + 1, n, mode)};
}

}  // namespace

float srgb_to_linear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

const std::array<float, 512>& decode_table() {
  static const std::array<float, 512> table = [] {
    std::array<float, 512> t{};
    for (int c = 0; c < 256; ++c) t[size_t(c)] = float(c) / 255.0f, t[size_t(256 + c)] = srgb_to_linear(float(c) / 255.0f);
    return t;
  }();
  return table;
}

bool Texture::valid() const {
  return width > 0 && height > 0 && words && words->size() >= size_t(width) * size_t(height) * words_per_texel(format);
}

glm::vec4 Texture::texel(int x, int y) const { return decode(size_t(y) * size_t(width) + size_t(x)); }

void Texture::assign(int w, int h, const std::vector<glm::vec4>& rgba) {
  auto out = std::make_shared<std::vector<uint32_t>>();
  out->reserve(4 * rgba.size());
  for (const glm::vec4& c : rgba)
    for (int k = 0; k < 4; ++k) out->push_back(std::bit_cast<uint32_t>(c[k]));
  width = w, height = h, format = TexelFormat::Rgba32F, words = std::move(out);
}

Texture::Footprint Texture::locate(glm::vec2 uv) const {
  Footprint f;
  if (!valid()) return f;
  f.valid = true;
  // Beyond |uv| = 1e6 a float uv cannot address a texel anyway; bounding it keeps the index
  // arithmetic below finite.
  const double u = std::isfinite(uv.x) ? std::clamp(double(uv.x), -1e6, 1e6) : 0.0;
  const double v = std::isfinite(uv.y) ? std::clamp(double(uv.y), -1e6, 1e6) : 0.0;
  const size_t stride = size_t(words_per_texel(format)), w = size_t(width);
  if (filter == Filter::Nearest) {
    const int x = wrap_index(int64_t(std::floor(u * width)), width, wrap_s);
    const int y = wrap_index(int64_t(std::floor(v * height)), height, wrap_t);
    f.nearest = true;
    f.texel[0] = size_t(y) * w + size_t(x);
    __builtin_prefetch(words->data() + stride * f.texel[0]);
    return f;
  }
  // Bilinear between the four nearest texel centres, which sit at (i + 0.5) / size.
  const double x = u * width - 0.5, y = v * height - 0.5;
  const double x0 = std::floor(x), y0 = std::floor(y);
  f.fx = float(x - x0), f.fy = float(y - y0);
  const auto [xa, xb] = wrap_pair(int64_t(x0), width, wrap_s);
  const auto [ya, yb] = wrap_pair(int64_t(y0), height, wrap_t);
  f.texel[0] = size_t(ya) * w + size_t(xa), f.texel[1] = size_t(ya) * w + size_t(xb);
  f.texel[2] = size_t(yb) * w + size_t(xa), f.texel[3] = size_t(yb) * w + size_t(xb);
  for (size_t t : f.texel) __builtin_prefetch(words->data() + stride * t);
  return f;
}

glm::vec4 Texture::fetch(const Footprint& f) const {
  if (!f.valid) return glm::vec4(0.0f);
  if (f.nearest) return decode(f.texel[0]);
  const glm::vec4 t00 = decode(f.texel[0]), t10 = decode(f.texel[1]), t01 = decode(f.texel[2]), t11 = decode(f.texel[3]);
  const glm::vec4 top = t00 * (1.0f - f.fx) + t10 * f.fx;
  const glm::vec4 bottom = t01 * (1.0f - f.fx) + t11 * f.fx;
  return top * (1.0f - f.fy) + bottom * f.fy;
}

glm::vec4 Texture::decode(size_t i) const {
  const auto& w = *words;
  if (format == TexelFormat::Rgba32F)
    return {std::bit_cast<float>(w[4 * i]), std::bit_cast<float>(w[4 * i + 1]), std::bit_cast<float>(w[4 * i + 2]),
            std::bit_cast<float>(w[4 * i + 3])};
  const auto& t = decode_table();
  const uint32_t p = w[i], colour = format == TexelFormat::Rgba8Srgb ? 256u : 0u;
  return {t[colour + (p & 255u)], t[colour + (p >> 8 & 255u)], t[colour + (p >> 16 & 255u)], t[p >> 24]};
}

}  // namespace giq::scenes
