#pragma once
// PNG images decoded with libpng straight into a texture's texel layout. stb_image (which
// decodes JPEG and anything else) builds each PNG in a growing zlib buffer, then an unfiltered
// copy, then our copy: three full-size buffers, reallocations and their page faults, which
// made PNG decoding the largest part of loading a textured scene. The texels are those stb_image
// gives (the PNG's samples, no gamma applied; grey, palettes and tRNS expanded to RGBA, missing
// alpha opaque), tested against it for every colour type and bit depth.

#include <cstdint>
#include <string>
#include <vector>

namespace giq::scenes {

// Whether the bytes start with PNG's signature.
bool is_png(const std::vector<uint8_t>& bytes);

// Decodes a PNG of `width` x `height` (already known from its header): 8-bit images into
// `words8` (one word a texel, R in the low byte), 16-bit ones into `words16` (four channels a
// texel). Returns "" or why it could not be decoded (the caller may then try stb_image, which
// accepts some damaged files libpng refuses).
std::string decode_png(const std::vector<uint8_t>& bytes, int width, int height, std::vector<uint32_t>* words8,
                       std::vector<uint16_t>* words16);

}  // namespace giq::scenes
