#pragma once
// Image files. OpenEXR is read and written with the OpenEXR library directly, so the
// real-time runner needs no OpenImageIO at run time; other formats (PNG, JPEG, HDR, TIFF...)
// are read through OpenImageIO when the build has it (GIQ_WITH_OIIO). Every write is atomic:
// an interrupted run never leaves a half-written file under the final name.

#include <cstdint>
#include <filesystem>
#include <set>
#include <string>

#include "giq/image/image.h"

namespace giq::image {

// Before a reader allocates a pixel it checks what the file declares, so no small file can make
// giq allocate gigabytes (or read for a minute) before failing:
//   - the decoded image, every channel as float, takes at most kMaxImageBytes (4 GiB: 16384^2
//     pixels of 4 channels);
//   - the file can hold the pixel data it declares: the data as stored, divided by the largest
//     ratio its codec can reach (deflate's 1032:1 for ZIP and PNG, 1 for uncompressed...),
//     fits in the file's size;
//   - EXR: one chunk (a codec's block of scan lines, or a tile) holds at most 64 MiB, and no
//     tile is larger than the image (or 64 pixels): OpenEXR reserves chunk buffers per thread.
inline constexpr uint64_t kMaxImageBytes = uint64_t(4) << 30;

struct ExrOptions {
  // Channels stored as float16 instead of float32 (values beyond 65504 become inf: only for
  // channels known to be in range). Empty = everything float32.
  std::set<std::string> half_channels;
  enum class Compression { None, Zip, Piz } compression = Compression::Zip;
};

// Reads any image. EXR: every channel, header string attributes into metadata. 8/16-bit
// formats: decoded to linear float (sRGB transfer removed) as channels R,G,B[,A].
// Throws InputError (file, what was wrong) for a missing, unreadable or corrupt file.
Image read_image(const std::filesystem::path& path);

// True when the file starts with the OpenEXR magic number (linear HDR data), false for any
// other or an unreadable file.
bool is_exr_file(const std::filesystem::path& path);

void write_exr(const Image& image, const std::filesystem::path& path, const ExrOptions& options = {});

struct PngOptions {
  std::string layer;       // which RGB layer to show ("" = beauty)
  float exposure = 0.0f;   // stops: multiplies by 2^exposure before tone mapping
  bool srgb = true;        // apply the sRGB transfer function (else clamp linear values)
};
// Tone-maps an RGB layer to 8-bit sRGB PNG. Non-finite values are written as magenta so
// they cannot hide. Metadata is stored as PNG text chunks.
void write_png(const Image& image, const std::filesystem::path& path, const PngOptions& options = {});

// Writes an 8-bit RGB(A) buffer (row-major, top row first) as PNG with text chunks.
void write_png_rgb8(const std::filesystem::path& path, int width, int height, int channels,
                    const unsigned char* pixels, const std::map<std::string, std::string>& text = {});

}  // namespace giq::image
