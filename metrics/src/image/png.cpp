// PNG output through libpng (zlib), with metadata as text chunks: tEXt for ASCII values, iTXt
// (uncompressed UTF-8) otherwise (PNG specification, ISO/IEC 15948, section 11.3.4). libpng
// rather than stb_image_write: stb's own deflate made heat-map writing the slowest step of
// `giq score` (about a third of its CPU time on a 1080p pair).

#include <png.h>

#include <cmath>
#include <csetjmp>
#include <cstring>
#include <string>
#include <vector>

#include "giq/base/atomic_file.h"
#include "giq/base/error.h"
#include "giq/image/io.h"
#include "giq/image/srgb.h"

namespace giq::image {
namespace fs = std::filesystem;
namespace {

void check_text(const fs::path& path, const std::string& key, const std::string& value) {
  // Keywords: 1-79 printable Latin-1 characters, no leading/trailing/double spaces (11.3.4.2).
  bool ok = !key.empty() && key.size() <= 79 && key.front() != ' ' && key.back() != ' ' &&
            key.find("  ") == std::string::npos;
  for (unsigned char c : key) ok = ok && c >= 32 && c <= 126;
  if (!ok)
    throw InputError(path.string(), "text." + key, "PNG text keyword must be 1-79 printable ASCII characters");
  if (value.find('\0') != std::string::npos)
    throw InputError(path.string(), "text." + key, "PNG text value contains a NUL byte");
}

struct Sink {
  std::string bytes;
  char error[256] = "";
  std::jmp_buf jump;
};

void on_write(png_structp png, png_bytep data, png_size_t size) {
  static_cast<Sink*>(png_get_io_ptr(png))->bytes.append(reinterpret_cast<const char*>(data), size);
}

void on_error(png_structp png, png_const_charp message) {
  Sink* sink = static_cast<Sink*>(png_get_error_ptr(png));
  std::snprintf(sink->error, sizeof sink->error, "%s", message);
  std::longjmp(sink->jump, 1);
}

void on_warning(png_structp, png_const_charp) {}

// libpng reports errors by longjmp: this function owns no object with a destructor between
// setjmp and the libpng calls (everything it touches is prepared by the caller).
bool encode(Sink& sink, int width, int height, int channels, png_bytep* rows, png_textp text, int text_count) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, on_error, on_warning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(sink.jump)) {
    png_destroy_write_struct(&png, info ? &info : nullptr);
    return false;
  }
  static const int kColour[5] = {0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                 PNG_COLOR_TYPE_RGB_ALPHA};
  png_set_write_fn(png, &sink, on_write, nullptr);
  // zlib level 3: heat maps and the strip are written on every score; with level 6 the maps
  // of a 1080p pair took about 2 s more CPU time.
  png_set_compression_level(png, 3);
  png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 8, kColour[channels], PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (text_count) png_set_text(png, info, text, text_count);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

void write_png_rgb8(const fs::path& path, int width, int height, int channels, const unsigned char* pixels,
                    const std::map<std::string, std::string>& text) {
  if (width <= 0 || height <= 0 || channels < 1 || channels > 4)
    throw InputError(path.string(), "", "cannot write a PNG of " + std::to_string(width) + "x" +
                                            std::to_string(height) + "x" + std::to_string(channels));
  std::vector<png_text> chunks;
  for (const auto& [key, value] : text) {
    check_text(path, key, value);
    bool ascii = true;
    for (unsigned char c : value) ascii = ascii && c < 128;
    png_text t{};
    t.compression = ascii ? PNG_TEXT_COMPRESSION_NONE : PNG_ITXT_COMPRESSION_NONE;
    t.key = const_cast<char*>(key.c_str());
    t.text = const_cast<char*>(value.c_str());
    if (ascii) t.text_length = value.size();
    else t.itxt_length = value.size();
    chunks.push_back(t);
  }
  std::vector<png_bytep> rows(static_cast<size_t>(height));
  for (int y = 0; y < height; ++y)
    rows[size_t(y)] = const_cast<png_bytep>(pixels + size_t(y) * size_t(width) * size_t(channels));
  Sink sink;
  if (!encode(sink, width, height, channels, rows.data(), chunks.data(), int(chunks.size())))
    throw InputError(path.string(), "", std::string("PNG encoding failed: ") + sink.error);
  write_file_atomically(path, sink.bytes);
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
