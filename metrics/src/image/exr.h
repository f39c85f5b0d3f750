#pragma once
// Internal: the OpenEXR reader behind read_image().

#include <filesystem>

#include "giq/image/image.h"

namespace giq::image {

Image read_exr(const std::filesystem::path& path);

}  // namespace giq::image
