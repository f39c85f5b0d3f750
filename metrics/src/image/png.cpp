// PNG output: stb_image_write encodes the pixels (Debian's libstb provides the implementation),
// then text chunks are spliced in after IHDR. stb cannot write text chunks itself; the chunk
// layout and CRC follow the PNG specification (ISO/IEC 15948, sections 5.3, 11.3.4 and
// Annex D).

#include <stb_image_write.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

#include "giq/base/atomic_file.h"
#include "giq/base/error.h"
#include "giq/image/io.h"
#include "giq/image/srgb.h"

namespace giq::image {
namespace fs = std::filesystem;
namespace {

// CRC-32 as PNG defines it (polynomial 0xEDB88320, reflected; PNG spec Annex D).
uint32_t crc32(const unsigned char* data, size_t n, uint32_t crc = 0xffffffffu) {
  static const std::array<uint32_t, 256> table = [] {
    std::array<uint32_t, 256> t{};
    for (uint32_t i = 0; i < 256; ++i) {
      uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xedb88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  for (size_t i = 0; i < n; ++i) crc = table[(crc ^ data[i]) & 0xffu] ^ (crc >> 8);
  return crc;
}

void put_u32(std::string& s, uint32_t v) {
  s += char((v >> 24) & 0xff), s += char((v >> 16) & 0xff), s += char((v >> 8) & 0xff), s += char(v & 0xff);
}

std::string chunk(const char type[4], const std::string& data) {
  std::string c;
  put_u32(c, uint32_t(data.size()));
  std::string body(type, 4);
  body += data;
  c += body;
  put_u32(c, crc32(reinterpret_cast<const unsigned char*>(body.data()), body.size()) ^ 0xffffffffu);
  return c;
}

// tEXt holds Latin-1 text; anything else (UTF-8 beyond ASCII) goes into an uncompressed iTXt.
std::string text_chunk(const fs::path& path, const std::string& key, const std::string& value) {
  // Keywords: 1-79 printable Latin-1 characters, no leading/trailing/double spaces (11.3.4.2).
  bool ok = !key.empty() && key.size() <= 79 && key.front() != ' ' && key.back() != ' ' &&
            key.find("  ") == std::string::npos;
  for (unsigned char c : key) ok = ok && c >= 32 && c <= 126;
  if (!ok)
    throw InputError(path.string(), "text." + key, "PNG text keyword must be 1-79 printable ASCII characters");
  if (value.find('\0') != std::string::npos)
    throw InputError(path.string(), "text." + key, "PNG text value contains a NUL byte");
  bool ascii = true;
  for (unsigned char c : value) ascii = ascii && c < 128;
  if (ascii) return chunk("tEXt", key + '\0' + value);
  // iTXt: keyword, NUL, compression flag 0, method 0, empty language tag, NUL, empty
  // translated keyword, NUL, UTF-8 text.
  return chunk("iTXt", key + '\0' + '\0' + '\0' + '\0' + '\0' + value);
}

void append_bytes(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
}

}  // namespace

void write_png_rgb8(const fs::path& path, int width, int height, int channels, const unsigned char* pixels,
                    const std::map<std::string, std::string>& text) {
  if (width <= 0 || height <= 0 || channels < 1 || channels > 4)
    throw InputError(path.string(), "", "cannot write a PNG of " + std::to_string(width) + "x" +
                                            std::to_string(height) + "x" + std::to_string(channels));
  std::string png;
  if (!stbi_write_png_to_func(append_bytes, &png, width, height, channels, pixels, width * channels))
    throw InputError(path.string(), "", "PNG encoding failed");
  // Signature (8 bytes) then IHDR (4 length + 4 type + 13 data + 4 CRC = 25 bytes); text
  // chunks may go anywhere between IHDR and IEND, so right after IHDR.
  const size_t after_ihdr = 8 + 25;
  if (png.size() < after_ihdr || png.compare(12, 4, "IHDR") != 0)
    throw InputError(path.string(), "", "PNG encoder produced an unexpected layout");
  std::string chunks;
  for (const auto& [key, value] : text) chunks += text_chunk(path, key, value);
  png.insert(after_ihdr, chunks);
  write_file_atomically(path, png);
}

void write_png(const Image& image, const fs::path& path, const PngOptions& options) {
  if (!image.has_layer(options.layer))
    throw InputError(path.string(), options.layer.empty() ? "R,G,B" : options.layer,
                     "image has no such RGB layer to write as PNG");
  const auto names = image.layer_channels(options.layer);
  const float* c[3] = {image.channel(names[0]), image.channel(names[1]), image.channel(names[2])};
  const float scale = std::exp2(options.exposure);
  const size_t n = image.pixel_count();
  std::vector<unsigned char> rgb(n * 3);
  for (size_t i = 0; i < n; ++i) {
    const bool finite = std::isfinite(c[0][i]) && std::isfinite(c[1][i]) && std::isfinite(c[2][i]);
    for (int k = 0; k < 3; ++k) {
      unsigned char v;
      if (!finite) {
        // Magenta marks NaN/Inf so a broken pixel can never pass for a plausible colour.
        v = k == 1 ? 0 : 255;
      } else {
        float x = c[k][i] * scale;
        x = options.srgb ? srgb_encode(x) : std::fmin(std::fmax(x, 0.0f), 1.0f);
        v = static_cast<unsigned char>(std::lround(x * 255.0f));
      }
      rgb[i * 3 + size_t(k)] = v;
    }
  }
  write_png_rgb8(path, image.width(), image.height(), 3, rgb.data(), image.metadata);
}

}  // namespace giq::image
