#include "png_texels.h"

#include <png.h>
#include <sys/mman.h>

#include <bit>
#include <csetjmp>
#include <cstdio>
#include <cstring>

namespace giq::scenes {
namespace {

struct Source {
  const uint8_t* data;
  size_t size, offset;
  char error[256];
  std::jmp_buf jump;
};

void on_read(png_structp png, png_bytep out, png_size_t n) {
  Source* s = static_cast<Source*>(png_get_io_ptr(png));
  if (n > s->size - s->offset) png_error(png, "file ends early");
  std::memcpy(out, s->data + s->offset, n);
  s->offset += n;
}

void on_error(png_structp png, png_const_charp message) {
  Source* s = static_cast<Source*>(png_get_error_ptr(png));
  std::snprintf(s->error, sizeof s->error, "%s", message);
  std::longjmp(s->jump, 1);
}

void on_warning(png_structp, png_const_charp) {}

// Sizes v to n elements, asking for transparent huge pages first: a 2048² texture is 4096 base
// pages whose first-touch faults took more time than inflating the PNG (on a VM where a fault
// costs microseconds); with 2 MiB pages the same texels cost eight.
template <class T>
void resize_on_huge_pages(std::vector<T>& v, size_t n) {
  v.reserve(n);
  constexpr uintptr_t kHuge = uintptr_t(2) << 20;
  const uintptr_t begin = (reinterpret_cast<uintptr_t>(v.data()) + kHuge - 1) & ~(kHuge - 1);
  const uintptr_t end = (reinterpret_cast<uintptr_t>(v.data()) + n * sizeof(T)) & ~(kHuge - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);  // a hint: failure is harmless
  v.resize(n);
}

// libpng reports errors by longjmp: this function owns no object with a destructor (the rows
// are the caller's). `rows` has `height` entries into a buffer of width x 4 channels of
// `sixteen` ? 2 : 1 bytes each.
bool decode(Source& s, int width, int height, bool sixteen, png_bytep* rows) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &s, on_error, on_warning);
  if (!png) return std::snprintf(s.error, sizeof s.error, "out of memory"), false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(s.jump)) {
    png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
    return false;
  }
  png_set_read_fn(png, &s, on_read);
  // As lenient as stb_image, which checks no CRC and no Adler-32 (and so computes neither).
  png_set_crc_action(png, PNG_CRC_QUIET_USE, PNG_CRC_QUIET_USE);
#ifdef PNG_IGNORE_ADLER32
  png_set_option(png, PNG_IGNORE_ADLER32, PNG_OPTION_ON);
#endif
  png_set_benign_errors(png, 1);
  png_read_info(png, info);
  const png_uint_32 w = png_get_image_width(png, info), h = png_get_image_height(png, info);
  const int depth = png_get_bit_depth(png, info), colour = png_get_color_type(png, info);
  if (int64_t(w) != width || int64_t(h) != height || (depth == 16) != sixteen) {
    std::snprintf(s.error, sizeof s.error, "header disagrees with the first reading");
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  // Everything to RGBA of the file's depth, samples as stored (no gamma).
  if (colour == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (colour == PNG_COLOR_TYPE_GRAY && depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
  if (colour == PNG_COLOR_TYPE_GRAY || colour == PNG_COLOR_TYPE_GRAY_ALPHA) png_set_gray_to_rgb(png);
  if (!(colour & PNG_COLOR_MASK_ALPHA) && !png_get_valid(png, info, PNG_INFO_tRNS))
    png_set_add_alpha(png, sixteen ? 0xffff : 0xff, PNG_FILLER_AFTER);
  if (sixteen) png_set_swap(png);  // PNG is big-endian; texels are host (little-endian) words
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  if (png_get_rowbytes(png, info) != size_t(width) * 4 * (sixteen ? 2 : 1)) {
    std::snprintf(s.error, sizeof s.error, "unexpected row size after expansion");
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_read_image(png, rows);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

}  // namespace

bool is_png(const std::vector<uint8_t>& bytes) {
  static const uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  return bytes.size() >= 8 && std::memcmp(bytes.data(), kSignature, 8) == 0;
}

std::string decode_png(const std::vector<uint8_t>& bytes, int width, int height, std::vector<uint32_t>* words8,
                       std::vector<uint16_t>* words16) {
  static_assert(std::endian::native == std::endian::little, "texel words are little-endian RGBA");
  const bool sixteen = words16 != nullptr;
  const size_t texels = size_t(width) * size_t(height);
  uint8_t* base;
  size_t row_bytes;
  if (sixteen) {
    resize_on_huge_pages(*words16, 4 * texels);
    base = reinterpret_cast<uint8_t*>(words16->data()), row_bytes = size_t(width) * 8;
  } else {
    resize_on_huge_pages(*words8, texels);
    base = reinterpret_cast<uint8_t*>(words8->data()), row_bytes = size_t(width) * 4;
  }
  std::vector<png_bytep> rows(size_t(height), nullptr);
  for (size_t y = 0; y < rows.size(); ++y) rows[y] = base + y * row_bytes;
  Source s{bytes.data(), bytes.size(), 0, "", {}};
  if (!decode(s, width, height, sixteen, rows.data())) return s.error[0] ? s.error : "libpng failed";
  return "";
}

}  // namespace giq::scenes
